//! The one payload code generator: `impl Payload` (wire read and write) for a struct described
//! as a [`PayloadDef`], which `types::payload_def` makes of an IR struct. A spec's structs and a
//! `#[derive(Payload)]` struct reach it through the same validation and the same IR, so both
//! produce the same code for the same layout.
//!
//! Its parts: what it reads (`def`), one value on the wire (`scalar`), one field (`field`),
//! and the statements of a struct's `write` and `read` (`body`).

mod body;
mod def;
mod field;
mod scalar;

use proc_macro2::TokenStream;
use quote::quote;

use body::Body;
pub use def::{BitType, PBit, PField, PKind, PayloadDef};
pub use field::{elem_type, field_type};
use field::{size_sum, variable_len};
pub use scalar::{prim_type, read_scalar, write_scalar};

/// `const MIN_SIZE` and `fn wire_len` of a struct with fields of variable size (nothing for
/// a struct of fixed size); `None` when the struct has a fixed size.
fn emit_variable_size(def: &PayloadDef, rt: &TokenStream) -> Option<TokenStream> {
    let mut fixed = Vec::new();
    let mut lens = Vec::new();
    for f in &def.fields {
        match (variable_len(&f.kind, quote!(x), rt), &f.ident) {
            (Some(_), Some(id)) => lens.extend(variable_len(&f.kind, quote!(self.#id), rt)),
            _ => fixed.push(&f.kind),
        }
    }
    if lens.is_empty() {
        return None;
    }
    let fixed = size_sum(fixed, rt);
    let min = match def.min_size {
        Some(n) => quote!(#n),
        None => fixed.clone(),
    };
    Some(quote! {
        const MIN_SIZE: usize = #min;
        #[inline]
        fn wire_len(&self) -> usize {
            const FIXED: usize = #fixed;
            FIXED #(.saturating_add(#lens))*
        }
    })
}

/// `impl Payload for NAME`: SIZE, write and read, fields in wire order. `rt` is the path of the
/// runtime's `__private` module as the impl sees it.
pub fn emit_payload_impl(def: &PayloadDef, rt: &TokenStream) -> TokenStream {
    let name = &def.name;
    let Body {
        writes,
        reads,
        inits,
        after,
        ..
    } = Body::of(&def.fields, &def.name.to_string(), rt);
    // Padding after the last field is skipped once the value is built.
    let value = if after.is_empty() {
        quote!(#rt::Ok(Self { #(#inits),* }))
    } else {
        quote! {
            let value = Self { #(#inits),* };
            #(#after)*
            #rt::Ok(value)
        }
    };
    let size = match def.size {
        Some(n) => quote!(#n),
        None => size_sum(def.fields.iter().map(|f| &f.kind), rt),
    };
    let variable = emit_variable_size(def, rt);
    // A value of fixed size: its room checked once, not per field.
    let reserve = if variable.is_none() && !writes.is_empty() {
        quote!(let w = &mut w.reserve(<Self as #rt::Payload>::SIZE)?;)
    } else {
        quote!()
    };
    let only_bytes = match variable {
        None => needs_only_bytes(&def.fields, rt),
        Some(_) => None,
    };
    let only_bytes = only_bytes.map(|parts| {
        let parts = if parts.is_empty() {
            vec![quote!(true)]
        } else {
            parts
        };
        quote!(const READ_NEEDS_ONLY_BYTES: bool = #(#parts)&&*;)
    });
    quote! {
        impl #rt::Payload for #name {
            const SIZE: usize = #size;
            #variable
            #only_bytes
            #[inline]
            fn write(&self, w: &mut #rt::Writer<'_>) -> #rt::EncodeResult {
                #reserve
                #(#writes)*
                #rt::Ok(())
            }
            #[inline]
            fn read(r: &mut #rt::Reader<'_>) -> #rt::DecodeResult<Self> {
                #(#reads)*
                #value
            }
        }
    }
}

/// Whether reading `fields` can fail only for want of bytes (`Payload::READ_NEEDS_ONLY_BYTES`):
/// `None` if some field can fail otherwise (an enum, a clamped value, a bit member that is an
/// enum: the failures [`read_elem`] and the bit members' reads emit) or has a variable size;
/// else the conditions on nested types, all of which must hold. Checked against reading field
/// by field on every bundled spec's structs (`tests/tests/payload_length_first.rs`).
fn needs_only_bytes(fields: &[PField], rt: &TokenStream) -> Option<Vec<TokenStream>> {
    let mut nested = Vec::new();
    for f in fields {
        match &f.kind {
            PKind::Pad(_) => {}
            PKind::Scalar { scale, .. } if scale.as_ref().is_none_or(|s| s.clamp.is_none()) => {}
            PKind::Nested { ty, .. } => {
                let condition = quote!(<#ty as #rt::Payload>::READ_NEEDS_ONLY_BYTES);
                // Once per nested type.
                if !nested
                    .iter()
                    .any(|c: &TokenStream| c.to_string() == condition.to_string())
                {
                    nested.push(condition);
                }
            }
            PKind::Bits { members, .. }
                if members.iter().all(|m| !matches!(m.ty, BitType::Enum(..))) => {}
            PKind::Packed { scale, .. } if scale.as_ref().is_none_or(|s| s.clamp.is_none()) => {}
            _ => return None,
        }
    }
    Some(nested)
}
