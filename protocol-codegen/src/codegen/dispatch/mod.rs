//! Commands and messages: the `Command` id enum (module `command`), the dispatch enums
//! (`Message`, or `Request` and `Response` when the spec has directions; `message`), the
//! `RULES` static of each format with a packet type (`rules`: the runtime's packet rules, as
//! `protocol_spec::rules` lowers them), `Packet`, which decodes a frame into a header and a
//! message and encodes one back through its `RULES` (`packet`), the packets of the other
//! frame formats (`frames`, `link`, `given`), the `SESSION` static of a spec with a
//! conversation (`session`), the typed handlers with their dispatch (`handler`), and the
//! decoding of a frame as one command's struct (`typed`), and the packets a struct carries
//! (`carried`).

mod carried;
mod command;
mod frames;
mod given;
mod handler;
mod link;
mod message;
mod packet;
mod rules;
mod session;
mod typed;

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::frame::own_layouts;
use super::payload::prim_type;
use super::rt;
use super::types::int_lit;
use crate::ir::{Command, PacketKind, Prim, Protocol};
use carried::emit_carried;
use command::emit_command_enum;
use frames::{emit_can_packet, emit_message_packet};
pub use given::direction_layouts;
use handler::emit_handlers;
use link::{emit_base_payload, emit_commands_packet, emit_link};
use message::{emit_direction_message, emit_message_enum};
pub(crate) use packet::direction_test;
use packet::emit_packet;
use rules::emit_rules;
use session::emit_session;
use typed::emit_typed_decode;

/// Everything about commands and messages, for the first frame.
pub fn emit_dispatch(p: &Protocol) -> TokenStream {
    let Some(f) = p.frames.first() else {
        return quote!();
    };
    let rt = rt();
    // Every format with a packet type decodes and encodes through its rules.
    let rules: TokenStream = p
        .frames
        .iter()
        .filter(|f| f.packet != PacketKind::None)
        .map(|f| emit_rules(p, f, &rt))
        .chain(own_layouts(p).map(|(_, f)| emit_rules(p, f, &rt)))
        .collect();
    if f.dispatch.is_empty() {
        return match f.packet {
            PacketKind::Message(si) => {
                let packet = emit_message_packet(p, f, si, &rt);
                quote!(#rules #packet)
            }
            _ => quote!(),
        };
    }
    // The message enums' `payload_len` and `write_payload` are the runtime trait's.
    let mut out = quote!(use #rt::MessagePayload as _; #rules);
    out.extend(emit_command_enum(p, f, &rt));
    if p.directions.is_empty() {
        out.extend(emit_message_enum(
            p,
            0,
            &format_ident!("Message"),
            "A decoded message: one variant per command, holding its payload.",
            &rt,
        ));
    } else {
        for (di, d) in p.directions.iter().enumerate() {
            if d.message.is_some() || d.empty {
                // The direction's frames carry one struct, or only the command (an empty
                // direction), held by `Message` itself.
                continue;
            }
            let name = format_ident!("{}", d.rust_name);
            let doc = format!(
                "A {} message: one variant per command, holding its {} payload. {}",
                d.name, d.name, d.doc
            );
            out.extend(emit_message_enum(p, di, &name, &doc, &rt));
        }
        out.extend(emit_direction_message(p, &rt));
    }
    out.extend(emit_carried(p, &rt));
    out.extend(emit_packet(p, f, &rt));
    out.extend(emit_typed_decode(p, f, &rt));
    if p.frames.iter().any(|f| !f.extensions) {
        out.extend(emit_base_payload(p, &rt));
    }
    for lf in &p.frames {
        if lf.packet == PacketKind::Commands {
            out.extend(emit_commands_packet(p, lf, &rt));
        }
    }
    out.extend(emit_link(p, &rt));
    for mf in &p.frames {
        if let PacketKind::Message(si) = mf.packet {
            out.extend(emit_message_packet(p, mf, si, &rt));
        }
    }
    for cf in &p.frames {
        if cf.packet == PacketKind::Can {
            out.extend(emit_can_packet(p, cf, &rt));
        }
    }
    out.extend(emit_session(p, &rt));
    out.extend(emit_handlers(p, f, &rt));
    out
}

/// The types of a command id's values ([`Protocol::id_prims`]).
pub(super) fn key_prims(p: &Protocol) -> Vec<Prim> {
    p.id_prims()
}

pub(super) fn id_type(p: &Protocol) -> TokenStream {
    let prims: Vec<TokenStream> = key_prims(p).into_iter().map(prim_type).collect();
    if prims.len() == 1 {
        prims[0].clone()
    } else {
        quote!((#(#prims),*))
    }
}

pub(super) fn id_value(p: &Protocol, c: &Command) -> TokenStream {
    let lits: Vec<TokenStream> = key_prims(p)
        .into_iter()
        .zip(&c.id)
        .map(|(p, v)| int_lit(p, *v))
        .collect();
    if lits.len() == 1 {
        lits[0].clone()
    } else {
        quote!((#(#lits),*))
    }
}
