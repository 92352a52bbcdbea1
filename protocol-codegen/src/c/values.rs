//! One value between the wire and C: the statements that read or write a scalar, an enum, a
//! nested struct or fixed text (one element of an array), and the members of a bit field,
//! with the runtime's value rules: an enum value without variant is an error when the enum
//! rejects unknown values, a bit member or a 24-bit integer that does not fit is an encode
//! error.

use crate::ir::{BitMember, ByteOrder, Enum, Prim, Protocol, Scalar, UnknownPolicy, ValueType};

use super::names::{self, Names, mask, prim as c_prim, u64_lit};
use super::prelude::{put_call, take_call};
use super::template::fill;

/// `1` for a big-endian scalar, `0` for a little-endian one, as the helpers take it.
fn big(s: Scalar) -> u8 {
    u8::from(s.endian == ByteOrder::Big)
}

/// A statement that calls a helper returning an error code, and returns the error.
pub fn try_call(call: &str) -> String {
    fill!("    if ((e = ${call}) != 0) return e;\n", call)
}

/// The C value of raw bits `raw` of type `prim`.
fn from_raw(lo: &str, prim: Prim, raw: &str) -> String {
    match prim {
        Prim::Bool => format!("({raw} != 0)"),
        Prim::BoolInverted => format!("({raw} == 0)"),
        Prim::F16 => format!("{lo}f16({raw})"),
        Prim::F32 => format!("{lo}f32({raw})"),
        Prim::F64 => format!("{lo}f64({raw})"),
        p if p.is_signed() => {
            format!("({}){lo}sext({raw}, {}u)", c_prim(p), 8 * p.size())
        }
        p => format!("({}){raw}", c_prim(p)),
    }
}

/// The raw bits of C value `v` of type `prim` (a signed value sign-extended to 64 bits).
fn to_raw(lo: &str, prim: Prim, v: &str) -> String {
    match prim {
        Prim::Bool => format!("({v} ? 1u : 0u)"),
        Prim::BoolInverted => format!("({v} ? 0u : 1u)"),
        Prim::F16 => format!("{lo}f16_bits({v})"),
        Prim::F32 => format!("{lo}f32_bits({v})"),
        Prim::F64 => format!("{lo}f64_bits({v})"),
        p if p.is_signed() => format!("(uint64_t)(int64_t){v}"),
        _ => format!("(uint64_t){v}"),
    }
}

/// The range check of a value narrower on the wire than in C before it is written: a 24-,
/// 40-, 48- or 56-bit integer, or a float beyond the largest half.
pub fn range_check(lo: &str, prim: Prim, v: &str, up: &str) -> String {
    match prim {
        Prim::U24 => fill!(
            "    if (${v} > 0xFFFFFFu) return ${up}ERR_OUT_OF_RANGE;\n",
            v,
            up
        ),
        Prim::I24 => fill!(
            "    if (${v} < -8388608L || ${v} > 8388607L) return ${up}ERR_OUT_OF_RANGE;\n",
            v,
            up
        ),
        Prim::U40 | Prim::U48 | Prim::U56 => {
            let max = format!("{:#X}ull", u64::MAX >> (64 - prim.bits()));
            fill!(
                "    if (${v} > ${max}) return ${up}ERR_OUT_OF_RANGE;\n",
                v,
                max,
                up
            )
        }
        Prim::I40 | Prim::I48 | Prim::I56 => {
            let half = 1i64 << (prim.bits() - 1);
            let (min, max) = (format!("-{half}ll"), format!("{}ll", half - 1));
            fill!(
                "    if (${v} < ${min} || ${v} > ${max}) return ${up}ERR_OUT_OF_RANGE;\n",
                v,
                min,
                max,
                up
            )
        }
        Prim::F16 => fill!(
            "    if (${lo}f16_bits(${v}) > 0xFFFFu) return ${up}ERR_OUT_OF_RANGE;\n",
            lo,
            v,
            up
        ),
        _ => String::new(),
    }
}

/// Whether an enum refuses values without variant.
fn rejects(e: &Enum) -> bool {
    e.unknown == UnknownPolicy::Reject
}

/// The statements that read one value of type `ty` from the payload reader `r` into `dst`.
pub fn read_elem(p: &Protocol, n: &Names, ty: &ValueType, dst: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => {
            let take = take_call(n, scalar.prim.size(), big(*scalar), "raw");
            try_call(&take) + &super::scale::read(n, scalar.prim, sc, "raw", dst)
        }
        ValueType::Scalar { scalar, .. } => {
            let take = take_call(n, scalar.prim.size(), big(*scalar), "raw");
            let value = from_raw(lo, scalar.prim, "raw");
            try_call(&take) + &fill!("    ${dst} = ${value};\n", dst, value)
        }
        ValueType::Struct(si) => {
            let snake = names::snake(&p.structs[*si].name);
            try_call(&fill!("${lo}read_${snake}(r, &${dst})", lo, snake, dst))
        }
        ValueType::Enum(ei, scalar) => {
            let e = &p.enums[*ei];
            let ety = n.ty(&e.name);
            let mut out = try_call(&take_call(n, scalar.prim.size(), big(*scalar), "raw"));
            if rejects(e) {
                out.push_str(&fill!(
                    "    if (!${ety}_known(raw)) return ${up}ERR_INVALID_ENUM;\n",
                    ety,
                    up
                ));
            }
            let value = from_raw(lo, e.prim, "raw");
            out.push_str(&fill!("    ${dst} = (${ety})${value};\n", dst, ety, value));
            out
        }
        // Every byte as received (the runtime's `FixedStr` keeps them).
        ValueType::Text(len) => fill!(
            r"
    if (r->len - r->pos < ${len}u) return ${up}ERR_PAYLOAD_LENGTH;
    memcpy(${dst}, r->p + r->pos, ${len}u);
    r->pos += ${len}u;
",
            len,
            up,
            dst
        ),
    }
}

/// The statements that write one value of type `ty`, `src`, to the frame writer `w`.
pub fn write_elem(p: &Protocol, n: &Names, ty: &ValueType, src: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    match ty {
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => {
            let put = put_call(n, scalar.prim.size(), big(*scalar), "raw");
            super::scale::write(n, scalar.prim, sc, src) + &try_call(&put)
        }
        ValueType::Scalar { scalar, .. } => {
            let raw = to_raw(lo, scalar.prim, src);
            let put = put_call(n, scalar.prim.size(), big(*scalar), &raw);
            range_check(lo, scalar.prim, src, up) + &try_call(&put)
        }
        ValueType::Struct(si) => {
            let snake = names::snake(&p.structs[*si].name);
            try_call(&fill!("${lo}write_${snake}(w, &${src})", lo, snake, src))
        }
        ValueType::Enum(ei, scalar) => {
            let e = &p.enums[*ei];
            let raw = to_raw(lo, e.prim, src);
            let mut out = fill!("    raw = ${raw};\n", raw);
            if rejects(e) {
                let (ety, m) = (n.ty(&e.name), u64_lit(mask(8 * e.prim.size() as u32)));
                out.push_str(&fill!(
                    "    if (!${ety}_known(raw & ${m})) return ${up}ERR_OUT_OF_RANGE;\n",
                    ety,
                    m,
                    up
                ));
            }
            out + &try_call(&put_call(n, scalar.prim.size(), big(*scalar), "raw"))
        }
        ValueType::Text(len) => fill!(
            r"
    if (w->cap - w->pos < ${len}u) return ${up}ERR_SHORT_BUFFER;
    memcpy(w->p + w->pos, ${src}, ${len}u);
    w->pos += ${len}u;
",
            len,
            up,
            src
        ),
    }
}

/// The members of a bit field, read from its word.
pub fn read_bits(p: &Protocol, n: &Names, word: Scalar, members: &[BitMember]) -> String {
    let mut out = try_call(&take_call(n, word.prim.size(), big(word), "raw"));
    for m in members {
        let bits = format!("((raw >> {}) & {})", m.shift, u64_lit(mask(m.width)));
        out.push_str(&super::members::read_member(p, n, m, &bits));
    }
    out
}

/// The members of a bit field, each checked to fit, written as their word.
pub fn write_bits(p: &Protocol, n: &Names, word: Scalar, members: &[BitMember]) -> String {
    let mut out = String::from("    word = 0;\n");
    for m in members {
        out.push_str(&super::members::write_member(p, n, m));
        let shift = m.shift;
        out.push_str(&fill!("    word |= raw << ${shift};\n", shift));
    }
    out + &try_call(&put_call(n, word.prim.size(), big(word), "word"))
}
