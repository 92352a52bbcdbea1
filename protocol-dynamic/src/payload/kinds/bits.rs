//! A bitfield ([`FieldKind::Bits`](protocol_spec::ir::FieldKind::Bits)): a word whose bit
//! members are keys of the struct's object, each got and set by `field::get_bits` and
//! `field::set_bits`.

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{BitMember, Field, Protocol, Scalar};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{Path, ReadFail, read_member};
use crate::payload::write::member_raw;
use crate::value::{read_scalar, truncate, write_bits};

/// The word and its members.
pub(super) struct Bits<'a> {
    pub(super) word: Scalar,
    pub(super) members: &'a [BitMember],
}

impl<'a> Kind<'a> for Bits<'a> {
    fn read(
        &self,
        p: &Protocol,
        _f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let raw = read_scalar(r, self.word)?.as_u64();
        for (m, key) in self.members.iter().zip(&fnames.keys) {
            let v = read_member(p, m, raw, &Path::Field(at.path, &m.name))?;
            out.push(key, v);
        }
        Ok(())
    }

    fn write(
        &self,
        p: &Protocol,
        _f: &Field,
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let mut bits = 0u64;
        for m in self.members {
            let mpath = join(at.path, &m.name);
            let v = at
                .obj
                .get(&m.name)
                .ok_or_else(|| EncodeIssue::missing(&mpath))?;
            let raw = member_raw(p, m, v, &mpath)?;
            bits = field::set_bits(bits, raw, m.shift, m.width).map_err(|_| {
                EncodeIssue::new(&mpath, format!("{raw} does not fit {} bits", m.width))
            })?;
        }
        write_bits(w, self.word, truncate(self.word.prim, bits)).map_err(EncodeIssue::runtime)
    }

    fn keys(&self, _f: &'a Field) -> Vec<&'a str> {
        self.members.iter().map(|m| m.name.as_str()).collect()
    }
}
