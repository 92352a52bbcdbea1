//! A value a mask bit announces ([`FieldKind::When`](crate::ir::FieldKind::When)): present
//! when bit `bit` of the earlier field `mask` is set; an `Option` of the inner kind's type.
//! Encoding refuses a value whose presence disagrees with the bit (the runtime's
//! `field::check_mask_bit`): the mask is the application's field, never rewritten.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{Kind, size_sum};
use crate::codegen::ident;
use crate::codegen::payload::scalar::local;

/// The inner kind, present when the mask's bit is set.
pub(super) struct When<'a> {
    pub(super) inner: Box<dyn Kind + 'a>,
    pub(super) mask: Ident,
    pub(super) bit: u32,
}

impl<'a> When<'a> {
    pub(super) fn new(inner: Box<dyn Kind + 'a>, mask: &str, bit: u32) -> When<'a> {
        When {
            inner,
            mask: ident(mask),
            bit,
        }
    }
}

impl Kind for When<'_> {
    fn elem_type(&self) -> TokenStream {
        let t = self.inner.field_type();
        quote!(::core::option::Option<#t>)
    }

    fn is_eq(&self) -> bool {
        self.inner.is_eq()
    }

    fn fixed_size(&self) -> usize {
        self.inner.fixed_size()
    }

    fn variable_len(&self, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
        let size = size_sum([&*self.inner], rt);
        Some(quote!(match &#value { #rt::Some(_) => #size, #rt::None => 0 }))
    }

    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let read = self.inner.read(&quote!(r), rt);
        let (mask, bit) = (local(&self.mask), self.bit);
        quote!(if #rt::mask_bit(#mask as u64, #bit) { #rt::Some(#read) } else { #rt::None })
    }

    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        let w = self.inner.write(quote!((*v)), owner, rt);
        let (mask, bit) = (&self.mask, self.bit);
        quote! {
            #rt::check_mask_bit(#rt::Option::is_some(&#value), #owner.#mask as u64, #bit)?;
            if let #rt::Some(v) = &#value { #w }
        }
    }

    fn needs_locals(&self) -> bool {
        true
    }

    fn value_can_fail(&self) -> bool {
        true
    }
}
