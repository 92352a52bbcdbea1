//! NUL-terminated text ([`FieldKind::NulText`](crate::ir::FieldKind::NulText)): the runtime's
//! `NulStr<max>`, read, written and sized by its own `Payload` impl; fields may follow it.

use proc_macro2::TokenStream;
use quote::quote;

use super::Kind;
use crate::codegen::rt as type_rt;

/// Text of at most `max` bytes and its NUL.
pub(super) struct NulText {
    pub(super) max: usize,
}

impl NulText {
    fn ty(&self) -> TokenStream {
        let rt = type_rt();
        let max = self.max;
        quote!(#rt::NulStr<#max>)
    }
}

impl Kind for NulText {
    fn elem_type(&self) -> TokenStream {
        self.ty()
    }

    fn is_eq(&self) -> bool {
        true
    }

    fn size_parts(&self, rt: &TokenStream) -> (usize, Option<TokenStream>) {
        let ty = self.ty();
        (0, Some(quote!(<#ty as #rt::Payload>::SIZE)))
    }

    // Sized by its own impl; only spec structs ask, whose size the IR knows.
    fn fixed_size(&self) -> usize {
        0
    }

    fn variable_len(&self, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
        let ty = self.ty();
        Some(quote!(<#ty as #rt::Payload>::wire_len(&#value)))
    }

    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let ty = self.ty();
        quote!(<#ty as #rt::Payload>::read(r)?)
    }

    fn write(&self, value: TokenStream, _owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        let ty = self.ty();
        quote!(<#ty as #rt::Payload>::write(&#value, w)?;)
    }

    fn value_can_fail(&self) -> bool {
        true
    }
}
