//! `Packet`: the header values and the message of the first frame format, decoded from and
//! encoded to a frame through the format's `RULES` (the runtime's packet rules: payload,
//! acknowledgements, key, direction, stuffing, truncation, trailers, sealing). What stays here
//! is the key-to-struct match: which command a key names, which message a direction holds.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::frames::{can_first_methods, flag_trailer_len};
use super::given;
use super::key_prims;
use super::rules::rules_static;
use crate::codegen::frame::own_layouts;
use crate::codegen::ident;
use crate::codegen::payload::prim_type;
use crate::codegen::types::int_lit;
use crate::ir::{DirectionRule, Frame, Protocol, Transport};

/// The items of a frame format that its packet names, as validation named them.
pub(super) struct Items {
    pub max_payload_len: Ident,
    pub layout: Ident,
    pub rules: Ident,
    pub packet: Ident,
    pub header: Ident,
}

impl Items {
    pub(super) fn of(f: &Frame) -> Items {
        let id = |name: &str| format_ident!("{name}");
        Items {
            max_payload_len: id(&f.names.sizes.max_payload_len),
            layout: id(&f.names.layout_static),
            rules: rules_static(f),
            packet: id(&f.names.packet),
            header: id(&f.names.header),
        }
    }
}

/// The condition that a header is of direction `rule`, as an expression over `header` (the
/// typed header a user holds, for the integrations that route by direction).
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
        // Given directions have their own decoders.
        DirectionRule::Given => quote!(true),
    }
}

/// The key of a frame of format `f` as the `CommandId` of the link: `id`, from the rules'
/// `key` (one field) or `key_value`s (several). A value that does not fit the id's type is an
/// unknown command (a wider format of a link may carry keys the first cannot); a field no wider
/// than the id's type is cast.
pub(super) fn read_id(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let rules = rules_static(f);
    let prims = key_prims(p);
    let fits: Vec<TokenStream> = prims
        .iter()
        .zip(&f.dispatch)
        .enumerate()
        .map(|(i, (prim, &vi))| {
            let t = prim_type(*prim);
            let value = if prims.len() == 1 {
                quote!(key)
            } else {
                quote!(#rules.key_value(frame, #i)?)
            };
            if f.values[vi].width as usize <= prim.size() * 8 {
                quote!(#value as #t)
            } else {
                quote!(#t::try_from(#value).map_err(|_| #rt::unknown_command(key))?)
            }
        })
        .collect();
    let id = match &fits[..] {
        [one] => one.clone(),
        more => quote!((#(#more),*)),
    };
    quote! {
        let key = #rules.key(frame)?;
        let id: CommandId = #id;
        let command = Command::from_id(id).ok_or(#rt::unknown_command(key))?;
    }
}

/// A command's id as the values of the rules' key fields (`id` in scope).
pub(super) fn key_values(p: &Protocol) -> TokenStream {
    let n = key_prims(p).len();
    if n == 1 {
        return quote!([u64::from(id)]);
    }
    let idx = (0..n).map(syn::Index::from);
    quote!([#(u64::from(id.#idx)),*])
}

/// The message of a decoded command frame of format `f`: by the direction the rules read from
/// the header when the spec has directions.
pub(super) fn read_message(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    if p.directions.is_empty() || p.directions_given() {
        return quote!(Message::read_payload(command, payload)?);
    }
    let rules = rules_static(f);
    let arms = p.directions.iter().enumerate().map(|(i, d)| {
        let v = format_ident!("{}", d.rust_name);
        // `direction` names only the directions it tests: the last is all that is left.
        let pat = if i + 1 == p.directions.len() {
            quote!(_)
        } else {
            quote!(#i)
        };
        if d.empty {
            // Whatever the command: the header and no payload.
            return quote!(#pat => Message::#v(#rt::read_empty(command, payload)?),);
        }
        quote!(#pat => Message::#v(#v::read_payload(command, payload)?),)
    });
    quote!(match #rules.direction(frame)? { #(#arms)* })
}

/// The scratch a payload is unstuffed into: a buffer of the largest payload when the format
/// stuffs its payloads, else none.
pub(super) fn unstuff_scratch(f: &Frame) -> (TokenStream, TokenStream) {
    if f.stuffing.is_none() {
        return (quote!(), quote!(&mut []));
    }
    let max = Items::of(f).max_payload_len;
    (quote!(let mut scratch = [0u8; #max];), quote!(&mut scratch))
}

/// `Packet::body`: what a packet's frame carries, as the rules take it.
fn emit_body_fn(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let n = f.dispatch.len();
    let direction = if p.directions.is_empty() || p.directions_given() {
        quote!(#rt::None)
    } else {
        let arms = p.directions.iter().enumerate().map(|(i, d)| {
            let v = format_ident!("{}", d.rust_name);
            quote!(Message::#v(_) => #rt::Some(#i),)
        });
        quote!(match &self.message { #(#arms)* })
    };
    let keyless: Vec<_> = p
        .directions
        .iter()
        .filter_map(|d| Some((format_ident!("{}", d.rust_name), d.message?.1)))
        .collect();
    let command = if keyless.is_empty() && f.ack.is_none() {
        quote!(let command = self.message.command();)
    } else {
        let none = if keyless.is_empty() {
            quote!(#rt::Body::Ack)
        } else {
            let (names, starts): (Vec<_>, Vec<_>) = keyless.into_iter().unzip();
            let header_len = format_ident!("{}", f.names.sizes.header_len);
            let other = if f.ack.is_some() {
                quote!(#rt::Body::Ack)
            } else {
                quote!(#rt::Body::Struct { start: #header_len })
            };
            quote!(match &self.message { #(Message::#names(_) => #rt::Body::Struct { start: #starts },)* _ => #other })
        };
        quote! {
            let #rt::Some(command) = self.message.command() else {
                return #none;
            };
        }
    };
    let values = key_values(p);
    quote! {
        // A hint, not `inline(always)`: forced in, the key worked out here is threaded through
        // the payload writer's match at opt-level "s", a second jump table per command (HFLink
        // firmware 72 bytes larger, `bash benches/footprint.sh`).
        /// What the frame carries, as the packet rules take it; the key's values go into `key`.
        #[inline]
        fn body<'k>(&self, key: &'k mut [u64; #n]) -> #rt::Body<'k> {
            #command
            let id = command.id();
            *key = #values;
            #rt::Body::Command { key, carried: #rt::None, direction: #direction }
        }
    }
}

/// True when the format's rules may write a payload aside before placing it (trailing zeros,
/// stuffing, the carried fields of a format without extension fields).
fn may_write_aside(f: &Frame) -> bool {
    f.truncate_zeros || f.stuffing.is_some() || !f.extensions
}

/// The aside buffer a payload is written into before it is placed, when the format may write
/// aside, sized `len`; else none.
pub(super) fn aside(f: &Frame, len: &Ident) -> TokenStream {
    if may_write_aside(f) {
        quote!(&mut [0u8; #len])
    } else {
        quote!(&mut [])
    }
}

/// The frame at the start of `bytes` (the decoders' `decode`), as an expression: parsed
/// where it lies, or, for a format that escapes its frames, unescaped into a buffer of the
/// longest frame's size on the stack first (`FrameLayout::parse_wire`).
pub(super) fn parse_bytes(f: &Frame) -> TokenStream {
    let layout = format_ident!("{}", f.names.layout_static);
    if f.escape.is_some() {
        let max = format_ident!("{}", f.names.sizes.max_frame_len);
        quote!(#layout.parse_wire(bytes, &mut [0u8; #max])?)
    } else {
        quote!(#layout.parse(bytes)?)
    }
}

/// For a format that escapes its frames, the length of the frame on the wire, as an
/// expression: the frame encoded into a buffer on the stack (escaping may double the longest
/// frame) and measured. `body` and the encoding's arguments are bound; `unescaped` is the
/// length before escaping, the answer when the encoding fails (the encoder reports the
/// error). `None` for any other format.
pub(super) fn escaped_len(
    f: &Frame,
    rt: &TokenStream,
    encode: &TokenStream,
    unescaped: &TokenStream,
) -> Option<TokenStream> {
    f.escape.as_ref()?;
    let max = format_ident!("{}", f.names.sizes.max_frame_len);
    Some(quote! {
        let buf = &mut [0u8; 2 * #max];
        match #encode {
            #rt::Ok(n) => n,
            #rt::Err(_) => #unescaped,
        }
    })
}

/// The statement that encodes `self` as `body` into `buf`, through the rules'
/// `encode_message` (the aside buffer is empty where the format writes its payload in place).
/// The header is written by `Header::<write>`.
fn encode_body_with(
    f: &Frame,
    aside: &TokenStream,
    flagged: &TokenStream,
    write: &TokenStream,
) -> TokenStream {
    let rules = rules_static(f);
    let encode = encode_message(f);
    quote! {
        #rules.#encode(buf, #aside, &body, &self.message, #flagged, |frame| self.header.#write(frame))
    }
}

/// The rules' method that encodes a message of format `f`: for a serial format,
/// `encode_message_of` its layout type, which compiles only the rule kinds the format uses
/// (the encoder's paths of the other kinds are not linked, even unoptimised); a CAN frame has
/// no layout type and takes `encode_message`.
pub(super) fn encode_message(f: &Frame) -> TokenStream {
    if f.transport == Transport::Serial {
        let layout = format_ident!("{}", f.names.layout);
        quote!(encode_message_of::<#layout, _>)
    } else {
        quote!(encode_message)
    }
}

/// The bodies of `Packet::encoded_len` and `Packet::encode` through the layout of `f`, its
/// header written by `Header::<write>`.
fn encoding(f: &Frame, write: &TokenStream, rt: &TokenStream) -> (TokenStream, TokenStream) {
    let Items {
        max_payload_len,
        rules,
        ..
    } = Items::of(f);
    let flagged = flag_trailer_len(f);
    let aside = aside(f, &max_payload_len);
    let encode = encode_body_with(f, &aside, &flagged, write);
    let unescaped = quote!(#rules.message_len(&body, &self.message, #aside, #flagged));
    let len = match escaped_len(f, rt, &encode, &unescaped) {
        Some(measured) => quote! {
            let body = self.body(&mut key);
            #measured
        },
        None => quote!(#rules.message_len(&self.body(&mut key), &self.message, #aside, #flagged)),
    };
    (len, encode)
}

/// [`encoding`] for every direction: through the first format's layout, and through each
/// direction's own where one has fields of its own (chosen by the message's direction).
fn encodings(p: &Protocol, f: &Frame, rt: &TokenStream) -> (TokenStream, TokenStream) {
    let (len, encode) = encoding(f, &quote!(write), rt);
    let own: Vec<_> = own_layouts(p).collect();
    if own.is_empty() {
        return (len, encode);
    }
    let (mut len_arms, mut encode_arms) = (TokenStream::new(), TokenStream::new());
    for (d, of) in own {
        let v = format_ident!("{}", d.rust_name);
        let write = format_ident!("write_{}", d.name);
        let (l, e) = encoding(of, &quote!(#write), rt);
        len_arms.extend(quote!(Message::#v(_) => { #l }));
        encode_arms.extend(quote!(Message::#v(_) => #e,));
    }
    (
        quote!(match self.message { #len_arms _ => { #len } }),
        quote!(match self.message { #encode_arms _ => #encode }),
    )
}

/// `Packet::decode` and `Packet::from_frame` (with directions the decoder is given, the
/// decoders of each direction).
fn packet_decoders(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    if p.directions_given() {
        return given::decoders(p, f, rt);
    }
    let Items {
        rules,
        packet,
        header,
        ..
    } = Items::of(f);
    let ack = if f.ack.is_some() {
        quote! {
            if let #rt::Some(data) = #rules.ack_data(frame)? {
                let too_long = #rt::DecodeError::PayloadLength {
                    expected: #rules.ack_max(),
                    actual: data.len(),
                };
                let data = #rt::Bytes::from_slice(data).ok_or(too_long)?;
                return #rt::Ok(#packet { header, message: Message::Ack(data) });
            }
        }
    } else {
        quote!()
    };
    let id = read_id(p, f, rt);
    let parse = parse_bytes(f);
    let (scratch, scratch_ref) = unstuff_scratch(f);
    let message = read_message(p, f, rt);
    quote! {
        /// Decode the frame at the start of `bytes`, checking its framing (sync, length,
        /// checks) first.
        ///
        /// # Errors
        /// `DecodeError::Frame` if the bytes are not a valid frame, `Truncated` if they
        /// end early, and the errors of [`Self::from_frame`].
        pub fn decode(bytes: &[u8]) -> #rt::DecodeResult<Self> {
            Self::from_frame(#parse)
        }
        /// Decode a frame whose framing a decoder already checked.
        ///
        /// # Errors
        /// `UnknownCommand` for an id the spec does not have, `UnknownDirection` when the
        /// header matches no direction, `PayloadLength` when the payload's size is not the
        /// command's, and errors of the payload's fields.
        pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
            let header = #header::read(frame)?;
            #ack
            #id
            #scratch
            let payload = #rules.payload(frame, #scratch_ref)?;
            let message = #message;
            #rt::Ok(#packet { header, message })
        }
    }
}

/// `Packet`: the header values and the message of the first frame format, decoded from and
/// encoded to a frame through its `RULES`.
pub(super) fn emit_packet(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let Items { packet, header, .. } = Items::of(f);
    let decoders = packet_decoders(p, f, rt);
    let can = can_first_methods(f, rt);
    let body_fn = emit_body_fn(p, f, rt);
    let n = f.dispatch.len();
    let (len, encode) = encodings(p, f, rt);
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
    quote! {
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
            #can
            #body_fn
            /// Bytes of the encoded frame.
            #[inline(always)]
            pub fn encoded_len(&self) -> usize {
                let mut key = [0u64; #n];
                #len
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is shorter than [`Self::encoded_len`],
            /// `ValueOutOfRange` if a header value does not fit its field or does not tell the
            /// message's direction.
            #not_carried
            #[inline(always)]
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                let mut key = [0u64; #n];
                let body = self.body(&mut key);
                #encode
            }
        }
    }
}
