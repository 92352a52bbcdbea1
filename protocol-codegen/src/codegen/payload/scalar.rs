//! One value on the wire: scalar reads and writes, float scaling and rounding, bit-packed
//! arrays.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::def::PKind;
use crate::ir::{BitOrder, ByteOrder, Prim, Rounding, Scalar, Scale};

/// The Rust type of a primitive.
pub fn prim_type(prim: Prim) -> TokenStream {
    let t = Ident::new(prim.rust_name(), Span::call_site());
    quote!(#t)
}

fn suffix(s: Scalar) -> String {
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
fn read_scalar_from(reader: &TokenStream, s: Scalar) -> TokenStream {
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

/// Reading one element of a field from `reader` (`r`, or `r.pad(n)?` after padding). The
/// field rules are the runtime's (`field`), called with the field's constants.
///
/// Whatever can fail here other than for want of bytes (clamped scales, enums) must also make
/// [`needs_only_bytes`] answer `None`; a kind it does not know it answers `None` for.
pub(super) fn read_elem(kind: &PKind, reader: &TokenStream, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Scalar {
            scalar,
            scale: None,
            ..
        } => read_scalar_from(reader, *scalar),
        PKind::Scalar {
            scalar,
            scale: Some(sc),
            ..
        } => to_physical(read_scalar_from(reader, *scalar), sc, rt),
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::read(#reader)?),
        PKind::Enum { ty, scalar, .. } => {
            let raw = read_scalar_from(reader, *scalar);
            quote!(#ty::from_raw(#raw)?)
        }
        PKind::Bytes {
            ty,
            size_from: None,
            ..
        } => quote!(<#ty>::read_rest(r)?),
        PKind::Var { ty } => quote!(<#ty as #rt::Payload>::read(r)?),
        PKind::Bytes {
            ty,
            size_from: Some(n),
            ..
        } => {
            let var = local(n);
            quote!(<#ty>::read_sized(r, #var as u64)?)
        }
        PKind::Pad(_)
        | PKind::Bits { .. }
        | PKind::Group { .. }
        | PKind::Array { .. }
        | PKind::Optional(_)
        | PKind::Packed { .. }
        | PKind::Check { .. } => quote!(()),
    }
}

/// The physical value of the raw integer expression `raw`.
fn to_physical(raw: TokenStream, sc: &Scale, rt: &TokenStream) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let phys = prim_type(sc.physical);
    let value = quote!(#rt::to_physical(#raw as #phys, #f, #o));
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

/// The runtime's name of a bit order.
fn bit_order(rt: &TokenStream, order: BitOrder) -> TokenStream {
    match order {
        BitOrder::LsbFirst => quote!(#rt::BitOrder::LsbFirst),
        BitOrder::MsbFirst => quote!(#rt::BitOrder::MsbFirst),
    }
}

/// Reading a bit-packed array: its bytes at once, then each element from them.
pub(super) fn read_packed(kind: &PKind, rt: &TokenStream) -> TokenStream {
    let PKind::Packed {
        count,
        bits,
        order,
        prim,
        scale,
        size,
    } = kind
    else {
        return quote!(());
    };
    let order = bit_order(rt, *order);
    let raw = quote!(#rt::get_packed(bytes, i, #bits, #order));
    let (t, elem) = match scale {
        None => {
            let t = prim_type(*prim);
            (t.clone(), quote!(#raw as #t))
        }
        Some(sc) => (prim_type(sc.physical), to_physical(raw, sc, rt)),
    };
    quote! {{
        let bytes = r.take(#size)?;
        let mut a: [#t; #count] = [<#t as ::core::default::Default>::default(); #count];
        for (i, e) in a.iter_mut().enumerate() { *e = #elem; }
        a
    }}
}

/// Writing a bit-packed array `value`: each element into its bits of a zeroed run of bytes,
/// then the run.
pub(super) fn write_packed(kind: &PKind, value: TokenStream, rt: &TokenStream) -> TokenStream {
    let PKind::Packed {
        bits,
        order,
        prim,
        scale,
        size,
        ..
    } = kind
    else {
        return quote!();
    };
    let order = bit_order(rt, *order);
    let raw = match scale {
        None => quote!(*e as u64),
        Some(sc) => {
            let raw = to_raw(quote!(*e), sc, Some(*prim), rt);
            quote!(#raw as u64)
        }
    };
    quote! {{
        let mut bytes = [0u8; #size];
        for (i, e) in #value.iter().enumerate() {
            #rt::set_packed(&mut bytes, i, #bits, #order, #raw)?;
        }
        w.put_bytes(&bytes)?;
    }}
}

/// The local variable a struct's read code holds field `id` in.
pub(super) fn local(id: &Ident) -> Ident {
    format_ident!("f_{}", id.to_string().trim_start_matches("r#"))
}
