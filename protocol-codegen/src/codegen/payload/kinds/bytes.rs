//! Bytes ([`FieldKind::Bytes`](crate::ir::FieldKind::Bytes)): the runtime's `Bytes<max>`, or
//! `Str<max>` for text without a terminator, every byte left in the payload (but the checks
//! after it) or as many as an earlier field states.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{Kind, Slot};
use crate::codegen::payload::body::Body;
use crate::codegen::payload::scalar::local;
use crate::codegen::{ident, rt as type_rt};

/// Bytes of at most `max`, sized by the field `size_from` or by the end of the payload.
pub(super) struct Bytes {
    max: usize,
    size_from: Option<Ident>,
    text: bool,
}

impl Bytes {
    pub(super) fn new(max: usize, size_from: &Option<String>, text: bool) -> Bytes {
        Bytes {
            max,
            size_from: size_from.as_deref().map(ident),
            text,
        }
    }

    fn ty(&self) -> TokenStream {
        let rt = type_rt();
        let max = self.max;
        if self.text {
            quote!(#rt::Str<#max>)
        } else {
            quote!(#rt::Bytes<#max>)
        }
    }
}

impl Kind for Bytes {
    fn elem_type(&self) -> TokenStream {
        self.ty()
    }

    fn is_eq(&self) -> bool {
        true
    }

    fn fixed_size(&self) -> usize {
        self.max
    }

    fn variable_len(&self, value: TokenStream, _rt: &TokenStream) -> Option<TokenStream> {
        Some(quote!(#value.len()))
    }

    fn read(&self, _reader: &TokenStream, _rt: &TokenStream) -> TokenStream {
        let ty = self.ty();
        match &self.size_from {
            None => quote!(<#ty>::read_rest(r)?),
            Some(n) => {
                let var = local(n);
                quote!(<#ty>::read_sized(r, #var as u64)?)
            }
        }
    }

    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        match &self.size_from {
            None => quote!(#value.write(w)?;),
            Some(n) => quote! {
                #rt::check_stated_len(#value.len(), #owner.#n as u64)?;
                #value.write(w)?;
            },
        }
    }

    fn needs_locals(&self) -> bool {
        self.size_from.is_some()
    }

    fn body(&self, b: &mut Body, i: usize, slots: &[Slot<'_>], rt: &TokenStream) {
        let Some(id) = &slots[i].ident else { return };
        if self.size_from.is_some() || i + 1 == slots.len() {
            b.value(self, id, rt);
            return;
        }
        // Every byte left but the checks after it.
        let keep: usize = slots[i + 1..].iter().map(|s| s.kind.fixed_size()).sum();
        let ty = self.ty();
        b.writes.push(quote!(self.#id.write(w)?;));
        let var = local(id);
        b.reads
            .push(quote!(let #var = <#ty>::read_rest_but(r, #keep)?;));
        b.inits.push(quote!(#id: #var));
    }

    /// A stated size the bytes must match.
    fn value_can_fail(&self) -> bool {
        self.size_from.is_some()
    }
}
