//! A bitfield ([`FieldKind::Bits`](crate::ir::FieldKind::Bits)): an integer on the wire whose
//! bits are fields of the Rust struct, each set into (and got from) its bits by the runtime.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{Decl, Kind, Slot, named_type};
use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::codegen::payload::body::{Body, read_in, write_in};
use crate::codegen::payload::scalar::{prim_type, read_scalar, write_scalar};
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

    /// A member's enum type, if it holds an enum, with the enum's raw type.
    fn member_enum(&self, m: &BitMember) -> Option<(TokenStream, Prim)> {
        let e = &self.p.enums[m.enum_index?];
        Some((named_type(&e.name, e.foreign), e.prim))
    }

    /// A member's Rust type: `bool`, an unsigned integer or an enum.
    fn member_type(&self, m: &BitMember) -> TokenStream {
        match self.member_enum(m) {
            Some((ty, _)) => ty,
            None if m.prim == Prim::Bool => quote!(bool),
            None => prim_type(m.prim),
        }
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
            let (raw, value) = match self.member_enum(m) {
                // Through the word type, as the word holds it (a signed raw value's bits).
                Some((ty, p)) => {
                    let t = prim_type(p);
                    (
                        quote!(#rt::enum_raw(self.#id, #ty::to_raw, #ty::from_raw)? as #wt as u64),
                        read_in(&path, quote!(#ty::from_raw(#field as #t)?), rt),
                    )
                }
                None if m.prim == Prim::Bool => (quote!(u64::from(self.#id)), quote!(#field != 0)),
                None => {
                    let t = prim_type(m.prim);
                    (quote!(self.#id as u64), quote!(#field as #t))
                }
            };
            let set = quote!(#var = #rt::set_bits(#var, #raw, #shift, #width)?;);
            // A `bool` fits its bit; a wider value or an enum's raw value may not.
            sets.push(match m.prim {
                Prim::Bool if m.enum_index.is_none() => set,
                _ => write_in(&path, set, rt),
            });
            inits.push(quote!(#id: #value));
        }
        (sets, inits)
    }
}

impl Kind for Bits<'_> {
    fn elem_type(&self) -> TokenStream {
        quote!(())
    }

    fn is_eq(&self) -> bool {
        true
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
        for m in self.members {
            let ty = self.member_type(m);
            let text = format!(
                "{}{}(bits {}..{} of byte {}.)",
                m.doc,
                if m.doc.is_empty() { "" } else { " " },
                m.shift,
                m.shift + m.width,
                f.offset
            );
            let doc = doc_attrs(&text);
            let id = ident(&m.name);
            d.fields.push(quote!(#doc pub #id: #ty));
        }
    }
}
