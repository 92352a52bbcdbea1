//! An array of values ([`FieldKind::Array`](crate::ir::FieldKind::Array)): the runtime's
//! `Group<T, max>` of primitives or enums, as many as the payload has left or as an earlier
//! integer field says.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::Kind;
use super::value::Value;
use crate::codegen::payload::scalar::local;
use crate::codegen::{ident, rt as type_rt};
use crate::ir::{Protocol, ValueType};

/// Up to `max` elements of `elem`, counted by the field `size_from` or by the payload's end.
pub(super) struct Array<'a> {
    elem: Value<'a>,
    max: usize,
    size_from: Option<Ident>,
    /// `size_from` is a mask: one element per set bit.
    by_mask: bool,
    elem_size: usize,
}

impl<'a> Array<'a> {
    pub(super) fn new(
        p: &'a Protocol,
        ty: &'a ValueType,
        max: usize,
        size_from: &Option<String>,
        by_mask: bool,
        size: usize,
    ) -> Array<'a> {
        Array {
            elem: Value::new(p, ty, None),
            max,
            size_from: size_from.as_deref().map(ident),
            by_mask,
            elem_size: size / max,
        }
    }
}

impl Array<'_> {
    /// The number of elements the size field's value `value` states: the value, or the
    /// number of its set bits for a mask.
    fn stated(&self, value: TokenStream, rt: &TokenStream) -> TokenStream {
        if self.by_mask {
            quote!(#rt::mask_count(#value as u64))
        } else {
            quote!(#value as u64)
        }
    }
}

impl Kind for Array<'_> {
    fn elem_type(&self) -> TokenStream {
        let rt = type_rt();
        let (t, max) = (self.elem.field_type(), self.max);
        quote!(#rt::Group<#t, #max>)
    }

    fn is_eq(&self) -> bool {
        self.elem.is_eq()
    }

    fn fixed_size(&self) -> usize {
        self.max * self.elem_size
    }

    fn variable_len(&self, value: TokenStream, _rt: &TokenStream) -> Option<TokenStream> {
        let elem_size = self.elem_size;
        Some(quote!(#value.len().saturating_mul(#elem_size)))
    }

    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let (ty, max) = (self.elem_type(), self.max);
        let read = self.elem.read_elem(&quote!(r), rt);
        match &self.size_from {
            None => quote! {{
                let mut a = <#ty>::new();
                while #rt::more(r) {
                    let e = #read;
                    let size = <Self as #rt::Payload>::SIZE;
                    a.push(e).map_err(|_| #rt::group_full(r, size))?;
                }
                a
            }},
            Some(n) => {
                let var = local(n);
                let stated = self.stated(quote!(#var), rt);
                quote! {{
                    let n = #rt::array_len(#stated, #max)?;
                    let mut a = <#ty>::new();
                    for _ in 0..n {
                        a.push(#read).map_err(|_| #rt::DecodeError::SizeMismatch { place: #rt::Place::NONE })?;
                    }
                    a
                }}
            }
        }
    }

    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        let w1 = self.elem.write_elem(quote!(*e), rt);
        let stated = self.size_from.as_ref().map(|n| {
            let stated = self.stated(quote!(#owner.#n), rt);
            quote!(#rt::check_stated_len(#value.len(), #stated)?;)
        });
        quote!(#stated for e in #value.iter() { #w1 })
    }

    fn needs_locals(&self) -> bool {
        self.size_from.is_some()
    }

    fn value_can_fail(&self) -> bool {
        true
    }
}
