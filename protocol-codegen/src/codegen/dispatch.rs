//! Commands and messages: the `Command` id enum, the dispatch enums (`Message`, or `Request` and
//! `Response` when the spec has directions), and `Packet`, which decodes a frame into a header
//! and a message and encodes one back through the runtime's `FrameLayout::seal`.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::docs::doc_attrs;
use super::frame::{user_values, value_const};
use super::payload::prim_type;
use super::types::int_lit;
use super::{ident, rt};
use crate::ir::{Command, DirectionRule, Frame, PacketKind, Prim, Protocol, Transport};

/// Everything about commands and messages, for the first frame.
pub fn emit_dispatch(p: &Protocol) -> TokenStream {
    let Some(f) = p.frames.first() else {
        return quote!();
    };
    if f.dispatch.is_empty() {
        return quote!();
    }
    let rt = rt();
    let mut out = emit_command_enum(p, f, &rt);
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
            let name = format_ident!("{}", d.rust_name);
            let doc = format!(
                "A {} message: one variant per command, holding its {} payload. {}",
                d.name, d.name, d.doc
            );
            out.extend(emit_message_enum(p, di, &name, &doc, &rt));
        }
        out.extend(emit_direction_message(p, &rt));
    }
    out.extend(emit_packet(p, f, &rt));
    for mf in &p.frames {
        if let PacketKind::Message(si) = mf.packet {
            out.extend(emit_message_packet(p, mf, si, &mf.names.const_prefix, &rt));
        }
    }
    for cf in &p.frames {
        if cf.packet == PacketKind::Can {
            out.extend(emit_can_packet(cf, &cf.names.const_prefix, &rt));
        }
    }
    out
}

/// `<Name>Packet` for a CAN frame format: decode from and encode to a `CanFrame`, through the
/// frame's virtual layout (id, length, data) so the runtime verifies and seals its checks.
fn emit_can_packet(f: &Frame, prefix: &str, rt: &TokenStream) -> TokenStream {
    let header = format_ident!("{}", f.names.header);
    let packet = format_ident!("{}", f.names.packet);
    let layout = super::const_ident(&format!("{prefix}LAYOUT"));
    let header_len = super::const_ident(&format!("{prefix}HEADER_LEN"));
    let trailer_len = super::const_ident(&format!("{prefix}TRAILER_LEN"));
    let prefix_can_id = super::const_ident(&format!("{prefix}can_id"));
    let (reads, writes) = header_codec(f, prefix, rt);
    let doc = format!(
        " A whole `{}` CAN frame, decoded: the header values and the message.",
        f.name
    );
    let decode_doc = " Decode a received CAN frame, verifying its checks.";
    quote! {
        #[doc = #doc]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct #packet {
            /// The header values the sender set.
            pub header: #header,
            /// The command and its payload.
            pub message: Message,
        }
        impl #packet {
            #[doc = #decode_doc]
            ///
            /// # Errors
            /// `DecodeError::Frame` when a check fails or the length is wrong,
            /// `UnknownCommand` for an id the spec does not have, `PayloadLength` when the
            /// payload's size is not the command's.
            pub fn decode(can: &#rt::CanFrame) -> #rt::DecodeResult<Self> {
                let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
                let frame = #layout.parse(can.to_virtual(&mut virt))?;
                let command = Command::from_can_id(can.id).ok_or(#rt::DecodeError::UnknownCommand { key: can.id as u64 })?;
                let payload = frame
                    .get(#header_len..frame.len().saturating_sub(#trailer_len))
                    .ok_or(#rt::DecodeError::Truncated { needed: #header_len + #trailer_len, available: frame.len() })?;
                #rt::Ok(#packet {
                    header: #header { #(#reads,)* },
                    message: Message::read_payload(command, payload)?,
                })
            }
            /// Encode into a CAN frame.
            ///
            /// # Errors
            /// `EncodeError::ValueOutOfRange` when the command has no CAN id or a header value
            /// does not fit its field.
            pub fn encode(&self) -> #rt::Result<#rt::CanFrame, #rt::EncodeError> {
                let id = self.message.command().can_id().ok_or(#rt::EncodeError::ValueOutOfRange)?;
                let total = #header_len.saturating_add(self.message.payload_len()).saturating_add(#trailer_len);
                let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
                let frame = virt.get_mut(..total).ok_or(#rt::EncodeError::PayloadTooLarge { len: total, max: #rt::CAN_VIRTUAL_LEN })?;
                #rt::write_header(frame, wire::#prefix_can_id, u64::from(id))?;
                #(#writes)*
                let payload = frame
                    .get_mut(#header_len..total.saturating_sub(#trailer_len))
                    .ok_or(#rt::EncodeError::BufferTooSmall { needed: total, available: #rt::CAN_VIRTUAL_LEN })?;
                self.message.write_payload(&mut #rt::Writer::new(payload))?;
                #layout.seal(frame)?;
                #rt::CanFrame::from_virtual(frame)
            }
        }
    }
}

fn key_prims(f: &Frame) -> Vec<Prim> {
    f.dispatch.iter().map(|&i| f.values[i].prim).collect()
}

fn id_type(f: &Frame) -> TokenStream {
    let prims: Vec<TokenStream> = key_prims(f).into_iter().map(prim_type).collect();
    if prims.len() == 1 {
        prims[0].clone()
    } else {
        quote!((#(#prims),*))
    }
}

fn id_value(f: &Frame, c: &Command) -> TokenStream {
    let lits: Vec<TokenStream> = key_prims(f)
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

fn emit_command_enum(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let id_ty = id_type(f);
    // Ids 0, 1, 2, ... of one key field are the variants' discriminants: `id` is a cast. (Other
    // ids stay a match: sparse discriminants would make every match on a command sparse too.)
    let single = f.dispatch.len() == 1
        && p.commands
            .iter()
            .enumerate()
            .all(|(i, c)| c.id == [i as u64]);
    let keys: Vec<&str> = f
        .dispatch
        .iter()
        .map(|&i| f.values[i].name.as_str())
        .collect();
    let variants = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let ids =
            c.id.iter()
                .map(|x| format!("{x:#04x}"))
                .collect::<Vec<_>>()
                .join(", ");
        let d = doc_attrs(&format!("`{}` (id {ids}). {}", c.name, c.doc));
        if single {
            let id = id_value(f, c);
            quote!(#d #v = #id)
        } else {
            quote!(#d #v)
        }
    });
    let all = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        quote!(Self::#v)
    });
    let n = p.commands.len();
    let to_id = if single {
        quote!(self as CommandId)
    } else {
        let arms = p.commands.iter().map(|c| {
            let v = ident(&c.rust_name);
            let id = id_value(f, c);
            quote!(Self::#v => #id,)
        });
        quote!(match self { #(#arms)* })
    };
    let repr = if single {
        quote!(#[repr(#id_ty)])
    } else {
        quote!()
    };
    let from_id = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let id = id_value(f, c);
        quote!(#id => #rt::Some(Self::#v),)
    });
    let names = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let name = &c.name;
        quote!(Self::#v => #name,)
    });
    let id_doc = format!(
        " A command id: the value of the dispatch key ({}).",
        keys.join(", ")
    );
    let can = emit_can_ids(p, rt);
    quote! {
        #[doc = #id_doc]
        pub type CommandId = #id_ty;
        /// Every command of the spec, with its id.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #repr
        pub enum Command {
            #(#variants,)*
        }
        impl Command {
            /// Every command, in spec order.
            pub const ALL: [Command; #n] = [#(#all),*];
            /// The command's id.
            pub const fn id(self) -> CommandId {
                #to_id
            }
            /// The command with this id, if any.
            pub const fn from_id(id: CommandId) -> #rt::Option<Self> {
                match id {
                    #(#from_id)*
                    _ => #rt::None,
                }
            }
            /// The command's name in the spec.
            pub const fn name(self) -> &'static str {
                match self {
                    #(#names)*
                }
            }
            #can
        }
    }
}

/// `Command::can_id` and `Command::from_can_id`, when a frame format is CAN.
fn emit_can_ids(p: &Protocol, rt: &TokenStream) -> TokenStream {
    if p.frames
        .iter()
        .skip(1)
        .any(|f| matches!(f.transport, Transport::Can { .. }))
    {
        let to = p.commands.iter().map(|c| {
            let v = ident(&c.rust_name);
            match c.can_id {
                Some(id) => {
                    let id = id as u32;
                    quote!(Self::#v => #rt::Some(#id),)
                }
                None => quote!(Self::#v => #rt::None,),
            }
        });
        let from = p.commands.iter().filter_map(|c| {
            let v = ident(&c.rust_name);
            let id = c.can_id? as u32;
            Some(quote!(#id => #rt::Some(Self::#v),))
        });
        quote! {
            /// The command's CAN id, if it has one.
            pub const fn can_id(self) -> #rt::Option<u32> {
                match self {
                    #(#to)*
                }
            }
            /// The command with this CAN id, if any.
            pub const fn from_can_id(id: u32) -> #rt::Option<Self> {
                match id {
                    #(#from)*
                    _ => #rt::None,
                }
            }
        }
    } else {
        quote!()
    }
}

fn emit_message_enum(
    p: &Protocol,
    di: usize,
    name: &proc_macro2::Ident,
    doc: &str,
    rt: &TokenStream,
) -> TokenStream {
    // Acknowledgements (a frame format with `ack`): a variant without a command.
    let ack_max = p
        .frames
        .first()
        .and_then(|f| f.ack.map(|(_, hl)| f.max_len() - hl - f.trailer_len));
    let doc = doc_attrs(doc);
    let mut variants = Vec::new();
    let mut command_arms = Vec::new();
    let mut visit_arms = Vec::new();
    let mut read_arms = Vec::new();
    let mut any_empty = false;
    for c in &p.commands {
        let v = ident(&c.rust_name);
        match c.payloads.get(di).copied().flatten() {
            Some(si) => {
                let s = ident(&p.structs[si].name);
                let d = doc_attrs(&format!(
                    "`{}`, carrying a `{}`. {}",
                    c.name, p.structs[si].name, c.doc
                ));
                variants.push(quote!(#d #v(#s)));
                command_arms.push(quote!(Self::#v(_) => Command::#v,));
                visit_arms.push(quote!(Self::#v(p) => v.visit(p),));
                read_arms.push(quote!(Command::#v => Self::#v(#rt::read_payload(bytes)?),));
            }
            None => {
                let d = doc_attrs(&format!("`{}`, with an empty payload. {}", c.name, c.doc));
                variants.push(quote!(#d #v));
                command_arms.push(quote!(Self::#v => Command::#v,));
                visit_arms.push(quote!(Self::#v => v.visit(&()),));
                read_arms.push(quote!(Command::#v if bytes.is_empty() => Self::#v,));
                any_empty = true;
            }
        }
    }
    let command_fn = match ack_max {
        None => quote! {
            /// The command of this message.
            #[inline(always)]
            pub const fn command(&self) -> Command {
                match self {
                    #(#command_arms)*
                }
            }
        },
        Some(max) => {
            variants.push(quote! {
                #[doc = " An acknowledgement: no command, the acknowledgement data."]
                Ack(#rt::Bytes<#max>)
            });
            visit_arms.push(quote!(Self::Ack(data) => v.visit(data),));
            quote! {
                /// The command of this message (`None` for an acknowledgement).
                #[inline(always)]
                pub const fn command(&self) -> #rt::Option<Command> {
                    #rt::Some(match self {
                        #(#command_arms)*
                        Self::Ack(_) => return #rt::None,
                    })
                }
            }
        }
    };
    let payload_fns = emit_payload_fns(rt, quote!(match self { #(#visit_arms)* }));
    // The commands without payload match only an empty one; any other bytes fall through.
    if any_empty {
        read_arms.push(quote!(_ => return #rt::Err(#rt::expected_empty(bytes)),));
    }
    quote! {
        #doc
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum #name {
            #(#variants,)*
        }
        impl #name {
            #command_fn
            #payload_fns
            /// Read the payload of `command` from exactly `bytes`.
            ///
            /// # Errors
            /// `DecodeError::PayloadLength` if the payload's size is not the command's, or any
            /// error of the payload's fields (an unknown enum value, ...).
            pub fn read_payload(command: Command, bytes: &[u8]) -> #rt::DecodeResult<Self> {
                // `?` in each arm and one `Ok`: every error leaves by one path.
                let message = match command {
                    #(#read_arms)*
                };
                #rt::Ok(message)
            }
        }
    }
}

/// `visit_payload` (whose body, `visit`, opens the message once), and `payload_len` and
/// `write_payload` through it.
fn emit_payload_fns(rt: &TokenStream, visit: TokenStream) -> TokenStream {
    quote! {
        /// Hands the payload to `v` (`&()` when the command carries none): the one place
        /// that opens the message, for [`payload_len`](Self::payload_len) and
        /// [`write_payload`](Self::write_payload).
        #[inline(always)]
        pub fn visit_payload<V: #rt::PayloadVisitor>(&self, v: V) -> V::Output {
            #visit
        }
        /// Bytes of the payload on the wire.
        #[inline(always)]
        pub fn payload_len(&self) -> usize {
            self.visit_payload(#rt::WireLen)
        }
        /// Write the payload.
        ///
        /// # Errors
        /// `EncodeError::BufferTooSmall` if `w` has too little room, `ValueOutOfRange` if a
        /// field's value does not fit its wire form.
        #[inline(always)]
        pub fn write_payload(&self, w: &mut #rt::Writer<'_>) -> #rt::EncodeResult {
            self.visit_payload(#rt::WritePayload(w))
        }
    }
}

fn emit_direction_message(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let variants = p.directions.iter().map(|d| {
        let v = format_ident!("{}", d.rust_name);
        let doc = doc_attrs(&format!("A {}. {}", d.name, d.doc));
        quote!(#doc #v(#v))
    });
    let names: Vec<_> = p
        .directions
        .iter()
        .map(|d| format_ident!("{}", d.rust_name))
        .collect();
    let payload_fns = emit_payload_fns(
        rt,
        quote!(match self { #(Self::#names(m) => m.visit_payload(v),)* }),
    );
    quote! {
        /// A decoded message: its direction, then the command and payload.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Message {
            #(#variants,)*
        }
        impl Message {
            /// The command of this message.
            #[inline(always)]
            pub const fn command(&self) -> Command {
                match self {
                    #(Self::#names(m) => m.command(),)*
                }
            }
            #payload_fns
        }
    }
}

/// The condition that a header is of direction `rule`, as an expression over `header`.
fn direction_test(p: &Protocol, f: &Frame, rule: &DirectionRule) -> TokenStream {
    match rule {
        DirectionRule::InSet { value, set } => {
            let v = &f.values[*value];
            let id = ident(&v.name);
            let a = &p.addresses[*set];
            let (first, last) = (int_lit(v.prim, a.first), int_lit(v.prim, a.last));
            quote!((#first..=#last).contains(&header.#id))
        }
        DirectionRule::Equals { value, equals } => {
            let id = ident(&f.values[*value].name);
            quote!((header.#id as u64) == #equals)
        }
    }
}

/// Reading the dispatch key of a frame into `id`, its value as a `u64` for
/// `UnknownCommand`, and writing `command`'s id into `frame`.
struct Key {
    read: TokenStream,
    as_u64: TokenStream,
    write: TokenStream,
}

fn packet_key(f: &Frame, rt: &TokenStream) -> Key {
    let consts: Vec<_> = f
        .dispatch
        .iter()
        .map(|&i| value_const("", &f.values[i]))
        .collect();
    let prims = key_prims(f);
    if let ([c], [prim]) = (&consts[..], &prims[..]) {
        let t = prim_type(*prim);
        return Key {
            read: quote!(let id: CommandId = header_value(frame, wire::#c)? as #t;),
            as_u64: quote!(id as u64),
            write: quote!(#rt::write_header(frame, wire::#c, command.id() as u64)?;),
        };
    }
    let vars: Vec<_> = (0..consts.len()).map(|i| format_ident!("k{}", i)).collect();
    let types: Vec<_> = prims.iter().map(|p| prim_type(*p)).collect();
    let idx: Vec<syn::Index> = (0..consts.len()).map(syn::Index::from).collect();
    let widths: Vec<u32> = f.dispatch.iter().map(|&i| f.values[i].width).collect();
    let mut key = quote!(0u64);
    for (v, w) in vars.iter().zip(&widths) {
        key = quote!(((#key) << #w) | (#v as u64));
    }
    Key {
        read: quote!(#(let #vars = header_value(frame, wire::#consts)? as #types;)* let id: CommandId = (#(#vars),*);),
        as_u64: quote!({ let (#(#vars),*) = id; #key }),
        write: quote!(let id = command.id(); #(#rt::write_header(frame, wire::#consts, id.#idx as u64)?;)*),
    }
}

/// The message of a decoded frame (by direction when the spec has directions), and the check
/// that an encoded message's direction matches its header.
fn packet_direction(p: &Protocol, f: &Frame, rt: &TokenStream) -> (TokenStream, TokenStream) {
    if p.directions.is_empty() {
        return (quote!(Message::read_payload(command, payload)?), quote!());
    }
    let names: Vec<_> = p
        .directions
        .iter()
        .map(|d| format_ident!("{}", d.rust_name))
        .collect();
    let tests: Vec<_> = p
        .directions
        .iter()
        .map(|d| direction_test(p, f, &d.rule))
        .collect();
    let message = quote! {
        #(if #tests { Message::#names(#names::read_payload(command, payload)?) } else)*
        { return #rt::Err(#rt::DecodeError::UnknownDirection); }
    };
    let check = quote! {
        let header = &self.header;
        let matches = match &self.message { #(Message::#names(_) => #tests,)* };
        if !matches {
            return #rt::Err(#rt::EncodeError::ValueOutOfRange);
        }
    };
    (message, check)
}

/// What acknowledgements add to `Packet`: their decoding (before the dispatch key, which they
/// lack), their length, the flag written on encoding, where the payload starts, and the
/// command id written (none for an acknowledgement).
#[derive(Default)]
struct AckParts {
    decode: TokenStream,
    len_arms: TokenStream,
    flag: TokenStream,
    start: TokenStream,
    write_key: TokenStream,
}

fn packet_ack(f: &Frame, key: &Key, rt: &TokenStream) -> AckParts {
    let write = &key.write;
    let Some((vi, ack_header_len)) = f.ack else {
        return AckParts {
            start: quote!(HEADER_LEN),
            write_key: quote!(let command = self.message.command(); #write),
            ..AckParts::default()
        };
    };
    let flag = value_const("", &f.values[vi]);
    // Validation gives the flag the role `Ack`; 1 is its only other possible value.
    let equals = match f.values[vi].role {
        crate::ir::Role::Ack(equals) => equals,
        _ => 1,
    };
    let other = 1 - equals;
    let max = f.max_len() - ack_header_len - f.trailer_len;
    let bare = f.bare_len.is_some();
    let end = if bare {
        quote!(if frame.len() == #ack_header_len { frame.len() } else { frame.len().saturating_sub(TRAILER_LEN) })
    } else {
        quote!(frame.len().saturating_sub(TRAILER_LEN))
    };
    let bare_arm = if bare {
        quote!(Message::Ack(data) if data.is_empty() => #ack_header_len,)
    } else {
        quote!()
    };
    AckParts {
        decode: quote! {
            if header_value(frame, wire::#flag)? == #equals {
                let data = frame
                    .get(#ack_header_len..#end)
                    .ok_or(#rt::DecodeError::Truncated { needed: #ack_header_len, available: frame.len() })?;
                let data = #rt::Bytes::from_slice(data).ok_or(#rt::DecodeError::PayloadLength { expected: #max, actual: data.len() })?;
                return #rt::Ok(Packet { header, message: Message::Ack(data) });
            }
        },
        len_arms: quote! {
            #bare_arm
            Message::Ack(data) => (#ack_header_len as usize).saturating_add(data.len()).saturating_add(TRAILER_LEN),
        },
        flag: quote! {
            let is_ack = matches!(self.message, Message::Ack(_));
            #rt::write_header(frame, wire::#flag, if is_ack { #equals } else { #other })?;
        },
        start: quote!(if matches!(self.message, Message::Ack(_)) { #ack_header_len } else { HEADER_LEN }),
        write_key: quote!(if let #rt::Some(command) = self.message.command() { #write }),
    }
}

/// `Packet::encoded_len`'s body: the frame's length, with acknowledgements' own lengths, and
/// with the bytes stuffing inserts (counted by writing the payload aside).
fn packet_encoded_len(f: &Frame, ack: &AckParts, rt: &TokenStream) -> TokenStream {
    let plain = quote!(
        HEADER_LEN
            .saturating_add(self.message.payload_len())
            .saturating_add(TRAILER_LEN)
    );
    let unstuffed = if ack.len_arms.is_empty() {
        plain
    } else {
        let arms = &ack.len_arms;
        quote!(match &self.message { #arms _ => #plain })
    };
    if f.stuffing.is_none() {
        return unstuffed;
    }
    quote! {
        let mut scratch = [0u8; MAX_PAYLOAD_LEN];
        let mut w = #rt::Writer::new(&mut scratch);
        let inserted = match self.message.write_payload(&mut w) {
            #rt::Ok(()) => STUFFING.count(w.written()),
            #rt::Err(_) => 0,
        };
        (#unstuffed).saturating_add(inserted)
    }
}

/// Byte stuffing: the payload is unstuffed before it is read, stuffed after it is written;
/// the `STUFFING` const.
fn packet_stuffing(f: &Frame, rt: &TokenStream) -> (TokenStream, TokenStream, TokenStream) {
    match &f.stuffing {
        Some((after, insert)) => (
            quote! {
                let mut unstuffed = [0u8; MAX_PAYLOAD_LEN];
                let payload = STUFFING.unstuff(payload, &mut unstuffed)?;
            },
            quote!(let plen = STUFFING.stuff_in_place(region, plen)?;),
            quote! {
                /// The payload's byte stuffing: the sender inserts `insert` after every `after`.
                pub const STUFFING: #rt::Stuffing<'static> = #rt::Stuffing { after: &[#(#after),*], insert: #insert };
            },
        ),
        None => (quote!(), quote!(), quote!()),
    }
}

/// The trailer's length in an encoded frame: a bare header (the header alone) has none.
fn packet_trailer(f: &Frame) -> TokenStream {
    if f.bare_len.is_some() {
        quote!(if start == HEADER_LEN || plen > 0 {
            TRAILER_LEN
        } else {
            0
        })
    } else {
        quote!(TRAILER_LEN)
    }
}

/// `Packet`: the header values and the message of the first frame format, decoded from and
/// encoded to a frame through `LAYOUT`.
fn emit_packet(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let (header_fields, header_writes) = header_codec(f, "", rt);
    let key = packet_key(f, rt);
    let (message, direction_check) = packet_direction(p, f, rt);
    let ack = packet_ack(f, &key, rt);
    let encoded_len = packet_encoded_len(f, &ack, rt);
    let (read_key, key_u64) = (&key.read, &key.as_u64);
    let AckParts {
        decode: ack_decode,
        flag: ack_flag,
        start: start_of,
        write_key,
        ..
    } = &ack;
    let (unstuff, stuff, stuffing_const) = packet_stuffing(f, rt);
    let trailer_of = packet_trailer(f);
    quote! {
        #stuffing_const
        /// A header value of a frame (inlined: with the field a constant, a load at a fixed offset).
        #[inline(always)]
        fn header_value(frame: &[u8], field: #rt::WordField) -> #rt::DecodeResult<u64> {
            field.read(frame).ok_or(#rt::DecodeError::Truncated { needed: HEADER_LEN, available: frame.len() })
        }
        /// A whole frame, decoded: the header values and the message.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct Packet {
            /// The header values the sender set.
            pub header: Header,
            /// The command and its payload.
            pub message: Message,
        }
        impl Packet {
            /// Decode the frame at the start of `bytes`, checking its framing (sync, length,
            /// checks) first.
            ///
            /// # Errors
            /// `DecodeError::Frame` if the bytes are not a valid frame, `Truncated` if they
            /// end early, and the errors of [`Packet::from_frame`].
            pub fn decode(bytes: &[u8]) -> #rt::DecodeResult<Self> {
                Self::from_frame(LAYOUT.parse(bytes)?)
            }
            /// Decode a frame whose framing a decoder already checked.
            ///
            /// # Errors
            /// `UnknownCommand` for an id the spec does not have, `UnknownDirection` when the
            /// header matches no direction, `PayloadLength` when the payload's size is not the
            /// command's, and errors of the payload's fields.
            pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                let header = Header { #(#header_fields,)* };
                #ack_decode
                #read_key
                let command = Command::from_id(id).ok_or(#rt::DecodeError::UnknownCommand { key: #key_u64 })?;
                let payload = frame
                    .get(HEADER_LEN..frame.len().saturating_sub(TRAILER_LEN))
                    .ok_or(#rt::DecodeError::Truncated { needed: HEADER_LEN + TRAILER_LEN, available: frame.len() })?;
                #unstuff
                let message = #message;
                #rt::Ok(Packet { header, message })
            }
            /// Bytes of the encoded frame.
            #[inline(always)]
            pub fn encoded_len(&self) -> usize {
                #encoded_len
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is shorter than [`Packet::encoded_len`],
            /// `ValueOutOfRange` if a header value does not fit its field or does not match the
            /// message's direction.
            #[inline(always)]
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                #direction_check
                let needed = self.encoded_len();
                let available = buf.len();
                if available < needed {
                    return #rt::Err(#rt::EncodeError::BufferTooSmall { needed, available });
                }
                let start = #start_of;
                // The payload first, in place: its size on the wire decides the frame's length.
                let region = buf
                    .get_mut(start..available.saturating_sub(TRAILER_LEN))
                    .ok_or(#rt::EncodeError::BufferTooSmall { needed, available })?;
                let mut w = #rt::Writer::new(region);
                self.message.write_payload(&mut w)?;
                let plen = w.position();
                #stuff
                let total = start.saturating_add(plen).saturating_add(#trailer_of);
                let frame = buf.get_mut(..total).ok_or(#rt::EncodeError::BufferTooSmall { needed: total, available })?;
                #(#header_writes)*
                #ack_flag
                #write_key
                LAYOUT.seal(frame)?;
                #rt::Ok(total)
            }
        }
    }
}

/// `<Name>Packet` for a frame format without dispatch key: every frame carries one struct.
fn emit_message_packet(
    p: &Protocol,
    f: &Frame,
    si: usize,
    prefix: &str,
    rt: &TokenStream,
) -> TokenStream {
    let header = format_ident!("{}", f.names.header);
    let packet = format_ident!("{}", f.names.packet);
    let st = ident(&p.structs[si].name);
    let layout = super::const_ident(&format!("{prefix}LAYOUT"));
    let header_len = super::const_ident(&format!("{prefix}HEADER_LEN"));
    let trailer_len = super::const_ident(&format!("{prefix}TRAILER_LEN"));
    let (reads, writes) = header_codec(f, prefix, rt);
    let doc = format!(
        " A whole `{}` frame, decoded: the header values and its `{}`.",
        f.name, p.structs[si].name
    );
    quote! {
        #[doc = #doc]
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct #packet {
            /// The header values the sender set.
            pub header: #header,
            /// What the frame carries.
            pub payload: #st,
        }
        impl #packet {
            /// Decode the frame at the start of `bytes`, checking its framing first.
            ///
            /// # Errors
            /// `DecodeError::Frame` if the bytes are not a valid frame, `Truncated` if they end
            /// early, `PayloadLength` if the payload's size does not fit the struct.
            pub fn decode(bytes: &[u8]) -> #rt::DecodeResult<Self> {
                Self::from_frame(#layout.parse(bytes)?)
            }
            /// Decode a frame whose framing a decoder already checked.
            ///
            /// # Errors
            /// `PayloadLength` if the payload's size does not fit the struct, and errors of its
            /// fields.
            pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                let payload = frame
                    .get(#header_len..frame.len().saturating_sub(#trailer_len))
                    .ok_or(#rt::DecodeError::Truncated { needed: #header_len + #trailer_len, available: frame.len() })?;
                #rt::Ok(#packet {
                    header: #header { #(#reads,)* },
                    payload: #rt::Payload::from_bytes(payload)?,
                })
            }
            /// Bytes of the encoded frame.
            #[inline(always)]
            pub fn encoded_len(&self) -> usize {
                #header_len.saturating_add(#rt::Payload::wire_len(&self.payload)).saturating_add(#trailer_len)
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is too short, `ValueOutOfRange` if a
            /// header value does not fit its field.
            #[inline(always)]
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                let total = self.encoded_len();
                let available = buf.len();
                let frame = buf.get_mut(..total).ok_or(#rt::EncodeError::BufferTooSmall { needed: total, available })?;
                #(#writes)*
                let payload = frame
                    .get_mut(#header_len..total.saturating_sub(#trailer_len))
                    .ok_or(#rt::EncodeError::BufferTooSmall { needed: total, available })?;
                #rt::Payload::write(&self.payload, &mut #rt::Writer::new(payload))?;
                #layout.seal(frame)?;
                #rt::Ok(total)
            }
        }
    }
}

/// Reading the user-set header values of frame `f` into a header struct's fields, and writing
/// them back from `self.header`, through the `wire` consts of the frame (named with `prefix`).
fn header_codec(f: &Frame, prefix: &str, rt: &TokenStream) -> (Vec<TokenStream>, Vec<TokenStream>) {
    user_values(f)
        .map(|v| {
            let id = ident(&v.name);
            let c = value_const(prefix, v);
            let read = if v.prim == Prim::Bool {
                quote!(#id: header_value(frame, wire::#c)? != 0)
            } else {
                let t = prim_type(v.prim);
                quote!(#id: header_value(frame, wire::#c)? as #t)
            };
            let write = quote!(#rt::write_header(frame, wire::#c, self.header.#id as u64)?;);
            (read, write)
        })
        .unzip()
}
