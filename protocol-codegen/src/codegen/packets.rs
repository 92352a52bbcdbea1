//! The runtime's packet traits for each serial frame format that has a packet type:
//! `PacketLayout` on its `Layout` type (the stream's frames decoded into its `Packet`) and
//! `EncodePacket` on its `Packet`, so that the runtime's `PacketDecoder` and the integrations
//! (the `tokio` codec, the `embedded-io-async` reader and writer) drive generated codecs.
//!
//! On a link of several command formats, also `PacketLayout` on `AnyLayout` (each frame decoded
//! into an `AnyPacket` by the format it came in) and `EncodePacket` on `AnyPacket`.
//!
//! This module owns only those impls; each delegates to the packet's own `from_frame`,
//! `encoded_len` and `encode` (`dispatch`), which the optimiser inlines (the impls are
//! generic code's callees in the same crate). A CAN format has no stream, so no impl.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::rt;
use crate::ir::{PacketKind, Protocol, Transport};

/// The packet trait impls of every serial frame format with a packet type.
pub fn emit_packet_traits(p: &Protocol) -> TokenStream {
    let rt = rt();
    let mut out = TokenStream::new();
    for (fi, f) in p.frames.iter().enumerate() {
        let has_packet = match f.packet {
            PacketKind::Command => fi == 0 && !f.dispatch.is_empty(),
            PacketKind::Message(_) | PacketKind::Commands => true,
            PacketKind::None | PacketKind::Can => false,
        };
        if !has_packet || f.transport != Transport::Serial {
            continue;
        }
        let layout = format_ident!("{}", f.names.layout);
        let packet = format_ident!("{}", f.names.packet);
        if fi == 0 && p.directions_given() {
            // No header field tells the direction: a layout type per direction decodes.
            out.extend(super::dispatch::direction_layouts(p, f, &rt));
            out.extend(encode_packet(&packet, &rt));
            continue;
        }
        out.extend(quote! {
            impl #rt::PacketLayout for #layout {
                type Packet = #packet;
                type Error = #rt::DecodeError;
                fn decode_packet(&self, frame: &#rt::Frame<'_>) -> #rt::DecodeResult<#packet> {
                    #packet::from_frame(frame.bytes)
                }
            }
        });
        out.extend(encode_packet(&packet, &rt));
    }
    if !p.link.is_empty() {
        // The link's one decoder: each frame decoded by the format it came in.
        out.extend(quote! {
            impl #rt::PacketLayout for AnyLayout {
                type Packet = AnyPacket;
                type Error = #rt::DecodeError;
                fn decode_packet(&self, frame: &#rt::Frame<'_>) -> #rt::DecodeResult<AnyPacket> {
                    AnyPacket::from_frame(frame)
                }
            }
        });
        out.extend(encode_packet(&format_ident!("AnyPacket"), &rt));
    }
    out
}

/// `EncodePacket` on a packet type.
fn encode_packet(packet: &proc_macro2::Ident, rt: &TokenStream) -> TokenStream {
    quote! {
        impl #rt::EncodePacket for #packet {
            fn encoded_len(&self) -> usize {
                #packet::encoded_len(self)
            }
            fn encode_into(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                #packet::encode(self, buf)
            }
        }
    }
}
