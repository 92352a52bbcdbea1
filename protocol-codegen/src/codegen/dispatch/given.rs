//! Directions the decoder is given: no header field tells a request from a response, so
//! `Packet` has a decoder per direction (`decode_request`, `from_response_frame`, ...) instead
//! of `decode` and `from_frame`, and each direction has a layout type (`RequestLayout`) that
//! runtime stream decoders and integrations run. A direction that carries one struct in place of
//! the dispatch key starts its payload where the key would be (`Body::Struct` to the rules).
//!
//! Named decoders rather than a direction argument: a program is one side of a link, so the
//! direction it decodes is a fact of its source, and `Packet::decode_response` says in rustdoc,
//! with its own documentation, what it decodes; no direction value has to be built or matched.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::packet::parse_bytes;
use super::packet::{read_id, unstuff_scratch};
use super::rules::rules_static;
use crate::codegen::docs::doc_attrs;
use crate::codegen::frame::emit_rule_kinds;
use crate::ir::{Direction, Frame, Protocol};
use crate::layout::RuleKinds;

/// `decode_<direction>` and `from_<direction>_frame` for every direction.
/// A direction with fields of its own decodes through its own layout of the format
/// ([`Direction::frame`]), its header read by `Header::read_<direction>`.
pub(super) fn decoders(p: &Protocol, base: &Frame, rt: &TokenStream) -> TokenStream {
    let packet = format_ident!("{}", base.names.packet);
    let header = format_ident!("{}", base.names.header);
    let mut out = TokenStream::new();
    for d in &p.directions {
        let (f, read) = match &d.frame {
            Some(own) => (own, format_ident!("read_{}", d.name)),
            None => (base, format_ident!("read")),
        };
        let parse = parse_bytes(f);
        let rules = rules_static(f);
        let (scratch, scratch_ref) = unstuff_scratch(f);
        let v = format_ident!("{}", d.rust_name);
        let decode = format_ident!("decode_{}", d.name);
        let from_frame = format_ident!("from_{}_frame", d.name);
        let body = match d.message {
            Some((_, start)) => quote! {
                #scratch
                let payload = #rules.payload_from(frame, #start, #scratch_ref)?;
                let message = Message::#v(#rt::read_payload(payload)?);
            },
            None => {
                let id = read_id(p, f, rt);
                quote! {
                    #id
                    #scratch
                    let payload = #rules.payload(frame, #scratch_ref)?;
                    let message = Message::#v(#v::read_payload(command, payload)?);
                }
            }
        };
        let what = what(d);
        let decode_doc = doc_attrs(&format!(
            "Decode the frame at the start of `bytes` as {what}, checking its framing (sync, \
             length, checks) first. {}",
            d.doc
        ));
        let from_doc = doc_attrs(&format!(
            "Decode a frame whose framing a decoder already checked as {what}."
        ));
        let errors = match d.message {
            Some(_) => quote! {
                /// `PayloadLength` when the payload's size is not the struct's, and errors of
                /// its fields.
            },
            None => quote! {
                /// `UnknownCommand` for an id the spec does not have, `PayloadLength` when the
                /// payload's size is not the command's, and errors of the payload's fields.
            },
        };
        out.extend(quote! {
            #decode_doc
            ///
            /// # Errors
            /// `DecodeError::Frame` if the bytes are not a valid frame, `Truncated` if they
            /// end early, and the errors of the frame's decoding.
            pub fn #decode(bytes: &[u8]) -> #rt::DecodeResult<Self> {
                Self::#from_frame(#parse)
            }
            #from_doc
            ///
            /// # Errors
            #errors
            pub fn #from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                let header = #header::#read(frame)?;
                #body
                #rt::Ok(#packet { header, message })
            }
        });
    }
    out
}

/// The words that say what a direction's decoder makes of a frame.
fn what(d: &Direction) -> String {
    match d.message {
        Some(_) => format!("a {} (`Message::{}`)", d.name, d.rust_name),
        None => format!(
            "a {} (`Message::{}`, by the command's {} payload)",
            d.name, d.rust_name, d.name
        ),
    }
}

/// A layout type per direction, for the runtime's `PacketDecoder` and integrations: the frame
/// format's layout, each frame decoded in that direction.
pub fn direction_layouts(p: &Protocol, base: &Frame, rt: &TokenStream) -> TokenStream {
    let packet = format_ident!("{}", base.names.packet);
    let mut out = TokenStream::new();
    for d in &p.directions {
        let f = d.frame.as_ref().unwrap_or(base);
        let layout = format_ident!("{}", f.names.layout_static);
        let kinds = emit_rule_kinds(RuleKinds::of_link([f]));
        let ty = format_ident!("{}Layout", d.rust_name);
        let from_frame = format_ident!("from_{}_frame", d.name);
        let doc = doc_attrs(&format!(
            "[`{}`] decoding {}s: what a `PacketDecoder` (or an integration) of the side \
             that receives them runs; each frame becomes a `{}` through \
             [`{}::{from_frame}`].",
            f.names.layout_static, d.name, f.names.packet, f.names.packet
        ));
        out.extend(quote! {
            #doc
            #[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
            pub struct #ty;
            impl #rt::LayoutRef for #ty {
                #kinds
                #[inline(always)]
                fn layout(&self) -> &#rt::FrameLayout<'_> {
                    &#layout
                }
            }
            impl #rt::PacketLayout for #ty {
                type Packet = #packet;
                type Error = #rt::DecodeError;
                fn decode_packet(&self, frame: &#rt::Frame<'_>) -> #rt::DecodeResult<#packet> {
                    #packet::#from_frame(frame.bytes)
                }
            }
        });
    }
    out
}
