//! A bit field ([`FieldKind::Bits`](crate::ir::FieldKind::Bits)): a member of the C struct
//! per bit member, read from and written as their word (`values`' `read_bits`, `write_bits`).

use crate::ir::{BitMember, Field, Protocol, Scalar, Struct};

use super::Kind;
use crate::c::fields::Dir;
use crate::c::names::{self, Names, doc_comment};
use crate::c::template::fill;
use crate::c::values::{read_bits, write_bits};

/// The word and its members.
pub(super) struct Bits<'a> {
    pub(super) p: &'a Protocol,
    pub(super) word: Scalar,
    pub(super) members: &'a [BitMember],
}

impl Kind for Bits<'_> {
    fn members(&self, n: &Names, _f: &Field, out: &mut String) {
        for m in self.members {
            let ty = names::member_type(self.p, n, m);
            let (name, doc) = (names::field(&m.name), doc_comment(&m.doc, ""));
            out.push_str(&fill!("    ${ty} ${name};${doc}\n", ty, name, doc));
        }
    }

    fn code(&self, n: &Names, _s: &Struct, _f: &Field, dir: Dir, _here: &str) -> String {
        match dir {
            Dir::Read => read_bits(self.p, n, self.word, self.members),
            Dir::Write => write_bits(self.p, n, self.word, self.members),
        }
    }

    fn text(&self, n: &Names, _f: &Field) -> String {
        crate::c::members::text(self.p, n, self.members)
    }

    fn keys(&self, _f: &Field) -> Vec<String> {
        self.members.iter().map(|m| m.name.clone()).collect()
    }
}
