//! Scaled values in C: the runtime's field rules (`protocol_runtime::field`) printed as C
//! helpers, computed in the precision of the field's Rust type (`float` for an `f32` field,
//! `double` for an `f64` one), so that a C struct holds the same physical value the Rust codec
//! decodes, bit for bit, and encodes it to the same raw integer.
//!
//! * decoding: `physical = raw * factor + offset`, or `raw / n + offset` when `factor` is the
//!   reciprocal of an integer `n` (`to_physical`), the raw integer first converted to `f64`
//!   and then to the field's type as the runtime does; a value outside the clamp range (with
//!   the runtime's slack) is an error (`check_clamp`);
//! * encoding: clamped (`clamp`), divided back and rounded (`quantize`, to nearest or by
//!   truncation within float noise), then its integer part must fit the raw type (`fit`: the
//!   runtime's exclusive bounds of each type), never saturated.
//!
//! The rules' constants (the relative noise and clamp slack, the raw types' bounds) are the
//! runtime's own, printed from its [`Float`] and [`RawInt`] constants.
//!
//! The C arithmetic agrees with Rust's when the compiler does not fuse a multiply and an add
//! (`-ffp-contract=off`, the default of gcc in a strict `-std=c99` mode): every product and
//! sum is its own statement, so clang's default (fusing within one expression) fuses nothing.

use protocol_runtime::field::{Float, RawInt};

use crate::ir::{Prim, Rounding, Scale};

use super::names::{Names, float_of};
use super::template::fill;

/// A C literal of `x` in the physical type (the shortest decimal that reads back as the same
/// `f32` or `f64`).
pub fn lit(x: f64, physical: Prim) -> String {
    match physical {
        Prim::F32 => format!("{:?}f", x as f32),
        _ => format!("{x:?}"),
    }
}

/// The helpers of the field rules, in both float types (`templates/scale.c`).
pub fn helpers(n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = String::from(
        "/* ---- Scaled values: the runtime's field rules, in the field's float type ---- */\n\n",
    );
    for (ty, sfx, noise, slack, cut) in [
        (
            "float",
            "f32",
            format!("{:?}f", <f32 as Float>::NOISE),
            format!("{:?}f", <f32 as Float>::CLAMP_SLACK),
            // Every float of magnitude 2^23 or more is an integer already.
            r"
    if (x >= 8388608.0f || x <= -8388608.0f) return x;
    return (float)(int32_t)x;
",
        ),
        (
            "double",
            "f64",
            format!("{:?}", <f64 as Float>::NOISE),
            format!("{:?}", <f64 as Float>::CLAMP_SLACK),
            // As Rust's saturating `as i64`.
            r"
    if (x >= 9223372036854775808.0) return 9223372036854775808.0;
    if (x <= -9223372036854775808.0) return -9223372036854775808.0;
    return (double)(int64_t)x;
",
        ),
    ] {
        let cut = cut.strip_prefix('\n').unwrap_or(cut);
        let (one, zero, half) = if sfx == "f32" {
            ("1.0f", "0.0f", "0.5f")
        } else {
            ("1.0", "0.0", "0.5")
        };
        out.push_str(&fill!(
            include_str!("templates/scale.c"),
            lo,
            up,
            ty,
            sfx,
            noise,
            slack,
            cut,
            one,
            zero,
            half
        ));
        out.push('\n');
    }
    out
}

/// The runtime's exclusive bounds of a raw type (`fit`), in the physical type; a 24-, 40-,
/// 48- or 56-bit type is fitted to its Rust type first.
fn bounds(raw: Prim, physical: Prim) -> (String, String) {
    fn of<T: RawInt>(physical: Prim) -> (String, String) {
        match physical {
            Prim::F32 => (
                format!("{:?}f", T::BELOW_F32),
                format!("{:?}f", T::ABOVE_F32),
            ),
            _ => (format!("{:?}", T::BELOW), format!("{:?}", T::ABOVE)),
        }
    }
    match raw {
        Prim::U8 => of::<u8>(physical),
        Prim::U16 => of::<u16>(physical),
        Prim::U24 | Prim::U32 => of::<u32>(physical),
        Prim::U40 | Prim::U48 | Prim::U56 | Prim::U64 => of::<u64>(physical),
        Prim::I8 => of::<i8>(physical),
        Prim::I16 => of::<i16>(physical),
        Prim::I24 | Prim::I32 => of::<i32>(physical),
        Prim::I40 | Prim::I48 | Prim::I56 => of::<i64>(physical),
        // Validation gives scaled fields an integer raw type.
        _ => of::<i64>(physical),
    }
}

/// Statements that set `dst` to the physical value of the raw integer `raw` (a `uint64_t`
/// C expression of the raw bits) of type `prim`; a value outside the clamp range returns
/// `<PREFIX>ERR_OUTSIDE_CLAMP`.
pub fn read(n: &Names, prim: Prim, sc: &Scale, raw: &str, dst: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (ty, sfx) = float_of(sc.physical);
    let int = match prim {
        Prim::F16 | Prim::F32 | Prim::F64 => {
            format!("(double){lo}{}({raw})", prim.spec_name())
        }
        p if p.is_signed() => format!("(double){lo}sext({raw}, {}u)", 8 * p.size()),
        _ => format!("(double){raw}"),
    };
    let (factor, offset) = (lit(sc.factor, sc.physical), lit(sc.offset, sc.physical));
    let mut out = fill!(
        "    ${dst} = ${lo}to_physical_${sfx}((${ty})${int}, ${factor}, ${offset});\n",
        dst,
        lo,
        sfx,
        ty,
        int,
        factor,
        offset
    );
    if let Some((a, b)) = sc.clamp {
        let (a, b) = (lit(a, sc.physical), lit(b, sc.physical));
        out.push_str(&fill!(
            "    if (!${lo}within_${sfx}(${dst}, ${a}, ${b})) return ${up}ERR_OUTSIDE_CLAMP;\n",
            lo,
            sfx,
            dst,
            a,
            b,
            up
        ));
    }
    out
}

/// The statement that clamps `x` to the field's clamp range, if it has one.
fn clamp(lo: &str, sc: &Scale) -> String {
    let (_, sfx) = float_of(sc.physical);
    match sc.clamp {
        Some((a, b)) => {
            let (a, b) = (lit(a, sc.physical), lit(b, sc.physical));
            fill!(
                "        x = ${lo}clamp_${sfx}(x, ${a}, ${b});\n",
                lo,
                sfx,
                a,
                b
            )
        }
        None => String::new(),
    }
}

/// Statements that set `uint64_t raw` to the raw bits of the physical value `src` of a field
/// of raw type `prim`; a value the type cannot hold returns `<PREFIX>ERR_OUT_OF_RANGE`.
pub fn write(n: &Names, prim: Prim, sc: &Scale, src: &str) -> String {
    if prim.is_float() {
        return write_float(n, prim, sc, src);
    }
    let (lo, up) = (&n.lo, &n.up);
    let (ty, sfx) = float_of(sc.physical);
    let clamp = clamp(lo, sc);
    let (below, above) = bounds(prim, sc.physical);
    let (factor, offset) = (lit(sc.factor, sc.physical), lit(sc.offset, sc.physical));
    let truncate = u8::from(sc.rounding == Rounding::Truncate);
    let ct = super::names::prim(prim);
    let fits = match prim {
        Prim::U24 => fill!(
            "            if (k > 0xFFFFFFu) return ${up}ERR_OUT_OF_RANGE;\n",
            up
        ),
        Prim::I24 => fill!(
            "            if (k < -8388608L || k > 8388607L) return ${up}ERR_OUT_OF_RANGE;\n",
            up
        ),
        // The statement of an unscaled value, indented into the block above.
        _ => format!(
            "            {}",
            super::values::range_check(lo, prim, "k", up).trim_start()
        ),
    };
    let bits = if prim.is_signed() {
        "(uint64_t)(int64_t)k"
    } else {
        "(uint64_t)k"
    };
    fill!(
        r"
    {
        ${ty} x = ${src};
${clamp}        x = ${lo}quantize_${sfx}(x, ${factor}, ${offset}, ${truncate});
        if (!(x > ${below} && x < ${above})) return ${up}ERR_OUT_OF_RANGE;
        {
            ${ct} k = (${ct})x;
${fits}            raw = ${bits};
        }
    }
",
        ty,
        src,
        clamp,
        lo,
        sfx,
        factor,
        offset,
        truncate,
        below,
        above,
        up,
        ct,
        fits,
        bits
    )
}

/// Statements that set `uint64_t raw` to the bits of the physical value `src` of a field whose
/// wire type `prim` is a float: clamped (if the field clamps), unscaled (the runtime's
/// `unscale`), converted to the wire's type as Rust's `as` casts do (a half through `float`);
/// a value beyond the largest half returns `<PREFIX>ERR_OUT_OF_RANGE`.
fn write_float(n: &Names, prim: Prim, sc: &Scale, src: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let (ty, sfx) = float_of(sc.physical);
    let clamp = clamp(lo, sc);
    let (factor, offset) = (lit(sc.factor, sc.physical), lit(sc.offset, sc.physical));
    let (bits, check) = match prim {
        Prim::F64 => (format!("{lo}f64_bits((double)x)"), String::new()),
        Prim::F32 => (format!("{lo}f32_bits((float)x)"), String::new()),
        _ => (
            format!("{lo}f16_bits((float)x)"),
            fill!(
                "        if (raw > 0xFFFFu) return ${up}ERR_OUT_OF_RANGE;\n",
                up
            ),
        ),
    };
    fill!(
        r"
    {
        ${ty} x = ${src};
${clamp}        x = ${lo}unscale_${sfx}(x, ${factor}, ${offset});
        raw = ${bits};
${check}    }
",
        ty,
        src,
        clamp,
        lo,
        sfx,
        factor,
        offset,
        bits,
        check
    )
}
