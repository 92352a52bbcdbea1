//! An array of values ([`FieldKind::Array`](crate::ir::FieldKind::Array)): elements and their
//! count used, read to the payload's end or as many as a field states (which must fit).

use crate::ir::{Field, Protocol, Struct, ValueType};

use super::{Kind, member_head, used};
use crate::c::fields::{Dir, count_fits, indent, stated};
use crate::c::format::{self, Label, each};
use crate::c::names::{self, Names, value_type};
use crate::c::template::fill;
use crate::c::values::{read_elem, write_elem};

/// Up to `max` elements of `ty`, counted by the field `size_from` or by the payload's end.
pub(super) struct Array<'a> {
    pub(super) p: &'a Protocol,
    pub(super) ty: &'a ValueType,
    pub(super) max: usize,
    pub(super) size_from: &'a Option<String>,
    /// `size_from` is a mask: one element per set bit.
    pub(super) by_mask: bool,
}

impl Kind for Array<'_> {
    fn members(&self, n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let (ty, len) = (value_type(self.p, n, self.ty), self.max.max(1));
        out.push_str(&fill!(
            "    ${ty} ${name}[${len}];${doc}\n",
            ty,
            name,
            len,
            doc
        ));
        out.push_str(&used(&name, "Elements", self.max));
    }

    fn code(&self, n: &Names, s: &Struct, _f: &Field, dir: Dir, here: &str) -> String {
        let this = if dir == Dir::Read { "out" } else { "v" };
        let mut stated = self.size_from.as_ref().map(|size| stated(s, this, size));
        // A mask states the number of its set bits, counted into `raw`.
        let mut count = String::new();
        if let (true, Some(mask)) = (self.by_mask, &stated) {
            count = fill!(
                r"
    raw = 0;
    for (word = ${mask}; word != 0; word &= word - 1) raw++;
",
                mask
            );
            stated = Some("raw".to_string());
        }
        let code = match dir {
            Dir::Read => read_array(self.p, n, self.ty, self.max, stated.as_deref(), here),
            Dir::Write => write_array(self.p, n, self.ty, self.max, stated.as_deref(), here),
        };
        count + &code
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (key, name) = (&f.name, names::field(&f.name));
        let (item, at_i) = (Label::item(key), format!("v->{name}[i]"));
        each(
            &format!("v->{name}_len"),
            format::value(self.p, n, self.ty, &item, &at_i),
        )
    }
}

/// An array read: elements to the payload's end, or the count a field states (the
/// runtime's `field::array_len`: the stated count must fit `max`).
fn read_array(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    max: usize,
    stated: Option<&str>,
    here: &str,
) -> String {
    let up = &n.up;
    let Some(stated) = stated else {
        // An element past the capacity is read (its own errors first, as the runtime reads
        // it), then refused: the payload is longer than the struct's largest.
        let spare = indent(&read_elem(p, n, ty, "spare"), 2);
        let elem = indent(&read_elem(p, n, ty, &format!("{here}[{here}_len]")), 1);
        let ty = value_type(p, n, ty);
        return fill!(
            r"
    ${here}_len = 0;
    while (r->pos < r->len) {
        if (${here}_len == ${max}u) {
            ${ty} spare;
${spare}            (void)spare;
            return ${up}ERR_PAYLOAD_LENGTH;
        }
${elem}        ${here}_len++;
    }
",
            here,
            max,
            ty,
            spare,
            up,
            elem
        );
    };
    let elem = indent(&read_elem(p, n, ty, &format!("{here}[i]")), 1);
    fill!(
        r"
    stated = ${stated};
    if (stated > ${max}u) return ${up}ERR_SIZE_MISMATCH;
    ${here}_len = (size_t)stated;
    for (i = 0; i < ${here}_len; i++) {
${elem}    }
",
        stated,
        max,
        up,
        here,
        elem
    )
}

/// An array written.
fn write_array(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    max: usize,
    stated: Option<&str>,
    here: &str,
) -> String {
    let elem = indent(&write_elem(p, n, ty, &format!("{here}[i]")), 1);
    count_fits(n, max, stated, here)
        + &fill!(
            r"
    for (i = 0; i < ${here}_len; i++) {
${elem}    }
",
            here,
            elem
        )
}
