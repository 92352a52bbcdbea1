//! A bit-packed array ([`FieldKind::Packed`](crate::ir::FieldKind::Packed)): `count` unsigned
//! integers of `bits` bits back to back (the runtime's `packed`), read and written as `size`
//! bytes; an array of the raw type, or of the physical type with a scale.

use proc_macro2::TokenStream;
use quote::quote;

use super::Kind;
use crate::codegen::payload::scalar::{prim_type, to_physical, to_raw};
use crate::ir::{BitOrder, Prim, Scale};

/// `count` elements of `bits` bits in `size` bytes.
pub(super) struct Packed {
    pub(super) count: usize,
    pub(super) bits: u32,
    pub(super) order: BitOrder,
    pub(super) prim: Prim,
    pub(super) scale: Option<Scale>,
    pub(super) size: usize,
}

/// The runtime's name of a bit order.
fn bit_order(rt: &TokenStream, order: BitOrder) -> TokenStream {
    match order {
        BitOrder::LsbFirst => quote!(#rt::BitOrder::LsbFirst),
        BitOrder::MsbFirst => quote!(#rt::BitOrder::MsbFirst),
    }
}

impl Kind for Packed {
    fn elem_type(&self) -> TokenStream {
        match &self.scale {
            Some(sc) => prim_type(sc.physical),
            None => prim_type(self.prim),
        }
    }

    fn count(&self) -> Option<usize> {
        Some(self.count)
    }

    fn is_eq(&self) -> bool {
        self.scale.is_none()
    }

    fn fixed_size(&self) -> usize {
        self.size
    }

    /// Its bytes at once, then each element from them.
    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let (bits, count, size) = (self.bits, self.count, self.size);
        let order = bit_order(rt, self.order);
        let raw = quote!(#rt::get_packed(bytes, i, #bits, #order));
        let (t, elem) = match &self.scale {
            None => {
                let t = prim_type(self.prim);
                (t.clone(), quote!(#raw as #t))
            }
            Some(sc) => (prim_type(sc.physical), to_physical(raw, Prim::U64, sc, rt)),
        };
        quote! {{
            let bytes = r.take(#size)?;
            let mut a: [#t; #count] = [<#t as ::core::default::Default>::default(); #count];
            for (i, e) in a.iter_mut().enumerate() { *e = #elem; }
            a
        }}
    }

    /// Each element into its bits of a zeroed run of bytes, then the run.
    fn write(&self, value: TokenStream, _owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        let (bits, size) = (self.bits, self.size);
        let order = bit_order(rt, self.order);
        let raw = match &self.scale {
            None => quote!(*e as u64),
            Some(sc) => {
                let raw = to_raw(quote!(*e), sc, Some(self.prim), rt);
                quote!(#raw as u64)
            }
        };
        quote! {{
            let mut bytes = [0u8; #size];
            for (i, e) in #value.iter().enumerate() {
                #rt::set_packed(&mut bytes, i, #bits, #order, #raw)?;
            }
            w.put_bytes(&bytes)?;
        }}
    }

    fn short_only(&self, _rt: &TokenStream) -> Option<Option<TokenStream>> {
        self.scale
            .as_ref()
            .is_none_or(|s| s.clamp.is_none())
            .then_some(None)
    }

    fn value_can_fail(&self) -> bool {
        true
    }
}
