//! A check inside a payload ([`FieldKind::Check`](crate::ir::FieldKind::Check)): a check value
//! over the fields `first..=last` of the struct, verified on read and computed on write by the
//! runtime (`verify_check`, `put_check`); no field of the Rust struct.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{Decl, Kind, Slot};
use crate::codegen::frame::algorithm_expr;
use crate::codegen::payload::body::Body;
use crate::codegen::rt as type_rt;
use crate::ir::{ByteOrder, Field, PayloadCheck};

/// The check and the bytes of its stored value.
pub(super) struct Check<'a> {
    pub(super) check: &'a PayloadCheck,
    pub(super) size: usize,
}

impl Kind for Check<'_> {
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

    fn covers(&self) -> Option<(usize, usize)> {
        Some((self.check.first, self.check.last))
    }

    /// Verified and computed where it stands, over the positions its covered fields start
    /// and end at (`Body::check_starts`, `Body::check_ends`).
    fn body(&self, b: &mut Body, i: usize, _slots: &[Slot<'_>], rt: &TokenStream) {
        let c = self.check;
        // Its table's `static` is printed once, by `check_statics`.
        let checksum = algorithm_expr(&type_rt(), "", &c.algorithm, &c.naming, &mut Vec::new());
        let (start, end) = (
            format_ident!("check{i}_start"),
            format_ident!("check{i}_end"),
        );
        let order = match c.endian {
            ByteOrder::Little => quote!(#rt::ByteOrder::Little),
            ByteOrder::Big => quote!(#rt::ByteOrder::Big),
        };
        b.reads
            .push(quote!(#rt::verify_check(r, &#start, #end, &#checksum, #order)?;));
        b.writes
            .push(quote!(#rt::put_check(w, #start, #end, &#checksum, #order)?;));
    }

    fn own_code(&self) -> bool {
        true
    }

    fn declare(&self, _f: &Field, _id: Option<&Ident>, _d: &mut Decl) {}
}
