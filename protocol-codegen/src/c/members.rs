//! Bit members in C, of a word or a bit stream: the statements that set a member of the C
//! struct from its unsigned bits, and that set `raw` to a member's bits, with the runtime's
//! member rules: an enum value without variant is an error when the enum rejects unknown
//! values; a signed member is two's complement of its width (`sext` when read); a scaled
//! member goes through the scale helpers (`scale.rs`); a value that does not fit the member's
//! bits is `ERR_OUT_OF_RANGE`, never cut.

use crate::ir::{BitMember, Prim, Protocol, UnknownPolicy};

use super::format::{Label, enum_value, scalar};
use super::names::{self, Names, mask, prim as c_prim, u64_lit};
use super::template::fill;

/// The statements setting `out-><member>` from `bits`, a C expression of the member's
/// unsigned bits (evaluated more than once: a plain expression of locals).
pub fn read_member(p: &Protocol, n: &Names, m: &BitMember, bits: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let name = names::field(&m.name);
    let dst = format!("out->{name}");
    let width = m.width;
    if let Some(ei) = m.enum_index {
        let e = &p.enums[ei];
        let ety = n.ty(&e.name);
        let mut out = String::new();
        if e.unknown == UnknownPolicy::Reject {
            out.push_str(&fill!(
                "    if (!${ety}_known(${bits})) return ${up}ERR_INVALID_ENUM;\n",
                ety,
                bits,
                up
            ));
        }
        // A signed enum's value is its bits as a two's complement integer of its type.
        let value = if e.prim.is_signed() {
            format!(
                "({ety})({}){lo}sext({bits}, {}u)",
                c_prim(e.prim),
                8 * e.prim.size()
            )
        } else {
            format!("({ety}){bits}")
        };
        out.push_str(&fill!("    ${dst} = ${value};\n", dst, value));
        return out;
    }
    let raw = if m.is_signed() {
        format!("(uint64_t){lo}sext({bits}, {width}u)")
    } else {
        bits.to_string()
    };
    match (&m.scale, m.prim) {
        // Sign-extended to 64 bits already: read as an `int64_t`.
        (Some(sc), prim) => {
            let prim = if prim.is_signed() {
                Prim::I64
            } else {
                Prim::U64
            };
            super::scale::read(n, prim, sc, &raw, &dst)
        }
        (None, Prim::Bool) => fill!("    ${dst} = (${bits} != 0);\n", dst, bits),
        (None, prim) if prim.is_signed() => {
            let ty = c_prim(prim);
            fill!(
                "    ${dst} = (${ty})${lo}sext(${bits}, ${width}u);\n",
                dst,
                ty,
                lo,
                bits,
                width
            )
        }
        (None, prim) => {
            let ty = c_prim(prim);
            fill!("    ${dst} = (${ty})${bits};\n", dst, ty, bits)
        }
    }
}

/// The statements setting `raw` to the unsigned bits of member `v-><member>`, checked to fit
/// the member's width.
pub fn write_member(p: &Protocol, n: &Names, m: &BitMember) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let v = format!("v->{}", names::field(&m.name));
    let (width, top) = (m.width, u64_lit(mask(m.width)));
    let mut out = match (&m.scale, m.enum_index) {
        (_, Some(_)) => fill!("    raw = (uint64_t)${v};\n", v),
        (Some(sc), None) => {
            let prim = if m.is_signed() { Prim::I64 } else { Prim::U64 };
            super::scale::write(n, prim, sc, &v)
        }
        (None, None) if m.prim == Prim::Bool => fill!("    raw = (${v} ? 1u : 0u);\n", v),
        (None, None) if m.is_signed() => fill!("    raw = (uint64_t)(int64_t)${v};\n", v),
        (None, None) => fill!("    raw = (uint64_t)${v};\n", v),
    };
    if let Some(ei) = m
        .enum_index
        .filter(|&ei| p.enums[ei].unknown == UnknownPolicy::Reject)
    {
        let ety = n.ty(&p.enums[ei].name);
        out.push_str(&fill!(
            "    if (!${ety}_known(raw)) return ${up}ERR_OUT_OF_RANGE;\n",
            ety,
            up
        ));
    }
    if m.is_signed() {
        // Two's complement of `width` bits: the value sign-extends back to itself.
        out.push_str(&fill!(
            r"
    if ((uint64_t)${lo}sext(raw, ${width}u) != raw) return ${up}ERR_OUT_OF_RANGE;
    raw &= ${top};
",
            lo,
            width,
            up,
            top
        ));
    } else {
        out.push_str(&fill!(
            "    if (raw > ${top}) return ${up}ERR_OUT_OF_RANGE;\n",
            top,
            up
        ));
    }
    out
}

/// The text form's statements of the members (`v` the struct).
pub fn text(p: &Protocol, n: &Names, members: &[BitMember]) -> String {
    let lo = &n.lo;
    let mut out = String::new();
    for m in members {
        let v = format!("v->{}", names::field(&m.name));
        let label = Label::of(&m.name);
        out.push_str(&match (m.enum_index, &m.scale) {
            (Some(ei), _) => enum_value(n, &p.enums[ei].name, p.enums[ei].prim, &label, &v),
            (None, Some(sc)) => scalar(lo, sc.physical, &label, &v),
            (None, None) => scalar(lo, m.prim, &label, &v),
        });
    }
    out
}

/// A member's C type: its enum, the float of a scaled member, or its integer.
pub fn member_type(p: &Protocol, n: &Names, m: &BitMember) -> String {
    match (m.enum_index, &m.scale) {
        (Some(ei), _) => n.ty(&p.enums[ei].name),
        (None, Some(sc)) => names::float_of(sc.physical).0.to_string(),
        (None, None) => c_prim(m.prim).to_string(),
    }
}
