//! `Packet`: the header values and the message of the first frame format, decoded from and
//! encoded to a frame through `LAYOUT`, with the dispatch key, directions, acknowledgements and
//! byte stuffing the frame has.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::frames::{flag_trailer_len, header_codec};
use super::given;
use super::key_prims;
use crate::codegen::frame::wire_const;
use crate::codegen::ident;
use crate::codegen::payload::prim_type;
use crate::codegen::types::int_lit;
use crate::ir::{DirectionRule, Frame, Protocol};

/// The items of the first frame format that `Packet` names, as validation named them.
struct Items {
    header_len: Ident,
    trailer_len: Ident,
    max_payload_len: Ident,
    layout: Ident,
    packet: Ident,
    header: Ident,
}

impl Items {
    fn of(f: &Frame) -> Items {
        let id = |name: &str| format_ident!("{name}");
        Items {
            header_len: id(&f.names.sizes.header_len),
            trailer_len: id(&f.names.sizes.trailer_len),
            max_payload_len: id(&f.names.sizes.max_payload_len),
            layout: id(&f.names.layout_static),
            packet: id(&f.names.packet),
            header: id(&f.names.header),
        }
    }
}

/// The condition that a header is of direction `rule`, as an expression over `header`.
pub(crate) fn direction_test(p: &Protocol, f: &Frame, rule: &DirectionRule) -> TokenStream {
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
        // `packet_direction` leaves given directions to their own decoders.
        DirectionRule::Given => quote!(true),
    }
}

/// Reading the dispatch key of a frame into `id`, its value as a `u64` for
/// `UnknownCommand`, and writing `command`'s id into `frame`.
struct Key {
    read: TokenStream,
    as_u64: TokenStream,
    write: TokenStream,
}

fn packet_key(p: &Protocol, f: &Frame, rt: &TokenStream) -> Key {
    let header_len = Items::of(f).header_len;
    let consts: Vec<_> = f.dispatch.iter().map(|&i| wire_const(f, i)).collect();
    let prims = key_prims(p);
    if let ([c], [prim]) = (&consts[..], &prims[..]) {
        let t = prim_type(*prim);
        return Key {
            read: quote!(let id = #rt::header_value(frame, wire::#c, #header_len)? as #t;),
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
        read: quote!(#(let #vars = #rt::header_value(frame, wire::#consts, #header_len)? as #types;)* let id: CommandId = (#(#vars),*);),
        as_u64: quote!({ let (#(#vars),*) = id; #key }),
        write: quote!(let id = command.id(); #(#rt::write_header(frame, wire::#consts, id.#idx as u64)?;)*),
    }
}

/// The message of a decoded frame of format `f` (by direction when the spec has directions,
/// read from `f`'s own direction field), and the check that an encoded message's direction
/// matches its header.
pub(super) fn packet_direction(
    p: &Protocol,
    f: &Frame,
    rt: &TokenStream,
) -> (TokenStream, TokenStream) {
    if p.directions_given() {
        // Each direction has its own decoder (`given`); a message is written as it is.
        return (quote!(), quote!());
    }
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
        .map(|d| direction_test(p, f, &d.rule.in_frame(f)))
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

fn packet_ack(p: &Protocol, f: &Frame, key: &Key, rt: &TokenStream) -> AckParts {
    let Items {
        header_len,
        trailer_len,
        packet,
        ..
    } = Items::of(f);
    let write = &key.write;
    if let Some(k) = given::keyless(p, f, write, rt) {
        return AckParts {
            len_arms: k.len_arms,
            start: k.start,
            write_key: k.write_key,
            ..AckParts::default()
        };
    }
    let Some((vi, ack_header_len)) = f.ack else {
        return AckParts {
            start: quote!(#header_len),
            write_key: quote!(let command = self.message.command(); #write),
            ..AckParts::default()
        };
    };
    let flag = wire_const(f, vi);
    // Validation gives the flag the role `Ack`; 1 is its only other possible value.
    let equals = match f.values[vi].role {
        crate::ir::Role::Ack(equals) => equals,
        _ => 1,
    };
    let other = 1 - equals;
    let max = f.max_len() - ack_header_len - f.trailer_len;
    let bare = f.bare_len.is_some();
    let end = if bare {
        quote!(if frame.len() == #ack_header_len { frame.len() } else { frame.len().saturating_sub(#trailer_len) })
    } else {
        quote!(frame.len().saturating_sub(#trailer_len))
    };
    let bare_arm = if bare {
        quote!(Message::Ack(data) if data.is_empty() => #ack_header_len,)
    } else {
        quote!()
    };
    AckParts {
        decode: quote! {
            if #rt::header_value(frame, wire::#flag, #header_len)? == #equals {
                let data = frame
                    .get(#ack_header_len..#end)
                    .ok_or(#rt::DecodeError::Truncated { needed: #ack_header_len, available: frame.len() })?;
                let data = #rt::Bytes::from_slice(data).ok_or(#rt::DecodeError::PayloadLength { expected: #max, actual: data.len() })?;
                return #rt::Ok(#packet { header, message: Message::Ack(data) });
            }
        },
        len_arms: quote! {
            #bare_arm
            Message::Ack(data) => (#ack_header_len as usize).saturating_add(data.len()).saturating_add(#trailer_len),
        },
        flag: quote! {
            let is_ack = matches!(self.message, Message::Ack(_));
            #rt::write_header(frame, wire::#flag, if is_ack { #equals } else { #other })?;
        },
        start: quote!(if matches!(self.message, Message::Ack(_)) { #ack_header_len } else { #header_len }),
        write_key: quote!(if let #rt::Some(command) = self.message.command() { #write }),
    }
}

/// `Packet::encoded_len`'s body: the frame's length, with acknowledgements' own lengths, and
/// with the bytes stuffing inserts (counted by writing the payload aside).
fn packet_encoded_len(f: &Frame, ack: &AckParts, rt: &TokenStream) -> TokenStream {
    let Items {
        header_len,
        trailer_len,
        max_payload_len,
        ..
    } = Items::of(f);
    // With trailing-zero truncation the payload's size on the wire is known once it is
    // written: it is written aside and trimmed.
    let (sent, plen) = if f.truncate_zeros {
        (
            quote! {
                let mut aside = [0u8; #max_payload_len];
                let mut w = #rt::Writer::new(&mut aside);
                let sent = match self.message.write_payload(&mut w) {
                    #rt::Ok(()) => #rt::trimmed_len(w.written()),
                    #rt::Err(_) => self.message.payload_len(),
                };
            },
            quote!(sent),
        )
    } else {
        (quote!(), quote!(self.message.payload_len()))
    };
    let flagged = match f.flag_trailer {
        Some(_) => {
            let len = flag_trailer_len(f);
            quote!(.saturating_add(#len))
        }
        None => quote!(),
    };
    let short = quote!(
        #header_len
            .saturating_add(#plen)
            .saturating_add(#trailer_len)
    );
    // A wider length adds its bytes when the short form's count reaches the marker.
    let plain = match f.length_extension {
        Some(_) => {
            let layout = Items::of(f).layout;
            quote!({
                let short = #short;
                short.saturating_add(#layout.extension_for(short)) #flagged
            })
        }
        None => quote!(#short #flagged),
    };
    let unstuffed = if ack.len_arms.is_empty() {
        plain
    } else {
        let arms = &ack.len_arms;
        quote!(match &self.message { #arms _ => #plain })
    };
    if f.stuffing.is_none() {
        return quote!(#sent #unstuffed);
    }
    quote! {
        let mut scratch = [0u8; #max_payload_len];
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
    let max_payload_len = Items::of(f).max_payload_len;
    match &f.stuffing {
        Some((after, insert)) => (
            quote! {
                let mut unstuffed = [0u8; #max_payload_len];
                let payload = STUFFING.unstuff(payload, &mut unstuffed)?;
            },
            quote!(let plen = STUFFING.stuff_in_place(room, plen)?;),
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
    let Items {
        header_len,
        trailer_len,
        ..
    } = Items::of(f);
    if f.bare_len.is_some() {
        quote!(if start == #header_len || plen > 0 {
            #trailer_len
        } else {
            0
        })
    } else {
        quote!(#trailer_len)
    }
}

/// Where a frame's payload starts and its trailer ends, as `Packet` reads and writes them.
struct Spans {
    /// Bytes before the payload of a received `frame`.
    header_in: TokenStream,
    /// The statement that moves the written payload behind a wider length, if any.
    place: TokenStream,
    /// Bytes after the payload of a received `frame`.
    trailer_in: TokenStream,
    /// Bytes after the payload of a frame to send, at the most.
    trailer_out: TokenStream,
    /// What a flag trailer adds to the total of a frame to send.
    flagged_total: TokenStream,
}

impl Spans {
    fn of(f: &Frame) -> Spans {
        let Items {
            header_len,
            trailer_len,
            layout,
            ..
        } = Items::of(f);
        // A wider length: the payload starts after it when the frame has one.
        let (header_in, place) = match &f.length_extension {
            Some(_) => (
                quote!(#header_len.saturating_add(#layout.extension_len(frame))),
                quote!(let start = #layout.place_payload(buf, start, plen, #trailer_len)?;),
            ),
            None => (quote!(#header_len), quote!()),
        };
        // A flag trailer: its bytes after the trailer, when the header has them.
        let (trailer_in, trailer_out, flagged_total) = match &f.flag_trailer {
            Some(_) => {
                let flagged = flag_trailer_len(f);
                (
                    quote!(#trailer_len.saturating_add(#layout.flag_trailer_len(frame))),
                    quote!(#trailer_len.saturating_add(#flagged)),
                    quote!(.saturating_add(#flagged)),
                )
            }
            None => (quote!(#trailer_len), quote!(#trailer_len), quote!()),
        };
        Spans {
            header_in,
            place,
            trailer_in,
            trailer_out,
            flagged_total,
        }
    }
}

/// The start of `Packet::encode`: the payload written first, as its size on the wire decides
/// the frame's length. In place, or, when trailing zeros are dropped, aside and then placed
/// trimmed (the whole payload need not fit the frame's buffer). Defines `plen`, and `room`
/// (the bytes after the payload's start) when `stuffing` needs it.
fn payload_write(
    f: &Frame,
    stuffing: bool,
    trailer_out: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    if f.truncate_zeros {
        let max_payload_len = Items::of(f).max_payload_len;
        // Stuffing works in the room after the placed payload.
        let room = if stuffing { quote!(room) } else { quote!(_) };
        quote! {
            let mut aside = [0u8; #max_payload_len];
            let mut w = #rt::Writer::new(&mut aside);
            self.message.write_payload(&mut w)?;
            let (#room, plen) = #rt::place_trimmed(buf, start, #trailer_out, w.written())?;
        }
    } else {
        quote! {
            let room = #rt::payload_room(buf, self.encoded_len(), start, #trailer_out)?;
            let mut w = #rt::Writer::new(room);
            self.message.write_payload(&mut w)?;
            let plen = w.position();
        }
    }
}

/// `Packet::decode` and `Packet::from_frame` (with directions the decoder is given, the
/// decoders of each direction).
fn packet_decoders(
    p: &Protocol,
    f: &Frame,
    reads: &given::Reads<'_>,
    ack_decode: &TokenStream,
    message: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    if p.directions_given() {
        return given::decoders(p, f, reads, rt);
    }
    let Items {
        layout,
        packet,
        header,
        ..
    } = Items::of(f);
    let Spans {
        header_in,
        trailer_in,
        ..
    } = Spans::of(f);
    let given::Reads {
        header_fields,
        read_key,
        key_u64,
        unstuff,
    } = reads;
    {
        quote! {
            /// Decode the frame at the start of `bytes`, checking its framing (sync, length,
            /// checks) first.
            ///
            /// # Errors
            /// `DecodeError::Frame` if the bytes are not a valid frame, `Truncated` if they
            /// end early, and the errors of [`Self::from_frame`].
            pub fn decode(bytes: &[u8]) -> #rt::DecodeResult<Self> {
                Self::from_frame(#layout.parse(bytes)?)
            }
            /// Decode a frame whose framing a decoder already checked.
            ///
            /// # Errors
            /// `UnknownCommand` for an id the spec does not have, `UnknownDirection` when the
            /// header matches no direction, `PayloadLength` when the payload's size is not the
            /// command's, and errors of the payload's fields.
            pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                let header = #header { #(#header_fields,)* };
                #ack_decode
                #read_key
                let command = Command::from_id(id).ok_or(#rt::unknown_command(#key_u64))?;
                let payload = #rt::payload_of(frame, #header_in, #trailer_in)?;
                #unstuff
                let message = #message;
                #rt::Ok(#packet { header, message })
            }
        }
    }
}

/// `Packet`: the header values and the message of the first frame format, decoded from and
/// encoded to a frame through `LAYOUT`.
pub(super) fn emit_packet(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let Items {
        layout,
        packet,
        header,
        ..
    } = Items::of(f);
    let (header_fields, header_writes) = header_codec(f, rt);
    let key = packet_key(p, f, rt);
    let (message, direction_check) = packet_direction(p, f, rt);
    let ack = packet_ack(p, f, &key, rt);
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
    // A command only a wider format of the link carries.
    let not_carried = if f.commands.len() < p.commands.len() {
        quote! {
            ///
            /// A command whose id does not fit this format's dispatch key is `ValueOutOfRange`
            /// too: a wider format of the link carries it.
        }
    } else {
        quote!()
    };
    let Spans {
        place,
        trailer_out,
        flagged_total,
        ..
    } = Spans::of(f);
    let write = payload_write(f, !stuff.is_empty(), &trailer_out, rt);
    let reads = given::Reads {
        header_fields: &header_fields,
        read_key,
        key_u64,
        unstuff: &unstuff,
    };
    let decoders = packet_decoders(p, f, &reads, ack_decode, &message, rt);
    quote! {
        #stuffing_const
        /// A whole frame, decoded: the header values and the message.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub struct #packet {
            /// The header values the sender set.
            pub header: #header,
            /// The command and its payload.
            pub message: Message,
        }
        impl #packet {
            #decoders
            /// Bytes of the encoded frame.
            #[inline(always)]
            pub fn encoded_len(&self) -> usize {
                #encoded_len
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is shorter than [`Self::encoded_len`],
            /// `ValueOutOfRange` if a header value does not fit its field or does not match the
            /// message's direction.
            #not_carried
            #[inline(always)]
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                #direction_check
                let start = #start_of;
                #write
                #stuff
                #place
                let total = start.saturating_add(plen).saturating_add(#trailer_of)#flagged_total;
                let frame = #rt::frame_room(buf, total)?;
                #(#header_writes)*
                #ack_flag
                #write_key
                #layout.seal(frame)?;
                #rt::Ok(total)
            }
        }
    }
}
