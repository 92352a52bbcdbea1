//! An optional value ([`FieldKind::Optional`](crate::ir::FieldKind::Optional)): present only
//! when bytes remain in the payload; an `Option` of the inner kind's type.

use proc_macro2::TokenStream;
use quote::quote;

use super::{Kind, size_sum};

/// The inner kind, present or not.
pub(super) struct Optional<'a>(pub(super) Box<dyn Kind + 'a>);

impl Kind for Optional<'_> {
    fn elem_type(&self) -> TokenStream {
        let t = self.0.field_type();
        quote!(::core::option::Option<#t>)
    }

    fn is_eq(&self) -> bool {
        self.0.is_eq()
    }

    fn fixed_size(&self) -> usize {
        self.0.fixed_size()
    }

    fn variable_len(&self, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
        let inner = &*self.0;
        let size = inner
            .variable_len(quote!(v), rt)
            .unwrap_or_else(|| size_sum([inner], rt));
        Some(quote!(match &#value { #rt::Some(v) => #size, #rt::None => 0 }))
    }

    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let read = self.0.read(&quote!(r), rt);
        quote!(if #rt::more(r) { #rt::Some(#read) } else { #rt::None })
    }

    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        let w = self.0.write(quote!((*v)), owner, rt);
        quote!(if let #rt::Some(v) = &#value { #w })
    }

    fn needs_locals(&self) -> bool {
        self.0.needs_locals()
    }

    fn value_can_fail(&self) -> bool {
        self.0.value_can_fail()
    }
}
