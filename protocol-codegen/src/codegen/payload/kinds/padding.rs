//! Padding ([`FieldKind::Padding`](crate::ir::FieldKind::Padding)): bytes written as zero and
//! skipped when read; no field of the Rust struct.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::{Decl, Kind, Slot};
use crate::codegen::payload::body::Body;
use crate::ir::Field;

/// A run of padding bytes.
pub(super) struct Padding {
    pub(super) size: usize,
}

impl Kind for Padding {
    fn elem_type(&self) -> TokenStream {
        quote!(())
    }

    fn is_eq(&self) -> bool {
        true
    }

    fn fixed_size(&self) -> usize {
        self.size
    }

    fn read(&self, _reader: &TokenStream, _rt: &TokenStream) -> TokenStream {
        quote!(())
    }

    fn write(&self, _value: TokenStream, _owner: &TokenStream, _rt: &TokenStream) -> TokenStream {
        quote!()
    }

    fn short_only(&self, _rt: &TokenStream) -> Option<Option<TokenStream>> {
        Some(None)
    }

    fn padding(&self) -> Option<usize> {
        Some(self.size)
    }

    fn body(&self, b: &mut Body, _i: usize, _slots: &[Slot<'_>], _rt: &TokenStream) {
        let n = self.size;
        b.writes.push(quote!(w.zeros(#n)?;));
        b.reads.push(quote!(r.skip(#n)?;));
    }

    fn declare(&self, _f: &Field, _id: Option<&Ident>, _d: &mut Decl) {}
}
