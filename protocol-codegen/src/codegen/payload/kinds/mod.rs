//! One module per field kind of the IR ([`FieldKind`]), each owning everything the Rust printer
//! prints of that kind: its Rust type, its wire size, how it is read and written, and what it
//! declares in the struct. [`of`] is the one place that matches on the kind; the rest of the
//! printer asks the [`Kind`] it returns.

mod array;
mod bits;
mod bytes;
mod check;
mod group;
mod nul_text;
mod optional;
mod packed;
mod padding;
mod stream;
mod value;
mod when;

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::body::Body;
use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::ir::{Field, FieldKind, Protocol, Struct};
pub(crate) use value::ok_of;

/// What the Rust printer prints of one field kind. A kind answers only what it has: the
/// defaults are those of a kind that is not there (no array count, no variable size).
pub(crate) trait Kind {
    /// The Rust type of one element (the whole field's type when it has no count).
    fn elem_type(&self) -> TokenStream;

    /// The elements of a fixed array field.
    fn count(&self) -> Option<usize> {
        None
    }

    /// The Rust type of the whole field.
    fn field_type(&self) -> TokenStream {
        let t = self.elem_type();
        match self.count() {
            Some(n) => quote!([#t; #n]),
            None => t,
        }
    }

    /// Whether the field's Rust type is `Eq` and `Hash` (no floats, no nested payloads).
    fn is_eq(&self) -> bool;

    /// The wire size: the bytes known at expansion, and a term over a nested type's `SIZE`
    /// (opaque to the derive), if any.
    fn size_parts(&self, _rt: &TokenStream) -> (usize, Option<TokenStream>) {
        (self.fixed_size(), None)
    }

    /// The wire size of a field of fixed size (the largest, for one that varies).
    fn fixed_size(&self) -> usize;

    /// The wire size of the field's `value`, for a field whose size varies.
    fn variable_len(&self, _value: TokenStream, _rt: &TokenStream) -> Option<TokenStream> {
        None
    }

    /// An expression reading the whole field from `reader` (`r`, or `r.pad(n)?` after padding
    /// for a kind that [`folds_pad`](Kind::folds_pad)).
    fn read(&self, reader: &TokenStream, rt: &TokenStream) -> TokenStream;

    /// Statements writing the field's `value`; `owner` is the expression whose fields sized
    /// bytes take their size from (`self`).
    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream;

    /// Whether reading the field can fail only for want of bytes: `Some` of the conditions on
    /// nested types that must also hold, `None` when it can fail otherwise (an enum, a clamped
    /// value) or has a variable size.
    fn short_only(&self, _rt: &TokenStream) -> Option<Option<TokenStream>> {
        None
    }

    /// Whether reading the field names an earlier field (sized bytes; a group, whose elements'
    /// sized bytes may name the repeating struct's fields).
    fn needs_locals(&self) -> bool {
        false
    }

    /// Whether the padding before the field can be skipped by its read (it is read in one
    /// step: a single value, not an array, group or optional field).
    fn folds_pad(&self) -> bool {
        false
    }

    /// Whether reading or writing the field can fail for its value, not only for want of
    /// bytes or room (an enum without variant, a clamped or scaled value, a stated size, a
    /// 24-bit integer, text without its NUL): its code then names the field in the error.
    fn value_can_fail(&self) -> bool {
        false
    }

    /// Whether only the struct's own code reads and writes the field (a bit word, a check):
    /// a repeated struct holding one is read and written by its own `Payload` impl.
    fn own_code(&self) -> bool {
        false
    }

    /// The bytes of a padding run.
    fn padding(&self) -> Option<usize> {
        None
    }

    /// The first and last field a check covers.
    fn covers(&self) -> Option<(usize, usize)> {
        None
    }

    /// The statements of field `i` of `slots` in its struct's `write` and `read`.
    fn body(&self, b: &mut Body, i: usize, slots: &[Slot<'_>], rt: &TokenStream) {
        if let Some(id) = &slots[i].ident {
            b.value(self, id, rt);
        }
    }

    /// The fields of the Rust struct that this field declares.
    fn declare(&self, f: &Field, id: Option<&Ident>, d: &mut Decl) {
        if let Some(n) = self.count() {
            d.all_small &= n <= 32;
        }
        d.eq &= self.is_eq();
        let id = id.cloned().unwrap_or_else(|| format_ident!("_unnamed"));
        let ty = self.field_type();
        let unit = if f.unit.is_empty() {
            String::new()
        } else {
            format!(" Unit: {}.", f.unit)
        };
        // A field the spec says nothing of has no doc line: the struct's wire table names it
        // (and gives its unit, which the doc repeats at the field).
        let text = format!("{}{}", f.doc, unit);
        d.undocumented |= text.is_empty();
        let doc = doc_attrs(text.trim_start());
        d.fields.push(quote!(#doc pub #id: #ty));
    }
}

/// The one match on the IR's field kind: the printer of `kind`, a field of `size` bytes.
pub(crate) fn of<'a>(p: &'a Protocol, kind: &'a FieldKind, size: usize) -> Box<dyn Kind + 'a> {
    match kind {
        FieldKind::Padding => Box::new(padding::Padding { size }),
        FieldKind::Value { ty, count } => Box::new(value::Value::new(p, ty, *count)),
        FieldKind::Bytes {
            max,
            size_from,
            text,
        } => Box::new(bytes::Bytes::new(*max, size_from, *text)),
        FieldKind::Group { elem, max } => Box::new(group::Group::new(p, *elem, *max)),
        FieldKind::Packed {
            count,
            bits,
            order,
            prim,
            scale,
        } => Box::new(packed::Packed {
            count: *count,
            bits: *bits,
            order: *order,
            prim: *prim,
            scale: *scale,
            size,
        }),
        FieldKind::Optional(inner) => Box::new(optional::Optional(of(p, inner, size))),
        FieldKind::When { kind, mask, bit } => {
            Box::new(when::When::new(of(p, kind, size), mask, *bit))
        }
        FieldKind::Bits { word, members } => Box::new(bits::Bits::new(p, *word, members)),
        FieldKind::BitStream { members } => Box::new(stream::Stream { p, members, size }),
        FieldKind::Array {
            ty,
            max,
            size_from,
            by_mask,
        } => Box::new(array::Array::new(p, ty, *max, size_from, *by_mask, size)),
        FieldKind::NulText { max } => Box::new(nul_text::NulText { max: *max }),
        FieldKind::Check(c) => Box::new(check::Check { check: c, size }),
    }
}

/// One field of a struct in wire order, as the payload printer sees it.
pub struct Slot<'a> {
    /// The field of the Rust struct (`None` for padding and checks).
    pub ident: Option<Ident>,
    /// Its kind's printer.
    pub kind: Box<dyn Kind + 'a>,
}

/// The fields of `s` in wire order.
pub fn slots<'a>(p: &'a Protocol, s: &'a Struct) -> Vec<Slot<'a>> {
    s.fields
        .iter()
        .map(|f| Slot {
            ident: (!f.name.is_empty() && !matches!(f.kind, FieldKind::Check(_)))
                .then(|| ident(&f.name)),
            kind: of(p, &f.kind, f.size),
        })
        .collect()
}

/// What a struct's fields declare: the Rust fields and what the struct may derive.
pub struct Decl {
    /// `doc pub name: Type` per Rust field.
    pub fields: Vec<TokenStream>,
    /// Every array has at most 32 elements (`Default` is derived).
    pub all_small: bool,
    /// Every field is `Eq` and `Hash`.
    pub eq: bool,
    /// Some field has no doc line.
    pub undocumented: bool,
}

impl Default for Decl {
    fn default() -> Self {
        Decl {
            fields: Vec::new(),
            all_small: true,
            eq: true,
            undocumented: false,
        }
    }
}

/// The wire size of `kinds` together, as a constant expression: the bytes known at expansion
/// summed into one literal, then the nested types' sizes.
pub(crate) fn size_sum<'k>(
    kinds: impl IntoIterator<Item = &'k (dyn Kind + 'k)>,
    rt: &TokenStream,
) -> TokenStream {
    let mut bytes = 0usize;
    let mut terms = Vec::new();
    for kind in kinds {
        let (b, term) = kind.size_parts(rt);
        bytes += b;
        terms.extend(term);
    }
    if bytes == 0 && !terms.is_empty() {
        quote!(#(#terms)+*)
    } else {
        quote!(#bytes #(+ #terms)*)
    }
}

/// The Rust type of a struct or enum a field names: a generated type's identifier, or a type
/// of the user's crate (a derive's) as written.
fn named_type(name: &str, foreign: bool) -> TokenStream {
    if foreign {
        // The derive printed it from tokens, so it parses back.
        name.parse().unwrap_or_default()
    } else {
        let n = ident(name);
        quote!(#n)
    }
}
