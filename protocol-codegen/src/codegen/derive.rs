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
//!   stored as a scaled integer), `#[payload(repr = "u8")]` (a type with `to_raw`/`from_raw`,
//!   such as a generated enum).
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
    Prim::from_rust_name(&lit.value())
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
    let mut fields = Vec::new();
    for f in &named.named {
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
                    let e: Expr = meta.value()?.parse()?;
                    a.scale = Some(match &e {
                        Expr::Lit(l) => match &l.lit {
                            Lit::Float(x) => x.base10_parse()?,
                            Lit::Int(x) => x.base10_parse::<i64>()? as f64,
                            _ => return Err(syn::Error::new(e.span(), "expected a number")),
                        },
                        _ => return Err(syn::Error::new(e.span(), "expected a number")),
                    });
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
        let endian = a.endian.unwrap_or(struct_endian);
        if a.pad_before > 0 {
            fields.push(PField {
                ident: None,
                kind: PKind::Pad(a.pad_before),
            });
        }
        let (elem, count) = match &f.ty {
            Type::Array(arr) => {
                let n = match &arr.len {
                    Expr::Lit(l) => match &l.lit {
                        Lit::Int(i) => i.base10_parse::<usize>()?,
                        _ => {
                            return Err(syn::Error::new(
                                arr.len.span(),
                                "array length must be an integer literal",
                            ));
                        }
                    },
                    _ => {
                        return Err(syn::Error::new(
                            arr.len.span(),
                            "array length must be an integer literal",
                        ));
                    }
                };
                (&*arr.elem, Some(n))
            }
            t => (t, None),
        };
        let prim = match elem {
            Type::Path(tp) if tp.qself.is_none() => tp
                .path
                .get_ident()
                .and_then(|i| Prim::from_rust_name(&i.to_string()))
                .map(|prim| Scalar { prim, endian }),
            _ => None,
        };
        let kind = if let Some(repr) = a.repr {
            PKind::Enum {
                ty: quote!(#elem),
                scalar: Scalar { prim: repr, endian },
                count,
            }
        } else if let Some(factor) = a.scale {
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
            PKind::Scalar {
                scalar: Scalar { prim: raw, endian },
                scale: Some(Scale {
                    factor,
                    offset: 0.0,
                    physical: phys.prim,
                    rounding: Rounding::Nearest,
                    clamp: None,
                }),
                count,
            }
        } else if let Some(s) = prim {
            PKind::Scalar {
                scalar: s,
                scale: None,
                count,
            }
        } else {
            PKind::Nested {
                ty: quote!(#elem),
                count,
            }
        };
        fields.push(PField {
            ident: f.ident.clone(),
            kind,
        });
        if a.pad_after > 0 {
            fields.push(PField {
                ident: None,
                kind: PKind::Pad(a.pad_after),
            });
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
