//! A repeated group ([`FieldKind::Group`](crate::ir::FieldKind::Group)): an array of the
//! element struct and its count used, each element read or written by the element struct's
//! own function (given the repeating struct's fields its sized bytes name).

use crate::ir::{Field, Protocol, Struct, ValueType};

use super::{Kind, member_head, used};
use crate::c::fields::{Dir, context_args};
use crate::c::format::{self, Label, each};
use crate::c::names::{self, Names};
use crate::c::template::fill;

/// Up to `max` elements of the struct `elem`.
pub(super) struct Group<'a> {
    pub(super) p: &'a Protocol,
    pub(super) elem: usize,
    pub(super) max: usize,
}

impl Kind for Group<'_> {
    fn members(&self, n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let (ty, max) = (n.ty(&self.p.structs[self.elem].name), self.max);
        out.push_str(&fill!(
            "    ${ty} ${name}[${max}];${doc}\n",
            ty,
            name,
            max,
            doc
        ));
        out.push_str(&used(&name, "Elements", self.max));
    }

    fn code(&self, n: &Names, s: &Struct, _f: &Field, dir: Dir, here: &str) -> String {
        let this = if dir == Dir::Read { "out" } else { "v" };
        let es = &self.p.structs[self.elem];
        group(n, es, self.max, &context_args(s, es, this), dir, here)
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (key, name) = (&f.name, names::field(&f.name));
        let ty = ValueType::Struct(self.elem);
        let (item, at_i) = (Label::item(key), format!("v->{name}[i]"));
        each(
            &format!("v->{name}_len"),
            format::value(self.p, n, &ty, &item, &at_i),
        )
    }
}

/// A group: structs `es` to the payload's end, at most `max` (read: one past it is read,
/// its own errors first as the runtime reads it, then refused), each given `ctx`.
fn group(n: &Names, es: &Struct, max: usize, ctx: &str, dir: Dir, here: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (ety, esnake) = (n.ty(&es.name), names::snake(&es.name));
    match dir {
        Dir::Read => fill!(
            r"
    ${here}_len = 0;
    while (r->pos < r->len) {
        if (${here}_len == ${max}u) {
            ${ety} spare;
            if ((e = ${lo}read_${esnake}(r, &spare${ctx})) != 0) return e;
            return ${up}ERR_PAYLOAD_LENGTH;
        }
        if ((e = ${lo}read_${esnake}(r, &${here}[${here}_len]${ctx})) != 0) return e;
        ${here}_len++;
    }
",
            here,
            max,
            ety,
            lo,
            esnake,
            ctx,
            up
        ),
        Dir::Write => fill!(
            r"
    if (${here}_len > ${max}u) return ${up}ERR_OUT_OF_RANGE;
    for (i = 0; i < ${here}_len; i++) {
        if ((e = ${lo}write_${esnake}(w, &${here}[i]${ctx})) != 0) return e;
    }
",
            here,
            max,
            up,
            lo,
            esnake,
            ctx
        ),
    }
}
