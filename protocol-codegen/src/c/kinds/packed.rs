//! A bit-packed array ([`FieldKind::Packed`](crate::ir::FieldKind::Packed)): `count`
//! elements of `bits` bits back to back (the prelude's `get_packed`/`set_packed`), an array
//! of the raw integer type or of the physical float with a scale.

use crate::ir::{BitOrder, Field, Prim, Scale, Struct};

use super::{Kind, member_head};
use crate::c::fields::{Dir, indent};
use crate::c::format::{Label, each, scalar};
use crate::c::names::{self, Names, float_of, prim as c_prim};
use crate::c::template::fill;

/// `count` elements of `bits` bits.
pub(super) struct Packed {
    pub(super) count: usize,
    pub(super) bits: u32,
    pub(super) order: BitOrder,
    pub(super) prim: Prim,
    pub(super) scale: Option<Scale>,
}

impl Kind for Packed {
    fn members(&self, _n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let ty = match self.scale {
            Some(sc) => float_of(sc.physical).0,
            None => names::prim(self.prim),
        };
        let count = self.count;
        out.push_str(&fill!(
            "    ${ty} ${name}[${count}];${doc}\n",
            ty,
            name,
            count,
            doc
        ));
    }

    fn code(&self, n: &Names, _s: &Struct, f: &Field, dir: Dir, here: &str) -> String {
        packed(n, f, self, dir, here)
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (key, name) = (&f.name, names::field(&f.name));
        let prim = self.scale.map_or(self.prim, |sc| sc.physical);
        let (item, at_i) = (Label::item(key), format!("v->{name}[i]"));
        each(
            &format!("{}u", self.count),
            scalar(&n.lo, prim, &item, &at_i),
        )
    }
}

/// A bit-packed array of `count` elements of `bits` bits (scaled, or integers of `prim`).
fn packed(n: &Names, f: &Field, k: &Packed, dir: Dir, here: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (count, bits, order, prim, scale) = (&k.count, &k.bits, &k.order, &k.prim, &k.scale);
    let msb = u8::from(*order == BitOrder::MsbFirst);
    let size = f.size;
    let each = format!("{here}[i]");
    if dir == Dir::Read {
        let get = fill!(
            "${lo}get_packed(r->p + r->pos, ${size}u, i, ${bits}u, ${msb})",
            lo,
            size,
            bits,
            msb
        );
        let elem = match scale {
            Some(sc) => indent(&crate::c::scale::read(n, Prim::U64, sc, &get, &each), 1),
            None => {
                let ty = c_prim(*prim);
                fill!("        ${each} = (${ty})${get};\n", each, ty, get)
            }
        };
        return fill!(
            r"
    if (r->len - r->pos < ${size}u) return ${up}ERR_PAYLOAD_LENGTH;
    for (i = 0; i < ${count}u; i++) {
${elem}    }
    r->pos += ${size}u;
",
            size,
            up,
            count,
            elem
        );
    }
    let raw = match scale {
        Some(sc) => indent(&crate::c::scale::write(n, *prim, sc, &each), 1),
        None => fill!("        raw = (uint64_t)${each};\n", each),
    };
    fill!(
        r"
    if (w->cap - w->pos < ${size}u) return ${up}ERR_SHORT_BUFFER;
    memset(w->p + w->pos, 0, ${size}u);
    for (i = 0; i < ${count}u; i++) {
${raw}        if (!${lo}set_packed(w->p + w->pos, ${size}u, i, ${bits}u, ${msb}, raw)) return ${up}ERR_OUT_OF_RANGE;
    }
    w->pos += ${size}u;
",
        size,
        up,
        count,
        raw,
        lo,
        bits,
        msb
    )
}
