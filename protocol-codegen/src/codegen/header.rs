//! A frame format's `Header`: the header values a sender sets, with `read` (from a checked
//! frame) and `write` (into a frame being assembled) through the frame's `wire` fields. Every
//! packet of the format reads and writes its header through them.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::docs::doc_attrs;
use super::frame::{user_values, wire_const};
use super::payload::prim_type;
use super::{ident, rt};
use crate::ir::{Frame, HeaderValue, Pos, Prim};

/// The `Header` struct of format `f` and its `read` and `write`.
pub(super) fn emit_header(f: &Frame) -> TokenStream {
    let rt = rt();
    let name = format_ident!("{}", f.names.header);
    let fields = user_values(f).map(|(_, v)| {
        let id = ident(&v.name);
        let ty = prim_type(v.prim);
        let d = doc_attrs(if v.doc.is_empty() {
            "Header value."
        } else {
            &v.doc
        });
        quote!(#d pub #id: #ty)
    });
    let trailer = f.flag_trailer.as_ref().map(|t| {
        let (id, len) = (ident(&t.name), t.len);
        let flag = &f.values[t.flag].name;
        let doc = doc_attrs(&format!(
            "{}{}The {len} bytes at the end of the frame, present when `{flag}` is set (the codec sets \
             it from this field). Carried as received, not verified.",
            t.doc,
            if t.doc.is_empty() { "" } else { "\n\n" }
        ));
        quote!(#doc pub #id: #rt::Option<[u8; #len]>,)
    });
    let (reads, writes) = header_codec(f, &rt);
    quote! {
        /// The header values a sender sets (the codec computes the sync, length, command and
        /// checks).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub struct #name {
            #(#fields,)*
            #trailer
        }
        impl #name {
            /// The header values of a frame (`DecodeError::Truncated` if it ends before one).
            #[inline(always)]
            pub fn read(frame: &[u8]) -> #rt::DecodeResult<Self> {
                #rt::Ok(Self { #(#reads,)* })
            }
            /// Writes the header values into a frame (`EncodeError::ValueOutOfRange` if one does
            /// not fit its field).
            #[inline(always)]
            pub fn write(&self, frame: &mut [u8]) -> #rt::Result<(), #rt::EncodeError> {
                #(#writes)*
                #rt::Ok(())
            }
        }
    }
}

/// Reading the user-set header values of frame `f` into the header struct's fields, and
/// writing them back from `self`, through the frame's `wire` consts. A value after the payload
/// of a format with a flag trailer lies back from the end of the frame's body (the frame
/// without the trailer): it is read from and written into the body, once the flag is written.
fn header_codec(f: &Frame, rt: &TokenStream) -> (Vec<TokenStream>, Vec<TokenStream>) {
    let header_len = format_ident!("{}", f.names.sizes.header_len);
    let layout = format_ident!("{}", f.names.layout_static);
    let in_body = |v: &HeaderValue| f.flag_trailer.is_some() && matches!(v.at, Pos::End(_));
    let (trailer_writes, trailer_read) = flag_trailer_codec(f, rt).unzip();
    let (reads, writes): (Vec<TokenStream>, Vec<TokenStream>) = user_values(f)
        .map(|(i, v)| {
            let id = ident(&v.name);
            let c = wire_const(f, i);
            let (from, into) = if in_body(v) {
                (
                    quote!(#rt::frame_body(&#layout, frame)),
                    quote!(#rt::frame_body_mut(&#layout, frame)),
                )
            } else {
                (quote!(frame), quote!(frame))
            };
            let value = quote!(#rt::header_value(#from, wire::#c, #header_len)?);
            let read = if v.prim == Prim::Bool {
                quote!(#id: #value != 0)
            } else {
                let t = prim_type(v.prim);
                quote!(#id: #value as #t)
            };
            let write = quote!(#rt::write_header(#into, wire::#c, self.#id as u64)?;);
            (read, write)
        })
        .unzip();
    let Some((read, (write_flag, write_bytes))) = trailer_read.zip(trailer_writes) else {
        return (reads, writes);
    };
    // The flag first where a value lies in the body, whose end the flag decides.
    let writes = if user_values(f).any(|(_, v)| in_body(v)) {
        [vec![write_flag], writes, vec![write_bytes]].concat()
    } else {
        [writes, vec![quote!(#write_flag #write_bytes)]].concat()
    };
    ([reads, vec![read]].concat(), writes)
}

/// The flag trailer's `Header` field read from a frame, and its flag and its bytes written
/// into one.
fn flag_trailer_codec(
    f: &Frame,
    rt: &TokenStream,
) -> Option<((TokenStream, TokenStream), TokenStream)> {
    let t = f.flag_trailer.as_ref()?;
    let (id, len, flag) = (ident(&t.name), t.len, wire_const(f, t.flag));
    let layout = format_ident!("{}", f.names.layout_static);
    Some((
        (
            quote!(#rt::write_header(frame, wire::#flag, u64::from(self.#id.is_some()))?;),
            quote!(#rt::write_flag_trailer(frame, self.#id.as_ref())?;),
        ),
        quote!(#id: #rt::flag_trailer::<#len>(&#layout, frame)),
    ))
}
