//! `#[derive(Payload)]` for hand-written structs: parse the struct and its `#[payload(...)]`
//! attributes into the payload generator's model, then emit with the same generator the spec
//! structs use.
//!
//! Attributes:
//! - on the struct: `#[payload(byte_order = "big")]` (default `"little"`),
//!   `#[payload(crate = "::my::protocol")]` (where the `protocol` crate is, when it is not
//!   `::protocol`; a bare path works too);
//! - on a field: `#[payload(byte_order = "big")]`, `#[payload(pad_before = 3)]`,
//!   `#[payload(pad_after = 1)]`, `#[payload(scale = 0.001, raw = "i16")]` (an `f32`/`f64` field
//!   stored as a scaled integer), `#[payload(raw = "u24")]` alone on an integer field (a `u32`
//!   or `i32` on the wire as the 24-bit `u24`/`i24`), `#[payload(repr = "u8")]` (a type with
//!   `to_raw`/`from_raw`, such as a generated enum).
//!
//! Fields of primitive types (`u8` … `i64`, `f32`, `f64`, `bool`) and arrays of them are
//! encoded directly; any other type must implement `Payload` itself.

use proc_macro2::TokenStream;
use quote::quote;
use syn::spanned::Spanned;
use syn::{Data, DeriveInput, Expr, Fields, Lit, Type};

use super::RuntimePath;
use super::payload::{PField, PKind, PayloadDef, emit_payload_impl};
use crate::ir::{ByteOrder, Prim, Rounding, Scalar, Scale};

#[derive(Default)]
struct FieldAttrs {
    endian: Option<ByteOrder>,
    pad_before: usize,
    pad_after: usize,
    scale: Option<f64>,
    raw: Option<Prim>,
    repr: Option<Prim>,
}

fn parse_endian(lit: &syn::LitStr) -> syn::Result<ByteOrder> {
    match lit.value().as_str() {
        "little" => Ok(ByteOrder::Little),
        "big" => Ok(ByteOrder::Big),
        _ => Err(syn::Error::new(
            lit.span(),
            "expected \"little\" or \"big\"",
        )),
    }
}

/// `crate = "::my::protocol"` (as serde's `crate = "..."`) or `crate = ::my::protocol`.
fn parse_crate_path(value: syn::parse::ParseStream<'_>) -> syn::Result<RuntimePath> {
    let path: syn::Path = if value.peek(syn::LitStr) {
        value.parse::<syn::LitStr>()?.parse()?
    } else {
        value.parse()?
    };
    Ok(RuntimePath(quote!(#path)))
}

fn parse_prim_lit(lit: &syn::LitStr) -> syn::Result<Prim> {
    Prim::from_spec_name(&lit.value())
        .filter(|p| p.is_signed() || p.is_unsigned())
        .ok_or_else(|| {
            syn::Error::new(
                lit.span(),
                "expected an integer type such as \"u8\" or \"i16\"",
            )
        })
}

/// Expand `#[derive(Payload)]`.
///
/// # Errors
/// A `syn::Error` pointing at the offending item for anything that is not a struct with named
/// fields, or an attribute it does not know.
pub fn derive_payload(input: &DeriveInput) -> syn::Result<TokenStream> {
    let named = check_struct_shape(input)?;
    let (struct_endian, paths) = parse_struct_attrs(input)?;
    let mut fields = Vec::new();
    for f in &named.named {
        let a = parse_field_attrs(f)?;
        let endian = a.endian.unwrap_or(struct_endian);
        if a.pad_before > 0 {
            fields.push(padding(a.pad_before));
        }
        fields.push(PField {
            ident: f.ident.clone(),
            kind: field_kind(f, &a, endian)?,
        });
        if a.pad_after > 0 {
            fields.push(padding(a.pad_after));
        }
    }
    let def = PayloadDef {
        name: input.ident.clone(),
        fields,
        size: None,
        min_size: None,
    };
    Ok(emit_payload_impl(&def, &paths.private()))
}

/// The derive takes a struct with named fields and no generic parameters: the wire layout is
/// the fields in order, and a generic field has no fixed wire type.
fn check_struct_shape(input: &DeriveInput) -> syn::Result<&syn::FieldsNamed> {
    let Data::Struct(data) = &input.data else {
        return Err(syn::Error::new(
            input.ident.span(),
            "#[derive(Payload)] supports structs only",
        ));
    };
    if !input.generics.params.is_empty() {
        return Err(syn::Error::new(
            input.generics.span(),
            "#[derive(Payload)] does not support generic structs",
        ));
    }
    let Fields::Named(named) = &data.fields else {
        return Err(syn::Error::new(
            input.ident.span(),
            "#[derive(Payload)] needs named fields",
        ));
    };
    Ok(named)
}

/// The struct's `#[payload(...)]`: its default byte order and where the runtime is.
fn parse_struct_attrs(input: &DeriveInput) -> syn::Result<(ByteOrder, RuntimePath)> {
    let mut struct_endian = ByteOrder::Little;
    let mut paths = RuntimePath::default();
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("payload")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("byte_order") {
                struct_endian = parse_endian(&meta.value()?.parse()?)?;
                Ok(())
            } else if meta.path.is_ident("crate") {
                paths = parse_crate_path(meta.value()?)?;
                Ok(())
            } else {
                Err(meta.error("unknown payload attribute; expected `byte_order` or `crate`"))
            }
        })?;
    }
    Ok((struct_endian, paths))
}

/// A field's `#[payload(...)]` attributes.
fn parse_field_attrs(f: &syn::Field) -> syn::Result<FieldAttrs> {
    let mut a = FieldAttrs::default();
    for attr in f.attrs.iter().filter(|a| a.path().is_ident("payload")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("byte_order") {
                a.endian = Some(parse_endian(&meta.value()?.parse()?)?);
            } else if meta.path.is_ident("pad_before") {
                a.pad_before = meta.value()?.parse::<syn::LitInt>()?.base10_parse()?;
            } else if meta.path.is_ident("pad_after") {
                a.pad_after = meta.value()?.parse::<syn::LitInt>()?.base10_parse()?;
            } else if meta.path.is_ident("scale") {
                a.scale = Some(parse_number(&meta.value()?.parse()?)?);
            } else if meta.path.is_ident("raw") {
                a.raw = Some(parse_prim_lit(&meta.value()?.parse()?)?);
            } else if meta.path.is_ident("repr") {
                a.repr = Some(parse_prim_lit(&meta.value()?.parse()?)?);
            } else {
                return Err(meta.error("unknown payload attribute; expected `byte_order`, `pad_before`, `pad_after`, `scale`, `raw` or `repr`"));
            }
            Ok(())
        })?;
    }
    Ok(a)
}

/// A number literal, integer or float, as an `f64` (a scale factor).
fn parse_number(e: &Expr) -> syn::Result<f64> {
    match e {
        Expr::Lit(l) => match &l.lit {
            Lit::Float(x) => x.base10_parse(),
            Lit::Int(x) => Ok(x.base10_parse::<i64>()? as f64),
            _ => Err(syn::Error::new(e.span(), "expected a number")),
        },
        _ => Err(syn::Error::new(e.span(), "expected a number")),
    }
}

/// Reserved bytes between fields.
fn padding(n: usize) -> PField {
    PField {
        ident: None,
        kind: PKind::Pad(n),
    }
}

/// A field's element type and, for an array, its length: an array's length must be an
/// integer literal, so that the wire size is known at expansion.
fn array_elem(ty: &Type) -> syn::Result<(&Type, Option<usize>)> {
    let Type::Array(arr) = ty else {
        return Ok((ty, None));
    };
    let len = match &arr.len {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) => i.base10_parse::<usize>()?,
        _ => {
            return Err(syn::Error::new(
                arr.len.span(),
                "array length must be an integer literal",
            ));
        }
    };
    Ok((&*arr.elem, Some(len)))
}

/// What the payload generator makes of a field: an enum through its `repr`, a scaled float
/// through its `raw` wire type, a primitive, or a nested type that implements `Payload`.
fn field_kind(f: &syn::Field, a: &FieldAttrs, endian: ByteOrder) -> syn::Result<PKind> {
    let (elem, count) = array_elem(&f.ty)?;
    let prim = match elem {
        Type::Path(tp) if tp.qself.is_none() => tp
            .path
            .get_ident()
            .and_then(|i| Prim::from_rust_name(&i.to_string()))
            .map(|prim| Scalar { prim, endian }),
        _ => None,
    };
    if let Some(repr) = a.repr {
        return Ok(PKind::Enum {
            ty: quote!(#elem),
            scalar: Scalar { prim: repr, endian },
            count,
        });
    }
    if let Some(factor) = a.scale {
        let Some(phys) = prim.filter(|s| s.prim.is_float()) else {
            return Err(syn::Error::new(
                f.ty.span(),
                "a scaled field must be `f32` or `f64`",
            ));
        };
        let Some(raw) = a.raw else {
            return Err(syn::Error::new(
                f.ty.span(),
                "a scaled field needs `raw = \"i16\"` (its wire type)",
            ));
        };
        return Ok(PKind::Scalar {
            scalar: Scalar { prim: raw, endian },
            scale: Some(Scale {
                factor,
                offset: 0.0,
                physical: phys.prim,
                rounding: Rounding::Nearest,
                clamp: None,
            }),
            count,
        });
    }
    if let Some(raw) = a.raw {
        // Without `scale`, `raw` is the wire form of an integer of the same Rust type.
        let Some(field) = prim.filter(|s| s.prim.rust_name() == raw.rust_name()) else {
            return Err(syn::Error::new(
                f.ty.span(),
                format!(
                    "`raw = \"{}\"` without `scale` needs a `{}` field",
                    raw.spec_name(),
                    raw.rust_name()
                ),
            ));
        };
        return Ok(PKind::Scalar {
            scalar: Scalar {
                prim: raw,
                endian: field.endian,
            },
            scale: None,
            count,
        });
    }
    Ok(match prim {
        Some(s) => PKind::Scalar {
            scalar: s,
            scale: None,
            count,
        },
        None => PKind::Nested {
            ty: quote!(#elem),
            count,
        },
    })
}
