//! The packets of the frame formats after the first: `<Name>Packet` for a format that carries
//! one struct, and for a CAN format; and the header codec every packet uses.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::packet::{Items, escaped_len, parse_bytes, unstuff_scratch};
use crate::codegen::ident;
use crate::ir::{Frame, Protocol, Transport};

/// `<Name>Packet` for a CAN frame format: decode from and encode to a `CanFrame`, through the
/// frame's virtual layout (id, length, data) so the runtime verifies and seals its checks, and
/// its rules, whose key is the CAN id.
pub(super) fn emit_can_packet(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let Items {
        layout,
        rules,
        packet,
        header,
        ..
    } = Items::of(f);
    // The virtual frame holds the identifier's number; its kind is the spec's.
    let is_extended = matches!(f.transport, Transport::Can { extended: true });
    let extended = if is_extended {
        quote!(.map(#rt::CanFrame::into_extended))
    } else {
        quote!()
    };
    let doc = format!(
        " A whole `{}` CAN frame, decoded: the header values and the message.",
        f.name
    );
    let decode_doc = " Decode a received CAN frame, verifying its checks.";
    // A message without a command (an acknowledgement of the first format) has no CAN id.
    let can_id = if super::message::command_none(p).is_some() {
        quote!(self.message.command().and_then(Command::can_id))
    } else {
        quote!(self.message.command().can_id())
    };
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
            /// payload's size is not the command's; `DecodeError::Frame(Reject::BadHeader)`
            /// for an identifier of the other kind (standard or extended) than the spec's.
            pub fn decode(can: &#rt::CanFrame) -> #rt::DecodeResult<Self> {
                let can = can.of_kind(#is_extended)?;
                let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
                let frame = #layout.parse(can.to_virtual(&mut virt))?;
                let key = #rules.key(frame)?;
                let command = u32::try_from(key)
                    .ok()
                    .and_then(Command::from_can_id)
                    .ok_or(#rt::unknown_command(key))?;
                let payload = #rules.payload(frame, &mut [])?;
                #rt::Ok(#packet {
                    header: #header::read(frame)?,
                    message: Message::read_payload(command, payload)?,
                })
            }
            /// Encode into a CAN frame.
            ///
            /// # Errors
            /// `EncodeError::ValueOutOfRange` when the command has no CAN id or a header value
            /// does not fit its field.
            pub fn encode(&self) -> #rt::Result<#rt::CanFrame, #rt::EncodeError> {
                let id = #can_id.ok_or(#rt::EncodeError::ValueOutOfRange { place: #rt::Place::NONE })?;
                let key = [u64::from(id)];
                let body = #rt::Body::Command { key: &key, carried: #rt::None, direction: #rt::None };
                let total = #rules.frame_len(&body, self.message.payload_len(), 0);
                if total > #rt::CAN_VIRTUAL_LEN {
                    return #rt::Err(#rt::EncodeError::PayloadTooLarge { len: total, max: #rt::CAN_VIRTUAL_LEN });
                }
                let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
                let len = #rules.assemble(
                    &mut virt,
                    &mut [],
                    &body,
                    || total,
                    0,
                    |w| self.message.write_payload(w),
                    |frame| self.header.write(frame),
                )?;
                #rt::CanFrame::from_virtual(virt.get(..len).unwrap_or_default())#extended
            }
        }
    }
}

/// The CAN methods of `Packet` when the first frame format is a CAN one (a CAN-only link, whose
/// dispatch key is a member of the identifier, `can_id_bits`): the frame is decoded from and
/// encoded to its virtual frame (identifier, length, data), as a later CAN format's packet is.
pub(super) fn can_first_methods(f: &Frame, rt: &TokenStream) -> TokenStream {
    let Transport::Can { extended } = f.transport else {
        return TokenStream::new();
    };
    let into_extended = if extended {
        quote!(.map(#rt::CanFrame::into_extended))
    } else {
        quote!()
    };
    quote! {
        /// Decode a received CAN frame, verifying its checks and constants.
        ///
        /// # Errors
        /// As [`Self::decode`]; `DecodeError::Frame(Reject::BadHeader)` for an identifier of
        /// the other kind (standard or extended) than the spec's.
        pub fn decode_can(can: &#rt::CanFrame) -> #rt::DecodeResult<Self> {
            let can = can.of_kind(#extended)?;
            let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
            Self::decode(can.to_virtual(&mut virt))
        }
        /// Encode into a CAN frame: the identifier assembled from its members, the data.
        ///
        /// # Errors
        /// As [`Self::encode`].
        pub fn encode_can(&self) -> #rt::Result<#rt::CanFrame, #rt::EncodeError> {
            let mut virt = [0u8; #rt::CAN_VIRTUAL_LEN];
            // Validation holds a CAN format's data to 8 bytes, so the virtual frame fits.
            let len = self.encode(&mut virt)?;
            #rt::CanFrame::from_virtual(virt.get(..len).unwrap_or_default())#into_extended
        }
    }
}

/// `<Name>Packet` for a frame format without dispatch key: every frame carries one struct.
pub(super) fn emit_message_packet(
    p: &Protocol,
    f: &Frame,
    si: usize,
    rt: &TokenStream,
) -> TokenStream {
    let Items {
        rules,
        packet,
        header,
        ..
    } = Items::of(f);
    let st = ident(&p.structs[si].name);
    let header_len = format_ident!("{}", f.names.sizes.header_len);
    let (scratch, scratch_ref) = unstuff_scratch(f);
    let flagged = flag_trailer_len(f);
    let parse = parse_bytes(f);
    let unescaped_len =
        quote!(#rules.frame_len(&body, #rt::Payload::wire_len(&self.payload), #flagged));
    let encode = quote! {
        #rules.assemble(
            buf,
            &mut [],
            &body,
            || #unescaped_len,
            #flagged,
            |w| #rt::Payload::write(&self.payload, w),
            |frame| self.header.write(frame),
        )
    };
    let len = escaped_len(f, rt, &encode, &unescaped_len).unwrap_or_else(|| unescaped_len.clone());
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
                Self::from_frame(#parse)
            }
            /// Decode a frame whose framing a decoder already checked.
            ///
            /// # Errors
            /// `PayloadLength` if the payload's size does not fit the struct, and errors of its
            /// fields.
            pub fn from_frame(frame: &[u8]) -> #rt::DecodeResult<Self> {
                #scratch
                let payload = #rules.payload(frame, #scratch_ref)?;
                #rt::Ok(#packet {
                    header: #header::read(frame)?,
                    payload: #rt::Payload::from_bytes(payload)?,
                })
            }
            /// Bytes of the encoded frame.
            #[inline(always)]
            pub fn encoded_len(&self) -> usize {
                let body = #rt::Body::Struct { start: #header_len };
                #len
            }
            /// Encode the frame into the start of `buf`; returns its length.
            ///
            /// # Errors
            /// `EncodeError::BufferTooSmall` if `buf` is too short, `ValueOutOfRange` if a
            /// header value does not fit its field.
            #[inline(always)]
            pub fn encode(&self, buf: &mut [u8]) -> #rt::Result<usize, #rt::EncodeError> {
                #rules.assemble(
                    buf,
                    &mut [],
                    &#rt::Body::Struct { start: #header_len },
                    || self.encoded_len(),
                    #flagged,
                    |w| #rt::Payload::write(&self.payload, w),
                    |frame| self.header.write(frame),
                )
            }
        }
    }
}

/// Bytes of the flag trailer of the frame being encoded (`self`), as an expression: 0 for a
/// frame without one.
pub(super) fn flag_trailer_len(f: &Frame) -> TokenStream {
    flag_trailer_len_of(f, &quote!(self.header))
}

/// [`flag_trailer_len`] of the header `header` (an expression of the header's type).
pub(super) fn flag_trailer_len_of(f: &Frame, header: &TokenStream) -> TokenStream {
    match &f.flag_trailer {
        Some(t) => {
            let (id, len) = (ident(&t.name), t.len);
            quote!(if #header.#id.is_some() { #len } else { 0usize })
        }
        None => quote!(0usize),
    }
}
