//! A bit stream ([`FieldKind::BitStream`](crate::ir::FieldKind::BitStream)): bytes read most
//! significant bit first as one stream, whose members are fields of the Rust struct, each got
//! from (and set into) its bits by the runtime's `bitstream`.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::bits::{member_doc, member_raw, member_type, member_value};
use super::{Decl, Kind, Slot, named_type};
use crate::codegen::ident;
use crate::codegen::payload::body::{Body, write_in};
use crate::codegen::payload::scalar::local;
use crate::ir::{BitMember, Field, Prim, Protocol};

/// The stream's members and its size in bytes.
pub(super) struct Stream<'a> {
    pub(super) p: &'a Protocol,
    pub(super) members: &'a [BitMember],
    pub(super) size: usize,
}

impl Kind for Stream<'_> {
    fn elem_type(&self) -> TokenStream {
        quote!(())
    }

    fn is_eq(&self) -> bool {
        self.members.iter().all(|m| m.scale.is_none())
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
        self.members
            .iter()
            .all(|m| m.enum_index.is_none())
            .then_some(None)
    }

    fn value_can_fail(&self) -> bool {
        true
    }

    /// The bytes in a local, the members set into them (a zeroed run: the bits after the last
    /// member stay zero) and got from them by the runtime.
    fn body(&self, b: &mut Body, i: usize, _slots: &[Slot<'_>], rt: &TokenStream) {
        let var = format_ident!("stream{}", i);
        let size = self.size;
        let (mut sets, mut gets) = (Vec::new(), Vec::new());
        for m in self.members {
            let (id, at, width) = (ident(&m.name), m.shift as usize, m.width);
            let path = b.field_path(&id);
            let raw = match m.enum_index {
                Some(ei) => {
                    let e = &self.p.enums[ei];
                    let ty = named_type(&e.name, e.foreign);
                    quote!(#rt::enum_raw(self.#id, #ty::to_raw, #ty::from_raw)? as u64)
                }
                None => member_raw(m, quote!(self.#id), rt),
            };
            let set = quote!(#rt::set_stream(&mut #var, #at, #width, #raw)?;);
            sets.push(match m.prim {
                Prim::Bool if m.enum_index.is_none() => set,
                _ => write_in(&path, set, rt),
            });
            let bits = quote!(#rt::get_stream(&#var, #at, #width));
            let value = member_value(self.p, m, bits, &path, rt);
            let local = local(&id);
            gets.push(quote!(let #local = #value;));
            b.inits.push(quote!(#id: #local));
        }
        b.writes
            .push(quote!(let mut #var = [0u8; #size]; #(#sets)* w.put_bytes(&#var)?;));
        // Each member as the stream is read: an enum without variant is an error before the
        // fields after the stream are read, as a value field's is.
        b.reads
            .push(quote!(let #var = r.bytes::<#size>()?; #(#gets)*));
        b.sequenced = true;
    }

    fn own_code(&self) -> bool {
        true
    }

    fn declare(&self, f: &Field, _id: Option<&Ident>, d: &mut Decl) {
        d.eq &= self.is_eq();
        for m in self.members {
            let place = format!(
                "bits {}..{} of the bit stream at byte {}, most significant bit first",
                m.shift,
                m.shift + m.width,
                f.offset
            );
            let doc = member_doc(m, &place);
            let (id, ty) = (ident(&m.name), member_type(self.p, m));
            d.fields.push(quote!(#doc pub #id: #ty));
        }
    }
}
