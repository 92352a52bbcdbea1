//! Spec constants, address sets, enums and payload structs as Rust items. The structs' wire
//! code comes from the shared payload generator ([`super::payload`]).

use proc_macro2::{Literal, TokenStream};
use quote::quote;

use super::docs::{doc_attrs, struct_doc};
use super::frame::algorithm_expr;
use super::payload::kinds::Decl;
use super::payload::{emit_payload_impl, payload_def, prim_type};
use super::{const_ident, ident};
use crate::ir::{Enum, FieldKind, Prim, Protocol, UnknownPolicy};

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
        // Two's complement bits of the type's width, sign-extended.
        Prim::I40 | Prim::I48 | Prim::I56 => {
            let shift = 64 - prim.bits();
            Literal::i64_suffixed(((value << shift) as i64) >> shift)
        }
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

/// Every struct: declaration (with layout docs) and its `Payload` impl.
pub fn emit_structs(p: &Protocol) -> TokenStream {
    let statics = check_statics(p);
    let items = p.structs.iter().map(|s| {
        let def = payload_def(p, s);
        let name = &def.name;
        let doc = doc_attrs(&struct_doc(p, s));
        let mut decl = Decl::default();
        for (slot, f) in def.fields.iter().zip(&s.fields) {
            slot.kind.declare(f, slot.ident.as_ref(), &mut decl);
        }
        let Decl {
            fields,
            all_small,
            eq,
            undocumented,
        } = decl;
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
