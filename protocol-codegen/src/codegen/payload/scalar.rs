//! One value on the wire: scalar reads and writes, float scaling and rounding, which the
//! field kinds (`kinds`) print their reads and writes with.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::ir::{ByteOrder, Prim, Rounding, Scalar, Scale};

/// The Rust type of a primitive.
pub fn prim_type(prim: Prim) -> TokenStream {
    let t = Ident::new(prim.rust_name(), Span::call_site());
    quote!(#t)
}

pub(crate) fn suffix(s: Scalar) -> String {
    if s.prim == Prim::BoolInverted {
        return "bool_inverted".to_string();
    }
    let base = s.prim.spec_name();
    if s.prim.size() == 1 {
        base.to_string()
    } else {
        match s.endian {
            ByteOrder::Little => format!("{base}_le"),
            ByteOrder::Big => format!("{base}_be"),
        }
    }
}

/// `r.u16_le()?`
pub fn read_scalar(s: Scalar) -> TokenStream {
    read_scalar_from(&quote!(r), s)
}

/// `reader.u16_le()?`, `reader` an expression of type `&mut Reader`.
pub(super) fn read_scalar_from(reader: &TokenStream, s: Scalar) -> TokenStream {
    let m = format_ident!("{}", suffix(s));
    quote!(#reader.#m()?)
}

/// `w.put_u16_le(value)?`
pub fn write_scalar(s: Scalar, value: TokenStream) -> TokenStream {
    let m = format_ident!("put_{}", suffix(s));
    quote!(w.#m(#value)?;)
}

fn float_lit(x: f64) -> TokenStream {
    let lit = proc_macro2::Literal::f64_suffixed(x);
    quote!(#lit)
}

/// A scaled field's constant in the field's float type: its arithmetic stays in that type
/// (an `f32` field computes in `f32`, no `f64` soft-float on a target with an `f32` FPU).
fn scale_lit(x: f64, sc: &Scale) -> TokenStream {
    match sc.physical {
        Prim::F32 => {
            let lit = proc_macro2::Literal::f32_suffixed(x as f32);
            quote!(#lit)
        }
        _ => float_lit(x),
    }
}

/// The runtime's name of a rounding mode.
fn rounding(rt: &TokenStream, r: Rounding) -> TokenStream {
    match r {
        Rounding::Nearest => quote!(#rt::Rounding::Nearest),
        Rounding::Truncate => quote!(#rt::Rounding::Truncate),
    }
}

/// The physical value of the raw expression `raw`, of the Rust type of `raw_prim` (an integer,
/// or a float's own type, which takes no cast).
pub(crate) fn to_physical(
    raw: TokenStream,
    raw_prim: Prim,
    sc: &Scale,
    rt: &TokenStream,
) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let phys = prim_type(sc.physical);
    let raw = if raw_prim.rust_name() == sc.physical.rust_name() {
        raw
    } else {
        quote!(#raw as #phys)
    };
    let value = quote!(#rt::to_physical(#raw, #f, #o));
    match sc.clamp {
        // A value outside the clamp range would not encode back to the same bytes.
        Some((lo, hi)) => {
            let (lo, hi) = (scale_lit(lo, sc), scale_lit(hi, sc));
            quote!(#rt::check_clamp(#value, #lo, #hi)?)
        }
        None => value,
    }
}

/// The raw integer (of type `raw`) of the physical value `value`: clamped (if the field
/// clamps), quantized and fitted by the runtime; a value the raw type cannot hold is an error.
pub(super) fn to_raw(
    value: TokenStream,
    sc: &Scale,
    raw: Option<Prim>,
    rt: &TokenStream,
) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let physical = match sc.clamp {
        Some((lo, hi)) => {
            let (lo, hi) = (scale_lit(lo, sc), scale_lit(hi, sc));
            quote!(#rt::clamp(#value, #lo, #hi))
        }
        None => value,
    };
    let mode = rounding(rt, sc.rounding);
    let fit = match raw {
        Some(p) => {
            let t = prim_type(p);
            quote!(#rt::fit::<#t>)
        }
        None => quote!(#rt::fit),
    };
    quote!(#fit(#rt::quantize(#physical, #f, #o, #mode))?)
}

/// The raw value, of the wire's float type `wire` (`f16` is an `f32` in Rust), of the
/// physical value `value` of a scaled float field: clamped (if the field clamps) and unscaled
/// by the runtime, then cast to the wire's Rust type where it differs.
pub(super) fn to_raw_float(
    value: TokenStream,
    sc: &Scale,
    wire: Prim,
    rt: &TokenStream,
) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let physical = match sc.clamp {
        Some((lo, hi)) => {
            let (lo, hi) = (scale_lit(lo, sc), scale_lit(hi, sc));
            quote!(#rt::clamp(#value, #lo, #hi))
        }
        None => value,
    };
    let raw = quote!(#rt::unscale(#physical, #f, #o));
    if wire.rust_name() == sc.physical.rust_name() {
        raw
    } else {
        let t = prim_type(wire);
        quote!(#raw as #t)
    }
}

/// The local variable a struct's read code holds field `id` in.
pub(super) fn local(id: &Ident) -> Ident {
    format_ident!("f_{}", id.to_string().trim_start_matches("r#"))
}
