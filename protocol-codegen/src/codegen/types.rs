//! Spec constants, address sets, enums and payload structs as Rust items. The structs' wire
//! code comes from the shared payload generator ([`super::payload`]).

use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::docs::{doc_attrs, struct_doc};
use super::frame::algorithm_expr;
use super::payload::{
    BitType, PBit, PField, PKind, PayloadDef, emit_payload_impl, field_type, prim_type,
};
use super::{const_ident, ident};
use crate::ir::{Enum, FieldKind, Prim, Protocol, Struct, UnknownPolicy, ValueType};

/// A literal of the given integer type holding `value` (two's complement bits for signed).
pub fn int_lit(prim: Prim, value: u64) -> TokenStream {
    let lit = match prim {
        Prim::U8 => Literal::u8_suffixed(value as u8),
        Prim::I8 => Literal::i8_suffixed(value as u8 as i8),
        Prim::U16 => Literal::u16_suffixed(value as u16),
        Prim::I16 => Literal::i16_suffixed(value as u16 as i16),
        Prim::U32 | Prim::U24 => Literal::u32_suffixed(value as u32),
        Prim::I32 => Literal::i32_suffixed(value as u32 as i32),
        // Two's complement bits of 24 bits, sign-extended.
        Prim::I24 => Literal::i32_suffixed(((value as u32) << 8) as i32 >> 8),
        Prim::I64 => Literal::i64_suffixed(value as i64),
        _ => Literal::u64_suffixed(value),
    };
    quote!(#lit)
}

/// `pub const NAME: u64 = value;` per spec constant.
pub fn emit_constants(p: &Protocol) -> TokenStream {
    let items = p.constants.iter().map(|c| {
        let name = const_ident(&c.name);
        let v = c.value;
        let doc = doc_attrs(if c.doc.is_empty() {
            "Spec constant."
        } else {
            &c.doc
        });
        quote!(#doc pub const #name: u64 = #v;)
    });
    quote!(#(#items)*)
}

/// `pub mod addresses` with a const per set: a `RangeInclusive` or a single address.
pub fn emit_addresses(p: &Protocol) -> TokenStream {
    if p.addresses.is_empty() {
        return quote!();
    }
    let prim = address_prim(p);
    let ty = prim_type(prim);
    let items = p.addresses.iter().map(|a| {
        let name = const_ident(&a.name);
        let doc = if a.doc.is_empty() {
            let what = if a.first == a.last {
                format!("{:#x}", a.first)
            } else {
                format!("{:#x} to {:#x}", a.first, a.last)
            };
            doc_attrs(&format!("Address `{}`: {what}.", a.name))
        } else {
            doc_attrs(&a.doc)
        };
        let first = int_lit(prim, a.first);
        let last = int_lit(prim, a.last);
        if a.first == a.last {
            quote!(#doc pub const #name: #ty = #first;)
        } else {
            quote!(#doc pub const #name: ::core::ops::RangeInclusive<#ty> = #first..=#last;)
        }
    });
    quote! {
        /// The spec's named addresses and address ranges.
        pub mod addresses {
            #(#items)*
        }
    }
}

/// The integer type of address fields: that of the first field marked `addresses`, else `u8`.
pub fn address_prim(p: &Protocol) -> Prim {
    p.frames
        .first()
        .and_then(|f| {
            f.values
                .iter()
                .find(|v| matches!(v.role, crate::ir::Role::User { addresses: true }))
        })
        .map_or(Prim::U8, |v| v.prim)
}

/// Every enum with `to_raw` and `from_raw`.
pub fn emit_enums(p: &Protocol) -> TokenStream {
    let items = p.enums.iter().map(emit_enum);
    quote!(#(#items)*)
}

fn emit_enum(e: &Enum) -> TokenStream {
    let rt = super::rt();
    let name = ident(&e.name);
    let raw = prim_type(e.prim);
    let mut doc = e.doc.clone();
    doc.push_str(&format!(
        "\n\nOn the wire as `{}`. {}",
        e.prim.spec_name(),
        match e.unknown {
            UnknownPolicy::Reject => "A value with no variant is a decode error.",
            UnknownPolicy::Keep => "A value with no variant decodes to `Unknown(raw)`.",
        }
    ));
    let doc = doc_attrs(&doc);
    let variants = e.variants.iter().enumerate().map(|(i, v)| {
        let vn = ident(&v.rust_name);
        let vdoc = doc_attrs(&format!(
            "`{}` = {}{}{}",
            v.name,
            v.value,
            if v.doc.is_empty() { "" } else { ": " },
            v.doc
        ));
        let default = if i == 0 { quote!(#[default]) } else { quote!() };
        quote!(#vdoc #default #vn)
    });
    let (unknown_variant, unknown_to, unknown_from) = match e.unknown {
        UnknownPolicy::Keep => (
            quote!(#[doc = " A value with no variant, kept as it was on the wire."] Unknown(#raw),),
            quote!(Self::Unknown(raw) => raw,),
            quote!(other => #rt::Ok(Self::Unknown(other)),),
        ),
        UnknownPolicy::Reject => (
            quote!(),
            quote!(),
            quote!(other => #rt::Err(#rt::DecodeError::InvalidEnum { value: other as u64, place: #rt::Place::NONE }),),
        ),
    };
    let to = e.variants.iter().map(|v| {
        let vn = ident(&v.rust_name);
        let lit = int_lit(e.prim, v.value);
        quote!(Self::#vn => #lit,)
    });
    let from = e.variants.iter().map(|v| {
        let vn = ident(&v.rust_name);
        let lit = int_lit(e.prim, v.value);
        quote!(#lit => #rt::Ok(Self::#vn),)
    });
    quote! {
        #doc
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub enum #name {
            #(#variants,)*
            #unknown_variant
        }
        impl #name {
            /// The value on the wire.
            pub const fn to_raw(self) -> #raw {
                match self {
                    #(#to)*
                    #unknown_to
                }
            }
            /// The variant of a wire value.
            ///
            /// # Errors
            /// `DecodeError::InvalidEnum` for a value with no variant, unless the enum keeps
            /// unknown values.
            pub const fn from_raw(raw: #raw) -> #rt::DecodeResult<Self> {
                match raw {
                    #(#from)*
                    #unknown_from
                }
            }
        }
    }
}

/// Lower an IR struct into the payload generator's model.
pub fn payload_def(p: &Protocol, s: &Struct) -> PayloadDef {
    PayloadDef {
        name: ident(&s.name),
        fields: payload_fields(p, s),
        size: Some(s.size),
        min_size: Some(s.min_size),
    }
}

fn payload_fields(p: &Protocol, s: &Struct) -> Vec<PField> {
    s.fields
        .iter()
        .map(|f| PField {
            ident: (!f.name.is_empty() && !matches!(f.kind, FieldKind::Check(_)))
                .then(|| ident(&f.name)),
            kind: payload_kind(p, &f.kind, f.size),
        })
        .collect()
}

fn payload_kind(p: &Protocol, kind: &FieldKind, size: usize) -> PKind {
    let rt = super::rt();
    match kind {
        FieldKind::Padding => PKind::Pad(size),
        FieldKind::Bytes { max, size_from } => PKind::Bytes {
            ty: quote!(#rt::Bytes<#max>),
            max: *max,
            size_from: size_from.as_deref().map(ident),
        },
        FieldKind::Group { elem, max } => {
            let e = &p.structs[*elem];
            let elem_ty = ident(&e.name);
            PKind::Group {
                ty: quote!(#rt::Group<#elem_ty, #max>),
                elem_ty: quote!(#elem_ty),
                elem: payload_fields(p, e),
                max: *max,
                elem_size: e.size,
            }
        }
        FieldKind::Optional(inner) => PKind::Optional(Box::new(payload_kind(p, inner, size))),
        FieldKind::Array { ty, max, size_from } => {
            let elem = payload_kind(
                p,
                &FieldKind::Value {
                    ty: ty.clone(),
                    count: None,
                },
                size / max,
            );
            let t = field_type(&elem);
            PKind::Array {
                ty: quote!(#rt::Group<#t, #max>),
                elem: Box::new(elem),
                max: *max,
                size_from: size_from.as_deref().map(ident),
                elem_size: size / max,
            }
        }
        FieldKind::NulText { max } => PKind::Var {
            ty: quote!(#rt::NulStr<#max>),
        },
        FieldKind::Check(c) => PKind::Check {
            // Its table's `static` is printed once, by `check_statics`.
            checksum: algorithm_expr(&rt, "", &c.algorithm, &c.naming, &mut Vec::new()),
            first: c.first,
            last: c.last,
            endian: c.endian,
            width: size,
        },
        FieldKind::Packed {
            count,
            bits,
            order,
            prim,
            scale,
        } => PKind::Packed {
            count: *count,
            bits: *bits,
            order: *order,
            prim: *prim,
            scale: *scale,
            size,
        },
        FieldKind::Bits { word, members } => PKind::Bits {
            word: *word,
            members: members
                .iter()
                .map(|m| PBit {
                    ident: ident(&m.name),
                    shift: m.shift,
                    width: m.width,
                    ty: match m.enum_index {
                        Some(i) => BitType::Enum(
                            named_type(&p.enums[i].name, p.enums[i].foreign),
                            p.enums[i].prim,
                        ),
                        None if m.prim == Prim::Bool => BitType::Bool,
                        None => BitType::Uint(m.prim),
                    },
                })
                .collect(),
        },
        FieldKind::Value { ty, count } => match ty {
            ValueType::Scalar { scalar, scale } => PKind::Scalar {
                scalar: *scalar,
                scale: *scale,
                count: *count,
            },
            ValueType::Struct(i) => PKind::Nested {
                ty: named_type(&p.structs[*i].name, p.structs[*i].foreign),
                count: *count,
            },
            ValueType::Enum(i, scalar) => PKind::Enum {
                ty: named_type(&p.enums[*i].name, p.enums[*i].foreign),
                scalar: *scalar,
                count: *count,
            },
            ValueType::Text(n) => PKind::Nested {
                ty: quote!(#rt::FixedStr<#n>),
                count: *count,
            },
        },
    }
}

/// The tables of the CRCs of the checks inside payloads, one `static` each.
fn check_statics(p: &Protocol) -> TokenStream {
    let rt = super::rt();
    let mut statics = Vec::new();
    for f in p.structs.iter().flat_map(|s| &s.fields) {
        if let FieldKind::Check(c) = &f.kind {
            algorithm_expr(&rt, &f.name, &c.algorithm, &c.naming, &mut statics);
        }
    }
    quote!(#(#statics)*)
}

/// The Rust type of a struct or enum a field names: a generated type's identifier, or a type
/// of the user's crate (a derive's) as written.
fn named_type(name: &str, foreign: bool) -> TokenStream {
    if foreign {
        // The derive printed it from tokens, so it parses back.
        name.parse().unwrap_or_default()
    } else {
        let n = ident(name);
        quote!(#n)
    }
}

/// Every struct: declaration (with layout docs) and its `Payload` impl.
pub fn emit_structs(p: &Protocol) -> TokenStream {
    let statics = check_statics(p);
    let items = p.structs.iter().map(|s| {
        let def = payload_def(p, s);
        let name = &def.name;
        let doc = doc_attrs(&struct_doc(p, s));
        let mut fields = Vec::new();
        let mut all_small = true;
        let mut eq = true;
        let mut undocumented = false;
        for (pf, f) in def.fields.iter().zip(&s.fields) {
            let unit = if f.unit.is_empty() {
                String::new()
            } else {
                format!(" Unit: {}.", f.unit)
            };
            match &pf.kind {
                PKind::Pad(_) | PKind::Check { .. } => {}
                PKind::Bits { members, .. } => {
                    let FieldKind::Bits {
                        members: ir_members,
                        ..
                    } = &f.kind
                    else {
                        continue;
                    };
                    for (m, im) in members.iter().zip(ir_members) {
                        let ty = match &m.ty {
                            BitType::Bool => quote!(bool),
                            BitType::Uint(p) => prim_type(*p),
                            BitType::Enum(t, _) => t.clone(),
                        };
                        let text = format!(
                            "{}{}(bits {}..{} of byte {}.)",
                            im.doc,
                            if im.doc.is_empty() { "" } else { " " },
                            im.shift,
                            im.shift + im.width,
                            f.offset
                        );
                        let d = doc_attrs(&text);
                        let id = &m.ident;
                        fields.push(quote!(#d pub #id: #ty));
                    }
                }
                kind => {
                    if let Some(n) = match kind {
                        PKind::Scalar { count, .. }
                        | PKind::Nested { count, .. }
                        | PKind::Enum { count, .. } => *count,
                        PKind::Packed { count, .. } => Some(*count),
                        _ => None,
                    } {
                        all_small &= n <= 32;
                    }
                    // Text is a nested payload of the runtime's, and `Eq`.
                    let text = matches!(
                        &f.kind,
                        FieldKind::Value {
                            ty: ValueType::Text(_),
                            ..
                        }
                    );
                    eq &= text || kind_is_eq(kind);
                    let id = pf
                        .ident
                        .clone()
                        .unwrap_or_else(|| format_ident!("_unnamed"));
                    let ty = field_type(kind);
                    // A field the spec says nothing of has no doc line: the struct's wire
                    // table names it (and gives its unit, which the doc repeats at the field).
                    let text = format!("{}{}", f.doc, unit);
                    undocumented |= text.is_empty();
                    let d = doc_attrs(text.trim_start());
                    fields.push(quote!(#d pub #id: #ty));
                }
            }
        }
        let default = if all_small {
            quote!(Default,)
        } else {
            quote!()
        };
        let eq = if eq { quote!(Eq, Hash,) } else { quote!() };
        // A struct whose sized bytes take their size from the struct that repeats it is read
        // and written by that struct's code: it has no wire form of its own.
        let imp = if s.context.is_empty() {
            emit_payload_impl(&def, &super::rt())
        } else {
            quote!()
        };
        let allow = if undocumented {
            quote!(#[allow(missing_docs)])
        } else {
            quote!()
        };
        quote! {
            #doc
            #allow
            #[derive(Debug, Clone, Copy, PartialEq, #eq #default)]
            pub struct #name {
                #(#fields,)*
            }
            #imp
        }
    });
    quote!(#statics #(#items)*)
}

/// Whether a field's Rust type is `Eq` and `Hash` (no floats, no nested payloads or groups).
fn kind_is_eq(kind: &PKind) -> bool {
    match kind {
        PKind::Scalar { scalar, scale, .. } => !scalar.prim.is_float() && scale.is_none(),
        PKind::Packed { scale, .. } => scale.is_none(),
        PKind::Nested { .. } | PKind::Group { .. } => false,
        PKind::Array { elem, .. } => kind_is_eq(elem),
        PKind::Optional(inner) => kind_is_eq(inner),
        PKind::Pad(_)
        | PKind::Enum { .. }
        | PKind::Bytes { .. }
        | PKind::Bits { .. }
        | PKind::Var { .. }
        | PKind::Check { .. } => true,
    }
}
