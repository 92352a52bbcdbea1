//! A link of several command formats: `<Name>Packet` for a format after the first that carries
//! the commands (its own dispatch key and header, the link's one `Message`), the payload rule
//! of a format without extension fields (`Message::base_len`, `read_base_payload`), and the
//! link's one decoder (`AnyLayout`, `any_decoder`) whose frames decode into an `AnyPacket`
//! that says which format each came in.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::frames::flag_trailer_len;
use super::packet::{Items, aside, parse_bytes, read_id, read_message, unstuff_scratch};
use crate::codegen::frame::emit_rule_kinds;
use crate::codegen::ident;
use crate::ir::{Frame, Protocol};
use crate::layout::RuleKinds;

/// `<Name>Packet` for a frame format with [`PacketKind::Commands`](crate::ir::PacketKind):
/// its header and the link's `Message`, decoded through its own layout and rules (its own
/// dispatch key: a key that does not fit the link's ids is an unknown command, an id that does
/// not fit the format's key fields is `ValueOutOfRange`).
pub(super) fn emit_commands_packet(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let first = &p.frames[0];
    let Items {
        rules,
        packet,
        header,
        ..
    } = Items::of(f);
    let parse = parse_bytes(f);
    // The whole payload is written aside before the format's part of it is placed.
    let aside_len = [first, f]
        .into_iter()
        .max_by_key(|g| g.payload_max)
        .map_or_else(
            || format_ident!("MAX_PAYLOAD_LEN"),
            |g| format_ident!("{}", g.names.sizes.max_payload_len),
        );
    let aside = aside(f, &aside_len);
    let id = read_id(p, f, rt);
    let (scratch, scratch_ref) = unstuff_scratch(f);
    let flagged = flag_trailer_len(f);
    let n = f.dispatch.len();
    // A format without extension fields carries the fields before them (`carried`).
    let (read, carried) = if f.extensions {
        (read_message(p, f, rt), quote!(#rt::None))
    } else {
        (
            quote!(Message::read_base_payload(command, payload)?),
            quote!(Message::base_len(command).map(|(base, _)| base)),
        )
    };
    let direction = if p.directions.is_empty() {
        quote!(#rt::None)
    } else {
        let arms = p.directions.iter().enumerate().map(|(i, d)| {
            let v = format_ident!("{}", d.rust_name);
            quote!(Message::#v(_) => #rt::Some(#i),)
        });
        quote!(match &self.message { #(#arms)* })
    };
    let key = if n == 1 {
        quote!([u64::from(id)])
    } else {
        let idx = (0..n).map(syn::Index::from);
        quote!([#(u64::from(id.#idx)),*])
    };
    let doc = format!(
        " A whole `{}` frame, decoded: the header values and the message (a command whose id \
         fits the format's dispatch key).",
        f.name
    );
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
            /// Decode the frame at the start of `bytes`, checking its framing first.
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
            /// header matches no direction, `PayloadLength` when the payload's size is not
            /// what this format carries of the command's, and errors of the payload's fields.
            pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                let header = #header::read(frame)?;
                #id
                #scratch
                let payload = #rules.payload(frame, #scratch_ref)?;
                let message = #read;
                #rt::Ok(#packet { header, message })
            }
            /// What the frame carries, as the packet rules take it; the key's values go into
            /// `key`.
            #[inline]
            fn body<'k>(&self, key: &'k mut [u64; #n]) -> #rt::Body<'k> {
                let command = self.message.command();
                let id = command.id();
                *key = #key;
                #rt::Body::Command { key, carried: #carried, direction: #direction }
            }
            /// Bytes of the encoded frame.
            pub fn encoded_len(&self) -> usize {
                let mut key = [0u64; #n];
                #rules.message_len(&self.body(&mut key), &self.message, #aside, #flagged)
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is too short, `ValueOutOfRange` if the
            /// command's id does not fit this format's dispatch key (the format does not carry
            /// it), a header value does not fit its field or does not tell the message's
            /// direction.
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                let mut key = [0u64; #n];
                let body = self.body(&mut key);
                #rules.encode_message(buf, #aside, &body, &self.message, #flagged, |frame| self.header.write(frame))
            }
        }
    }
}

/// `Message::base_len` and `Message::read_base_payload`: what a format without extension
/// fields carries of each command's payload.
pub(super) fn emit_base_payload(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let first = &p.frames[0];
    let filled_len = format_ident!("{}", first.names.sizes.max_payload_len);
    let arms: Vec<TokenStream> = p
        .commands
        .iter()
        .filter_map(|c| {
            let si = c.payloads.first().copied().flatten()?;
            let s = &p.structs[si];
            // A fixed-size struct without extension fields is carried whole: exactly its size,
            // not zero-filled as a first format that truncates trailing zeros reads it.
            let base = s.base_size.or((s.min_size == s.size).then_some(s.size))?;
            let (v, size) = (ident(&c.rust_name), s.size);
            Some(quote!(Command::#v => #rt::Some((#base, #size)),))
        })
        .collect();
    // The commands without an arm, when some have none.
    let rest = if arms.len() < p.commands.len() {
        quote!(_ => #rt::None,)
    } else {
        quote!()
    };
    quote! {
        impl Message {
            /// The bytes of `command`'s payload without its extension fields, and with them,
            /// for a command whose struct has extension fields or a fixed size.
            #[allow(clippy::match_same_arms)]
            pub const fn base_len(command: Command) -> #rt::Option<(usize, usize)> {
                match command {
                    #(#arms)*
                    #rest
                }
            }
            /// Read the payload of `command` as a format without extension fields carries it:
            /// exactly its fields before the extension fields, the extension fields zero.
            ///
            /// # Errors
            /// `DecodeError::PayloadLength` if the payload's size is not that, and the errors
            /// of [`Self::read_payload`].
            pub fn read_base_payload(command: Command, b: &[u8]) -> #rt::DecodeResult<Self> {
                match Self::base_len(command) {
                    #rt::Some((base, size)) => {
                        if b.len() != base {
                            return #rt::Err(#rt::DecodeError::PayloadLength { expected: base, actual: b.len() });
                        }
                        let mut filled = [0u8; #filled_len];
                        Self::read_payload(command, #rt::zero_filled(b, size, &mut filled)?)
                    }
                    #rt::None => Self::read_payload(command, b),
                }
            }
        }
    }
}

/// The link's one decoder: `AnyLayout` (the first format's layout and the others'),
/// `any_decoder`, and `AnyPacket`, a frame of any format decoded.
pub(super) fn emit_link(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let formats: Vec<&Frame> = p.link.iter().map(|&i| &p.frames[i]).collect();
    let Some((first, others)) = formats.split_first() else {
        return quote!();
    };
    let first_layout = format_ident!("{}", first.names.layout_static);
    let other_layouts: Vec<_> = others
        .iter()
        .map(|f| format_ident!("{}", f.names.layout_static))
        .collect();
    let n_others = others.len();
    let max_len = formats.iter().map(|f| f.max_len()).max().unwrap_or(0);
    let variants: Vec<_> = formats
        .iter()
        .map(|f| format_ident!("{}", f.names.pascal))
        .collect();
    let packets: Vec<_> = formats
        .iter()
        .map(|f| format_ident!("{}", f.names.packet))
        .collect();
    let variant_docs: Vec<_> = formats
        .iter()
        .map(|f| format!(" A `{}` frame.", f.name))
        .collect();
    let indices: Vec<usize> = (0..formats.len()).collect();
    let kinds = emit_rule_kinds(RuleKinds::of_link(formats.iter().copied()));
    quote! {
        /// The link's other command formats, after the first: the formats
        /// [`AnyLayout`] hands the engine.
        pub static ANY_OTHER_LAYOUTS: [#rt::FrameLayout<'static>; #n_others] = [#(#other_layouts),*];
        /// Every command format of the link as a type: the link's one decoder finds each
        /// format's frames by its sync, and says which format each came in (`Frame::format`,
        /// the index of its [`AnyPacket`] variant).
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
        pub struct AnyLayout;
        impl #rt::LayoutRef for AnyLayout {
            #kinds
            #[inline(always)]
            fn layout(&self) -> &#rt::FrameLayout<'_> {
                &#first_layout
            }
            #[inline(always)]
            fn others(&self) -> &[#rt::FrameLayout<'_>] {
                &ANY_OTHER_LAYOUTS
            }
        }
        /// Bytes of the buffer of an [`AnyDecoder`]: the largest frame of any format, the chunks
        /// staged behind it, and room for a checksum window; at least 2 KiB on hosts
        /// (`decoder_buffer_len` of the runtime).
        pub const ANY_DECODER_BUFFER_LEN: usize = #rt::decoder_buffer_len(#max_len);
        /// A streaming decoder of the frames of every command format of the link.
        pub type AnyDecoder = #rt::StreamDecoder<AnyLayout, ANY_DECODER_BUFFER_LEN>;
        /// A new decoder of the frames of every command format of the link.
        pub const fn any_decoder() -> AnyDecoder {
            #rt::StreamDecoder::new(AnyLayout)
        }
        /// A frame of any command format of the link, decoded: the variant says which format
        /// it came in.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum AnyPacket {
            #(#[doc = #variant_docs] #variants(#packets),)*
        }
        impl AnyPacket {
            /// Decode a frame an [`AnyDecoder`] found, by the format it came in.
            ///
            /// # Errors
            /// The errors of the format's packet's `from_frame`;
            /// `DecodeError::Frame(Reject::BadHeader)` for a format the link does not have.
            pub fn from_frame(frame: &#rt::Frame<'_>) -> #rt::DecodeResult<Self> {
                match frame.format {
                    #(#indices => #rt::Ok(Self::#variants(#packets::from_frame(frame.bytes)?)),)*
                    _ => #rt::Err(#rt::DecodeError::Frame(#rt::Reject::BadHeader)),
                }
            }
            /// The message, whatever the format.
            pub fn message(&self) -> &Message {
                match self {
                    #(Self::#variants(p) => &p.message,)*
                }
            }
            /// Bytes of the encoded frame, in its format.
            pub fn encoded_len(&self) -> usize {
                match self {
                    #(Self::#variants(p) => p.encoded_len(),)*
                }
            }
            /// Encode the frame, in its format, into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// The errors of the format's packet's `encode`.
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                match self {
                    #(Self::#variants(p) => p.encode(buf),)*
                }
            }
        }
    }
}
