//! A bit stream ([`FieldKind::BitStream`](crate::ir::FieldKind::BitStream)): a member of the C
//! struct per bit member, each got from and set into its bits of the stream's bytes (the
//! prelude's `get_stream`/`set_stream`) by the member rules of `members`.

use crate::ir::{BitMember, Field, Protocol, Struct};

use super::Kind;
use crate::c::fields::Dir;
use crate::c::members::{self, read_member, write_member};
use crate::c::names::{self, Names, doc_comment};
use crate::c::template::fill;

/// The stream's members.
pub(super) struct Stream<'a> {
    pub(super) p: &'a Protocol,
    pub(super) members: &'a [BitMember],
}

impl Kind for Stream<'_> {
    fn members(&self, n: &Names, _f: &Field, out: &mut String) {
        for m in self.members {
            let ty = members::member_type(self.p, n, m);
            let (name, doc) = (names::field(&m.name), doc_comment(&m.doc, &m.unit));
            out.push_str(&fill!("    ${ty} ${name};${doc}\n", ty, name, doc));
        }
    }

    fn code(&self, n: &Names, _s: &Struct, f: &Field, dir: Dir, _here: &str) -> String {
        let (lo, up, size) = (&n.lo, &n.up, f.size);
        let mut body = String::new();
        if dir == Dir::Read {
            for m in self.members {
                let (at, width) = (m.shift, m.width);
                let bits = fill!(
                    "${lo}get_stream(r->p + r->pos, ${size}u, ${at}u, ${width}u)",
                    lo,
                    size,
                    at,
                    width
                );
                body.push_str(&fill!("    raw = ${bits};\n", bits));
                body.push_str(&read_member(self.p, n, m, "raw"));
            }
            return fill!(
                r"
    if (r->len - r->pos < ${size}u) return ${up}ERR_PAYLOAD_LENGTH;
${body}    r->pos += ${size}u;
",
                size,
                up,
                body
            );
        }
        for m in self.members {
            let (at, width) = (m.shift, m.width);
            body.push_str(&write_member(self.p, n, m));
            body.push_str(&fill!(
                "    if (!${lo}set_stream(w->p + w->pos, ${size}u, ${at}u, ${width}u, raw)) return ${up}ERR_OUT_OF_RANGE;\n",
                lo,
                size,
                at,
                width,
                up
            ));
        }
        fill!(
            r"
    if (w->cap - w->pos < ${size}u) return ${up}ERR_SHORT_BUFFER;
    memset(w->p + w->pos, 0, ${size}u);
${body}    w->pos += ${size}u;
",
            size,
            up,
            body
        )
    }

    fn text(&self, n: &Names, _f: &Field) -> String {
        members::text(self.p, n, self.members)
    }

    fn keys(&self, _f: &Field) -> Vec<String> {
        self.members.iter().map(|m| m.name.clone()).collect()
    }
}
