//! A frame format's `Header`: the header values a sender sets, with `read` (from a checked
//! frame) and `write` (into a frame being assembled) through the frame's `wire` fields. Every
//! packet of the format reads and writes its header through them.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::docs::doc_attrs;
use super::frame::{user_values, wire_const};
use super::payload::prim_type;
use super::{ident, rt};
use crate::ir::{Direction, Frame, HeaderValue, Pos, Prim};

/// The `Header` struct of format `f` and its `read` and `write`. `own` are the layouts of `f`
/// of the directions with fields of their own (the first format only): the struct holds
/// their values too, `read` and `write` are the format's own layout (where another
/// direction's value reads as 0 and only 0 is written), and `read_<direction>` and
/// `write_<direction>` are each direction's.
pub(super) fn emit_header(f: &Frame, own: &[(&Direction, &Frame)]) -> TokenStream {
    let rt = rt();
    let name = format_ident!("{}", f.names.header);
    let mut values: Vec<&HeaderValue> = user_values(f).map(|(_, v)| v).collect();
    for (_, of) in own {
        for (_, v) in user_values(of) {
            if !values.iter().any(|x| x.name == v.name) {
                values.push(v);
            }
        }
    }
    // A value some frames of the format lack is `None` in them.
    let optional: Vec<&str> = values
        .iter()
        .filter(|v| !user_values(f).any(|(_, x)| x.name == v.name))
        .map(|v| v.name.as_str())
        .collect();
    let fields = values.iter().map(|v| {
        let id = ident(&v.name);
        let ty = prim_type(v.prim);
        let ty = if optional.contains(&v.name.as_str()) {
            quote!(#rt::Option<#ty>)
        } else {
            ty
        };
        let d = doc_attrs(&value_doc(v, own));
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
    let (read, write) = read_write(
        f,
        (&values, &optional),
        (quote!(read), quote!(write)),
        "",
        &rt,
    );
    let directed = own.iter().map(|(d, of)| {
        let (r, w) = (
            format_ident!("read_{}", d.name),
            format_ident!("write_{}", d.name),
        );
        let what = format!(" of a {}", d.name);
        read_write(
            of,
            (&values, &optional),
            (quote!(#r), quote!(#w)),
            &what,
            &rt,
        )
    });
    let directed = directed.map(|(r, w)| quote!(#r #w));
    quote! {
        /// The header values a sender sets (the codec computes the sync, length, command and
        /// checks).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
        pub struct #name {
            #(#fields,)*
            #trailer
        }
        impl #name {
            #read
            #write
            #(#directed)*
        }
    }
}

/// The documentation of header value `v`: its own, and which directions have it when it is
/// one direction's only.
fn value_doc(v: &HeaderValue, own: &[(&Direction, &Frame)]) -> String {
    let doc = if v.doc.is_empty() {
        "Header value."
    } else {
        &v.doc
    };
    let in_all = own
        .iter()
        .all(|(_, of)| user_values(of).any(|(_, x)| x.name == v.name));
    if in_all {
        return doc.to_string();
    }
    let dirs: Vec<String> = own
        .iter()
        .filter(|(_, of)| user_values(of).any(|(_, x)| x.name == v.name))
        .map(|(d, _)| format!("`{}`", d.name))
        .collect();
    format!(
        "{doc}\n\nIn {} frames only: `None` in the others, which have no place for it (encoding \
         `Some` there, or `None` in its own, is `EncodeError::ValueOutOfRange`).",
        dirs.join(", ")
    )
}

/// A header's `read` and `write` (named `read`, `write`) through the layout of `f`: of `all`
/// the header's values, those `optional` are `Option`s, and those `f` does not have read as
/// `None` and are written only as `None`.
fn read_write(
    f: &Frame,
    (all, optional): (&[&HeaderValue], &[&str]),
    (read, write): (TokenStream, TokenStream),
    what: &str,
    rt: &TokenStream,
) -> (TokenStream, TokenStream) {
    let (reads, writes) = header_codec(f, optional, rt);
    let absent: Vec<_> = all
        .iter()
        .filter(|v| !user_values(f).any(|(_, x)| x.name == v.name))
        .map(|v| ident(&v.name))
        .collect();
    let rest = (!absent.is_empty()).then(|| quote!(..Self::default()));
    let refuse = absent
        .iter()
        .map(|id| quote!(#rt::absent_header(self.#id)?;));
    let read_doc = format!(
        " The header values of a frame{what} (`DecodeError::Truncated` if it ends before one)."
    );
    let write_doc = format!(
        " Writes the header values into a frame{what} (`EncodeError::ValueOutOfRange` if one does"
    );
    (
        quote! {
            #[doc = #read_doc]
            #[inline(always)]
            pub fn #read(frame: &[u8]) -> #rt::DecodeResult<Self> {
                #rt::Ok(Self { #(#reads,)* #rest })
            }
        },
        quote! {
            #[doc = #write_doc]
            /// not fit its field).
            #[inline(always)]
            pub fn #write(&self, frame: &mut [u8]) -> #rt::Result<(), #rt::EncodeError> {
                #(#refuse)*
                #(#writes)*
                #rt::Ok(())
            }
        },
    )
}

/// Reading the user-set header values of frame `f` into the header struct's fields, and
/// writing them back from `self`, through the frame's `wire` consts. A value after the payload
/// of a format with a flag trailer lies back from the end of the frame's body (the frame
/// without the trailer): it is read from and written into the body, once the flag is written.
/// The values `optional` are `Option`s of the header struct: `Some` when read, and required
/// when written.
fn header_codec(
    f: &Frame,
    optional: &[&str],
    rt: &TokenStream,
) -> (Vec<TokenStream>, Vec<TokenStream>) {
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
            let value = if v.prim == Prim::Bool {
                quote!(#value != 0)
            } else {
                let t = prim_type(v.prim);
                quote!(#value as #t)
            };
            let (read, field) = if optional.contains(&v.name.as_str()) {
                (
                    quote!(#id: #rt::Some(#value)),
                    quote!(#rt::present_header(self.#id)?),
                )
            } else {
                (quote!(#id: #value), quote!(self.#id))
            };
            let write = quote!(#rt::write_header(#into, wire::#c, #field as u64)?;);
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
