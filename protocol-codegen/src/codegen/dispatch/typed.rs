//! A frame decoded as, and encoded from, one command's struct: the `CommandPayload` impl of
//! every struct that one command alone carries; `Packet::from_frame_as`, which compares the
//! frame's key with that command's id before it reads anything else; `Packet::encode_as`,
//! which writes the struct as its command's frame. Only the readers and writers of the structs
//! a program names are linked, where `Packet::from_frame` and `Packet::encode` match every
//! command and link every reader and writer.
//!
//! Printed for the first frame format when [`Protocol::sole_carriers`] names commands.

use proc_macro2::{Ident, TokenStream};
use quote::quote;

use super::frames::flag_trailer_len_of;
use super::packet::{Items, aside, encode_message, key_values, unstuff_scratch};
use crate::codegen::ident;
use crate::ir::{Frame, Protocol};

/// The `CommandPayload` impls and `Packet::from_frame_as` of format `f`, when it has them.
pub(super) fn emit_typed_decode(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let impls: Vec<TokenStream> = p
        .sole_carriers(f)
        .map(|(c, si)| {
            let s = ident(&p.structs[si].name);
            let v = ident(&c.rust_name);
            quote! {
                impl #rt::CommandPayload for #s {
                    type Command = Command;
                    const COMMAND: Command = Command::#v;
                }
            }
        })
        .collect();
    if impls.is_empty() {
        return quote!();
    }
    let Items {
        max_payload_len,
        rules,
        packet,
        header,
        ..
    } = Items::of(f);
    let encode = encode_as(p, f, &max_payload_len, rt);
    let values = key_values(p);
    let frame_values = (0..f.dispatch.len()).map(|i| quote!(#rules.key_value(frame, #i)?));
    let (scratch, scratch_ref) = unstuff_scratch(f);
    // A payload whose trailing zeros the sender dropped is read zero-extended; a whole one is
    // read where it lies, with no buffer zeroed (the struct's size is not a constant here, so
    // the buffer of a short one has the format's largest payload).
    let read = if f.truncate_zeros {
        let max = f.payload_max;
        quote!(#rt::read_filled::<M, #max>(payload))
    } else {
        quote!(#rt::read_payload(payload))
    };
    quote! {
        #(#impls)*
        impl #packet {
            /// Decode a frame whose framing a decoder already checked as command
            /// `M::COMMAND` alone: `None` when the frame holds another command (or an id the
            /// spec does not have). A program that handles a few commands calls it once for
            /// each and links the readers of those structs alone; [`Self::from_frame`]
            /// links every command's.
            ///
            /// # Errors
            /// `PayloadLength` when the payload's size is not the command's, and errors of
            /// the payload's fields, as [`Self::from_frame`] gives them for that command.
            pub fn from_frame_as<M: #rt::CommandPayload<Command = Command>>(
                frame: &[u8],
            ) -> #rt::DecodeResult<#rt::Option<(#header, M)>> {
                // In a `const`: the command's id and name fold even where nothing is
                // optimised (opt-level 0), so the `match` over every command is not linked.
                let (id, name) = const { (M::COMMAND.id(), M::COMMAND.name()) };
                if [#(#frame_values),*] != #values {
                    return #rt::Ok(#rt::None);
                }
                let header = #header::read(frame)?;
                #scratch
                let payload = #rules.payload(frame, #scratch_ref)?;
                let message = #rt::read_command(name, || { #read })?;
                #rt::Ok(#rt::Some((header, message)))
            }
            #encode
        }
    }
}

/// `Packet::encode_as`: `payload` written as its command's frame, with `header`.
fn encode_as(p: &Protocol, f: &Frame, max_payload_len: &Ident, rt: &TokenStream) -> TokenStream {
    let values = key_values(p);
    let Items { rules, header, .. } = Items::of(f);
    let aside = aside(f, max_payload_len);
    let flagged = flag_trailer_len_of(f, &quote!(header));
    let encode = encode_message(f);
    quote! {
        /// Encode `payload` as command `M::COMMAND`'s frame with `header` into the start of
        /// `buf`; returns its length. The same bytes as [`Self::encode`] of the packet that
        /// holds them, linking the writer of `M` alone.
        ///
        /// # Errors
        /// As [`Self::encode`].
        pub fn encode_as<M: #rt::CommandPayload<Command = Command>>(
            header: &#header,
            payload: &M,
            buf: &mut [u8],
        ) -> #rt::Result<usize, #rt::EncodeError> {
            let id = const { M::COMMAND.id() };
            let body = #rt::Body::Command { key: &#values, carried: #rt::None, direction: #rt::None };
            #rules.#encode(buf, #aside, &body, &#rt::CommandMessage(payload), #flagged, |frame| header.write(frame))
        }
    }
}
