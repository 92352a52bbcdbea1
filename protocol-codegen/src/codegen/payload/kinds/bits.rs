//! A bitfield ([`FieldKind::Bits`](crate::ir::FieldKind::Bits)): an integer on the wire whose
//! bits are fields of the Rust struct, each set into (and got from) its bits by the runtime.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{Decl, Kind, Slot, named_type};
use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::codegen::payload::body::{Body, read_in, write_in};
use crate::codegen::payload::scalar::{prim_type, read_scalar, to_physical, to_raw, write_scalar};
use crate::ir::{BitMember, Field, Prim, Protocol, Scalar};

/// The word and its members.
pub(super) struct Bits<'a> {
    p: &'a Protocol,
    word: Scalar,
    members: &'a [BitMember],
}

impl<'a> Bits<'a> {
    pub(super) fn new(p: &'a Protocol, word: Scalar, members: &'a [BitMember]) -> Bits<'a> {
        Bits { p, word, members }
    }

    /// Statements setting every member into the word `var` (write), and the members' values
    /// got from it (read).
    /// The errors of a member's value name the member as a field of the struct `b` builds.
    fn members_code(
        &self,
        var: &Ident,
        b: &Body,
        rt: &TokenStream,
    ) -> (Vec<TokenStream>, Vec<TokenStream>) {
        let wt = prim_type(self.word.prim);
        let mut sets = Vec::new();
        let mut inits = Vec::new();
        for m in self.members {
            let (id, shift, width) = (ident(&m.name), m.shift, m.width);
            let path = b.field_path(&id);
            let field = quote!(#rt::get_bits(#var, #shift, #width));
            // An enum's raw value goes through the word type, as the word holds it (a signed
            // raw value's bits).
            let raw = match member_enum(self.p, m) {
                Some((ty, _)) => {
                    quote!(#rt::enum_raw(self.#id, #ty::to_raw, #ty::from_raw)? as #wt as u64)
                }
                None => member_raw(m, quote!(self.#id), rt),
            };
            let set = quote!(#var = #rt::set_bits(#var, #raw, #shift, #width)?;);
            // A `bool` fits its bit; a wider value or an enum's raw value may not.
            sets.push(match m.prim {
                Prim::Bool if m.enum_index.is_none() => set,
                _ => write_in(&path, set, rt),
            });
            let value = member_value(self.p, m, field, &path, rt);
            inits.push(quote!(#id: #value));
        }
        (sets, inits)
    }
}

/// A member's enum type, if it holds an enum, with the enum's raw type.
fn member_enum(p: &Protocol, m: &BitMember) -> Option<(TokenStream, Prim)> {
    let e = &p.enums[m.enum_index?];
    Some((named_type(&e.name, e.foreign), e.prim))
}

/// A member's Rust type: `bool`, an integer, an enum, or the float a scaled member is.
pub(super) fn member_type(p: &Protocol, m: &BitMember) -> TokenStream {
    match (member_enum(p, m), m.scale) {
        (Some((ty, _)), _) => ty,
        (None, Some(sc)) => prim_type(sc.physical),
        (None, None) if m.prim == Prim::Bool => quote!(bool),
        (None, None) => prim_type(m.prim),
    }
}

/// The value of member `m` from its unsigned bits `bits` (a `u64` expression): a flag, an
/// integer (sign-extended from the member's width when signed), an enum, or the physical
/// value of a scaled one. Errors name the member's `path`.
pub(super) fn member_value(
    p: &Protocol,
    m: &BitMember,
    bits: TokenStream,
    path: &str,
    rt: &TokenStream,
) -> TokenStream {
    if let Some((ty, raw)) = member_enum(p, m) {
        let t = prim_type(raw);
        return read_in(path, quote!(#ty::from_raw(#bits as #t)?), rt);
    }
    if m.prim == Prim::Bool {
        return quote!(#bits != 0);
    }
    let width = m.width;
    let t = prim_type(m.prim);
    let raw = if m.is_signed() {
        quote!(#rt::sign_extend(#bits, #width) as #t)
    } else {
        quote!(#bits as #t)
    };
    match &m.scale {
        Some(sc) => to_physical(raw, m.prim, sc, rt),
        None => raw,
    }
}

/// The unsigned bits (a `u64` expression) of member `m` holding `value` (not an enum): the
/// raw integer of a scaled value, quantized and fitted by the runtime, and a signed value in
/// two's complement of the member's width (an error when it does not fit).
pub(super) fn member_raw(m: &BitMember, value: TokenStream, rt: &TokenStream) -> TokenStream {
    let width = m.width;
    let wide = match (&m.scale, m.is_signed()) {
        (Some(sc), true) => to_raw(value, sc, Some(Prim::I64), rt),
        (Some(sc), false) => to_raw(value, sc, Some(Prim::U64), rt),
        (None, true) => quote!(#value as i64),
        (None, false) if m.prim == Prim::Bool => quote!(u64::from(#value)),
        (None, false) => quote!(#value as u64),
    };
    if m.is_signed() {
        quote!(#rt::signed_bits(#wide, #width)?)
    } else {
        wide
    }
}

/// The doc of member `m`: its own text, its unit, and where its bits lie (`place`).
pub(super) fn member_doc(m: &BitMember, place: &str) -> TokenStream {
    let unit = if m.unit.is_empty() {
        String::new()
    } else {
        format!("Unit: {}. ", m.unit)
    };
    let text = format!(
        "{}{}{unit}({place}.)",
        m.doc,
        if m.doc.is_empty() { "" } else { " " },
    );
    doc_attrs(&text)
}

impl Kind for Bits<'_> {
    fn elem_type(&self) -> TokenStream {
        quote!(())
    }

    fn is_eq(&self) -> bool {
        self.members.iter().all(|m| m.scale.is_none())
    }

    fn fixed_size(&self) -> usize {
        self.word.prim.size()
    }

    fn read(&self, _reader: &TokenStream, _rt: &TokenStream) -> TokenStream {
        quote!(())
    }

    fn write(&self, _value: TokenStream, _owner: &TokenStream, _rt: &TokenStream) -> TokenStream {
        quote!()
    }

    fn short_only(&self, _rt: &TokenStream) -> Option<Option<TokenStream>> {
        self.members
            .iter()
            .all(|m| m.enum_index.is_none())
            .then_some(None)
    }

    /// The word in a local, the members set into it and got from it by the runtime.
    fn body(&self, b: &mut Body, i: usize, _slots: &[Slot<'_>], rt: &TokenStream) {
        let var = format_ident!("word{}", i);
        let wt = prim_type(self.word.prim);
        let (sets, inits) = self.members_code(&var, b, rt);
        b.inits.extend(inits);
        b.writes.push(quote!(let mut #var = 0u64; #(#sets)*));
        b.writes.push(write_scalar(self.word, quote!(#var as #wt)));
        let read = read_scalar(self.word);
        b.reads.push(quote!(let #var = u64::from(#read);));
        b.sequenced = true;
    }

    fn own_code(&self) -> bool {
        true
    }

    fn declare(&self, f: &Field, _id: Option<&Ident>, d: &mut Decl) {
        d.eq &= self.members.iter().all(|m| m.scale.is_none());
        for m in self.members {
            let ty = member_type(self.p, m);
            let place = format!(
                "bits {}..{} of byte {}",
                m.shift,
                m.shift + m.width,
                f.offset
            );
            let doc = member_doc(m, &place);
            let id = ident(&m.name);
            d.fields.push(quote!(#doc pub #id: #ty));
        }
    }
}
