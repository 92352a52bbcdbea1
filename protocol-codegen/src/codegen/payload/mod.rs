//! The one payload code generator: `impl Payload` (wire read and write) for a struct described
//! as a `PayloadDef`, which `payload_def` makes of an IR struct. A spec's structs and a
//! `#[derive(Payload)]` struct reach it through the same validation and the same IR, so both
//! produce the same code for the same layout.
//!
//! Its parts: one module per field kind (`kinds`, the only place that matches on the IR's
//! field kind), one value on the wire (`scalar`), and the statements of a struct's `write` and
//! `read` (`body`).

mod body;
pub(crate) mod kinds;
mod scalar;

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use crate::codegen::ident;
use crate::ir::{Protocol, Struct};
use body::Body;
use kinds::{Slot, size_sum, slots};
pub use scalar::{prim_type, read_scalar, write_scalar};
pub(crate) use scalar::{suffix, to_physical};

/// A struct as the payload generator sees it.
pub(crate) struct PayloadDef<'a> {
    /// The struct's name.
    pub(crate) name: Ident,
    /// Fields in wire order (generic structs are not supported: payloads are plain data).
    pub(crate) fields: Vec<Slot<'a>>,
    /// The wire size when the caller knows it (spec structs); otherwise it is computed as a
    /// const expression over the fields (derive, whose nested types are opaque).
    pub(crate) size: Option<usize>,
    /// The smallest wire size, for structs whose size varies (spec structs).
    pub(crate) min_size: Option<usize>,
}

/// An IR struct as the payload generator sees it.
pub(crate) fn payload_def<'a>(p: &'a Protocol, s: &'a Struct) -> PayloadDef<'a> {
    PayloadDef {
        name: ident(&s.name),
        fields: slots(p, s),
        size: Some(s.size),
        min_size: Some(s.min_size),
    }
}

/// `const MIN_SIZE` and `fn wire_len` of a struct with fields of variable size (nothing for
/// a struct of fixed size); `None` when the struct has a fixed size.
fn emit_variable_size(def: &PayloadDef, rt: &TokenStream) -> Option<TokenStream> {
    let mut fixed = Vec::new();
    let mut lens = Vec::new();
    for f in &def.fields {
        match (f.kind.variable_len(quote!(x), rt), &f.ident) {
            (Some(_), Some(id)) => lens.extend(f.kind.variable_len(quote!(self.#id), rt)),
            _ => fixed.push(&*f.kind),
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
pub(crate) fn emit_payload_impl(def: &PayloadDef, rt: &TokenStream) -> TokenStream {
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
        None => size_sum(def.fields.iter().map(|f| &*f.kind), rt),
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
/// enum: each kind answers in [`Kind::short_only`](kinds::Kind::short_only)) or has a variable
/// size; else the conditions on nested types, all of which must hold. Checked against reading
/// field by field on every bundled spec's structs (`tests/tests/it/payload_length_first.rs`).
fn needs_only_bytes(fields: &[Slot<'_>], rt: &TokenStream) -> Option<Vec<TokenStream>> {
    let mut nested = Vec::new();
    for f in fields {
        // Once per nested type.
        if let Some(condition) = f.kind.short_only(rt)? {
            if !nested
                .iter()
                .any(|c: &TokenStream| c.to_string() == condition.to_string())
            {
                nested.push(condition);
            }
        }
    }
    Some(nested)
}
