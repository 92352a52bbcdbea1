//! A value ([`FieldKind::Value`](crate::ir::FieldKind::Value)), or a fixed array of them: a
//! primitive (scaled or not), a nested struct, an enum over its wire integer, or NUL-padded
//! text (the runtime's `FixedStr<N>`, a nested payload). Also the element of an array field.

use proc_macro2::TokenStream;
use quote::quote;

use super::{Kind, named_type};
use crate::codegen::payload::scalar::{
    prim_type, read_scalar_from, to_physical, to_raw, to_raw_float, write_scalar,
};
use crate::codegen::rt as type_rt;
use crate::ir::{Protocol, ValueType};

/// A value of type `ty`, or `count` of them.
pub(super) struct Value<'a> {
    p: &'a Protocol,
    ty: &'a ValueType,
    count: Option<usize>,
}

impl<'a> Value<'a> {
    pub(super) fn new(p: &'a Protocol, ty: &'a ValueType, count: Option<usize>) -> Value<'a> {
        Value { p, ty, count }
    }

    /// The Rust type of a nested payload (a struct or text), `None` for a primitive or enum.
    fn nested(&self) -> Option<TokenStream> {
        match self.ty {
            ValueType::Struct(i) => Some(named_type(
                &self.p.structs[*i].name,
                self.p.structs[*i].foreign,
            )),
            ValueType::Text(n) => {
                let rt = type_rt();
                Some(quote!(#rt::FixedStr<#n>))
            }
            ValueType::Scalar { .. } | ValueType::Enum(..) => None,
        }
    }

    /// Reading one element from `reader`. The field rules are the runtime's (`field`),
    /// called with the field's constants; whatever can fail here other than for want of
    /// bytes (clamped scales, enums) makes [`Kind::short_only`] answer `None`.
    pub(super) fn read_elem(&self, reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        match self.ty {
            ValueType::Scalar {
                scalar,
                scale: None,
            } => read_scalar_from(reader, *scalar),
            ValueType::Scalar {
                scalar,
                scale: Some(sc),
            } => to_physical(read_scalar_from(reader, *scalar), scalar.prim, sc, rt),
            ValueType::Enum(i, scalar) => {
                let ty = named_type(&self.p.enums[*i].name, self.p.enums[*i].foreign);
                let raw = read_scalar_from(reader, *scalar);
                quote!(#ty::from_raw(#raw)?)
            }
            ValueType::Struct(_) | ValueType::Text(_) => {
                let ty = self.nested();
                quote!(<#ty as #rt::Payload>::read(#reader)?)
            }
        }
    }

    /// Writing one element `value` (an expression of the element type). A scaled value is
    /// clamped (if its field clamps), quantized and fitted to its raw type by the runtime: a
    /// value the raw type cannot hold is an error.
    pub(super) fn write_elem(&self, value: TokenStream, rt: &TokenStream) -> TokenStream {
        match self.ty {
            ValueType::Scalar {
                scalar,
                scale: None,
            } => write_scalar(*scalar, value),
            ValueType::Scalar {
                scalar,
                scale: Some(sc),
            } if scalar.prim.is_float() => {
                write_scalar(*scalar, to_raw_float(value, sc, scalar.prim, rt))
            }
            ValueType::Scalar {
                scalar,
                scale: Some(sc),
            } => write_scalar(*scalar, to_raw(value, sc, None, rt)),
            ValueType::Enum(i, scalar) => {
                let ty = named_type(&self.p.enums[*i].name, self.p.enums[*i].foreign);
                write_scalar(
                    *scalar,
                    quote!(#rt::enum_raw(#value, #ty::to_raw, #ty::from_raw)?),
                )
            }
            ValueType::Struct(_) | ValueType::Text(_) => {
                let ty = self.nested();
                quote!(<#ty as #rt::Payload>::write(&#value, w)?;)
            }
        }
    }
}

/// `Ok(read)`, the value of a closure that reads: `read` without its final `?` when it has
/// one (`Ok(x?)` is `x`).
pub(crate) fn ok_of(read: TokenStream, rt: &TokenStream) -> TokenStream {
    let mut tokens: Vec<proc_macro2::TokenTree> = read.clone().into_iter().collect();
    match tokens.last() {
        Some(proc_macro2::TokenTree::Punct(p)) if p.as_char() == '?' => {
            tokens.pop();
            tokens.into_iter().collect()
        }
        _ => quote!(#rt::Ok(#read)),
    }
}

impl Kind for Value<'_> {
    fn elem_type(&self) -> TokenStream {
        match self.ty {
            ValueType::Scalar {
                scale: Some(sc), ..
            } => prim_type(sc.physical),
            ValueType::Scalar { scalar, .. } => prim_type(scalar.prim),
            ValueType::Enum(i, _) => named_type(&self.p.enums[*i].name, self.p.enums[*i].foreign),
            ValueType::Struct(_) | ValueType::Text(_) => self.nested().unwrap_or_default(),
        }
    }

    fn count(&self) -> Option<usize> {
        self.count
    }

    fn is_eq(&self) -> bool {
        match self.ty {
            ValueType::Scalar { scalar, scale } => !scalar.prim.is_float() && scale.is_none(),
            // Text is a nested payload of the runtime's, and `Eq`.
            ValueType::Enum(..) | ValueType::Text(_) => true,
            ValueType::Struct(_) => false,
        }
    }

    fn size_parts(&self, rt: &TokenStream) -> (usize, Option<TokenStream>) {
        match (self.nested(), self.count) {
            (Some(ty), None) => (0, Some(quote!(<#ty as #rt::Payload>::SIZE))),
            (Some(ty), Some(n)) => (0, Some(quote!(<#ty as #rt::Payload>::SIZE * #n))),
            (None, _) => (self.fixed_size(), None),
        }
    }

    // A nested payload is sized by its own impl; only spec structs ask, whose nested structs
    // are fixed and whose size the IR knows.
    fn fixed_size(&self) -> usize {
        match self.ty {
            ValueType::Scalar { scalar, .. } | ValueType::Enum(_, scalar) => {
                scalar.prim.size() * self.count.unwrap_or(1)
            }
            ValueType::Struct(_) | ValueType::Text(_) => 0,
        }
    }

    fn read(&self, reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        match self.count {
            None => self.read_elem(reader, rt),
            Some(_) => {
                let read = ok_of(self.read_elem(&quote!(r), rt), rt);
                quote!(r.array(|r| #read)?)
            }
        }
    }

    fn write(&self, value: TokenStream, _owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        match self.count {
            None => self.write_elem(value, rt),
            Some(_) => {
                let w1 = self.write_elem(quote!(*e), rt);
                quote!(for e in #value.iter() { #w1 })
            }
        }
    }

    fn short_only(&self, rt: &TokenStream) -> Option<Option<TokenStream>> {
        match self.ty {
            ValueType::Scalar { scale, .. } if scale.as_ref().is_none_or(|s| s.clamp.is_none()) => {
                Some(None)
            }
            ValueType::Struct(_) | ValueType::Text(_) => {
                let ty = self.nested();
                Some(Some(quote!(<#ty as #rt::Payload>::READ_NEEDS_ONLY_BYTES)))
            }
            ValueType::Scalar { .. } | ValueType::Enum(..) => None,
        }
    }

    fn folds_pad(&self) -> bool {
        self.count.is_none()
    }

    /// An enum (its raw value may have no variant), a value scaled to an integer (clamped,
    /// quantized and fitted to its raw type) or a value narrower on the wire than in Rust
    /// (range-checked: a 24-, 40-, 48- or 56-bit integer, a half); a nested payload names its
    /// own fields.
    fn value_can_fail(&self) -> bool {
        match self.ty {
            ValueType::Scalar { scalar, scale } => {
                (scale.is_some() && !scalar.prim.is_float()) || scalar.prim.is_narrow()
            }
            ValueType::Enum(..) => true,
            ValueType::Struct(_) | ValueType::Text(_) => false,
        }
    }
}
