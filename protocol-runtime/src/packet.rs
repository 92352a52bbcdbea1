//! Typed packets from a stream: [`PacketDecoder`] runs the stream engine and decodes every frame
//! it finds into the packet type of its format, reporting rejected candidates, frames that hold
//! no packet and skipped bytes as [`PacketEvent`]s, with one error type for all of them.
//!
//! This module owns the two traits a codec implements to be driven by the integrations (the
//! `tokio` codec, the `embedded-io-async` reader and writer): [`PacketLayout`] (a frame format
//! whose frames decode into packets: generated `Layout` types and the run-time codec's formats)
//! and [`EncodePacket`] (a packet that encodes into a frame: generated `Packet` types). It does
//! not find frames (the engine does) nor decode payloads (the codec does).

use crate::decoder::{Event, Frame, Reject, Stats, StreamDecoder};
use crate::error::{DecodeError, EncodeError};
use crate::layout::LayoutRef;

/// A frame format whose valid frames decode into packets.
///
/// Generated code implements it for each serial format's `Layout` type (`Packet` is the
/// format's packet type and `Error` is [`DecodeError`]); the run-time codec implements it for
/// its formats. A frame rejected by the engine becomes an `Error` through `From<Reject>`, so a
/// stream's rejections and its undecodable frames are one error type.
pub trait PacketLayout: LayoutRef {
    /// A whole decoded frame.
    type Packet;
    /// Why a candidate or a frame holds no packet.
    type Error: From<Reject>;

    /// Decodes a frame whose framing the engine checked (`Packet::from_frame` of its bytes in
    /// generated code; on a link of several formats, `AnyPacket::from_frame`, which reads the
    /// frame's [`format`](Frame::format)).
    ///
    /// # Errors
    /// Why the frame holds no packet of the spec (an unknown command, a payload of the wrong
    /// size, a field out of its type).
    fn decode_packet(&self, frame: &Frame<'_>) -> Result<Self::Packet, Self::Error>;
}

/// A packet that encodes into a frame of its format (generated `Packet` types implement it).
pub trait EncodePacket {
    /// Bytes of the encoded frame.
    fn encoded_len(&self) -> usize;

    /// Encodes the frame into the start of `buf`; returns its length.
    ///
    /// # Errors
    /// [`EncodeError::BufferTooSmall`] if `buf` is shorter than
    /// [`encoded_len`](Self::encoded_len), [`EncodeError::ValueOutOfRange`] if a value does not
    /// fit its field.
    fn encode_into(&self, buf: &mut [u8]) -> Result<usize, EncodeError>;
}

impl<P: EncodePacket + ?Sized> EncodePacket for &P {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn encoded_len(&self) -> usize {
        P::encoded_len(self)
    }
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn encode_into(&self, buf: &mut [u8]) -> Result<usize, EncodeError> {
        P::encode_into(self, buf)
    }
}

/// What a [`PacketDecoder`] reports: the engine's [`Event`]s, with every frame decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PacketEvent<P, E = DecodeError> {
    /// A valid frame, decoded.
    Packet {
        /// Offset of the frame's first byte in the stream.
        offset: u64,
        /// Bytes of the frame.
        len: usize,
        /// The packet.
        packet: P,
    },
    /// A candidate the engine rejected (`E::from(reject)`; the search resumed one byte after
    /// `offset`), or a valid frame that holds no packet of the spec.
    Invalid {
        /// Offset of the candidate's or the frame's first byte in the stream.
        offset: u64,
        /// Why.
        error: E,
    },
    /// A run of `len` bytes where no candidate starts (as [`Event::Skipped`]).
    Skipped {
        /// Offset of the run's first byte in the stream.
        offset: u64,
        /// Bytes in the run.
        len: usize,
    },
}

impl<P, E> PacketEvent<P, E> {
    /// The packet, if this event is one.
    pub fn packet(self) -> Option<P> {
        match self {
            PacketEvent::Packet { packet, .. } => Some(packet),
            _ => None,
        }
    }
}

/// The [`PacketEvent`] of an engine [`Event`].
fn packet_event<L: PacketLayout>(layout: &L, event: Event<'_>) -> PacketEvent<L::Packet, L::Error> {
    match event {
        Event::Frame(f) => match layout.decode_packet(&f) {
            Ok(packet) => PacketEvent::Packet {
                offset: f.offset,
                len: f.bytes.len(),
                packet,
            },
            Err(error) => PacketEvent::Invalid {
                offset: f.offset,
                error,
            },
        },
        Event::Rejected { offset, reason } => PacketEvent::Invalid {
            offset,
            error: L::Error::from(reason),
        },
        Event::Skipped { offset, len } => PacketEvent::Skipped { offset, len },
    }
}

/// A stream decoder that yields typed packets: the runtime's [`StreamDecoder`] with a buffer of
/// `N` bytes, each frame decoded by its [`PacketLayout`].
///
/// ```
/// # use protocol_runtime::layout::{ByteOrder, Check, LengthRule, Pos, WordField};
/// # use protocol_runtime::{Checksum, DecodeError, Frame, FrameLayout, LayoutRef, PacketLayout};
/// # static LAMP: FrameLayout<'static> = FrameLayout {
/// #     sync: &[0xAA],
/// #     sync_set: &[],
/// #     header_len: 3,
/// #     min_len: 4,
/// #     max_len: 12,
/// #     length: LengthRule::Field {
/// #         field: WordField { at: Pos::Start(1), size: 1, order: ByteOrder::Big, shift: 0, width: 8 },
/// #         adjust: 4,
/// #     },
/// #     constants: &[],
/// #     header_checks: &[],
/// #     frame_checks: &[Check {
/// #         checksum: Checksum::Sum8,
/// #         from: Pos::Start(0),
/// #         to: Pos::End(1),
/// #         at: Pos::End(1),
/// #         order: ByteOrder::Big,
/// #     }],
/// #     markers: &[],
/// #     escape: None,
/// # };
/// // A frame format (generated code writes this for every serial format of a spec):
/// // `AA len cmd payload sum8`, with one command, PING (id 2).
/// #[derive(Clone, Copy)]
/// struct LampLayout;
/// impl LayoutRef for LampLayout {
///     fn layout(&self) -> &FrameLayout<'_> {
///         &LAMP
///     }
/// }
/// #[derive(Debug, Clone, Copy, PartialEq, Eq)]
/// struct Ping;
/// impl PacketLayout for LampLayout {
///     type Packet = Ping;
///     type Error = DecodeError;
///     fn decode_packet(&self, frame: &Frame<'_>) -> Result<Ping, DecodeError> {
///         match frame.bytes.get(2) {
///             Some(2) => Ok(Ping),
///             Some(&id) => Err(DecodeError::UnknownCommand { key: id.into() }),
///             None => Err(DecodeError::Truncated { needed: 3, available: frame.bytes.len() }),
///         }
///     }
/// }
///
/// use protocol_runtime::{PacketDecoder, PacketEvent};
///
/// // A stray byte, a frame with a bad sum, a PING frame (AA 00 02 AC), cut in two chunks.
/// let stream = [0x42, 0xAA, 0x00, 0x02, 0xAD, 0xAA, 0x00, 0x02, 0xAC];
/// let mut decoder = PacketDecoder::<_, 64>::new(LampLayout);
/// let mut events = Vec::new();
/// for chunk in stream.chunks(5) {
///     events.extend(decoder.packets(chunk));
/// }
/// assert_eq!(events[0], PacketEvent::Skipped { offset: 0, len: 1 });
/// assert!(matches!(events[1], PacketEvent::Invalid { offset: 1, .. }));
/// assert_eq!(events.last(), Some(&PacketEvent::Packet { offset: 5, len: 4, packet: Ping }));
/// assert_eq!(decoder.stats().frames, 1);
/// ```
pub struct PacketDecoder<L: PacketLayout, const N: usize> {
    frames: StreamDecoder<L, N>,
}

impl<L: PacketLayout, const N: usize> PacketDecoder<L, N> {
    /// A decoder of `layout`'s packets with an empty buffer.
    pub const fn new(layout: L) -> Self {
        PacketDecoder {
            frames: StreamDecoder::new(layout),
        }
    }

    /// The next event, consuming from `*input` as needed (the slice is advanced); `None` when
    /// the input is used up and more is needed (a partial frame stays buffered).
    pub fn next_packet(&mut self, input: &mut &[u8]) -> Option<PacketEvent<L::Packet, L::Error>> {
        // A copy of the layout (a `Copy` handle): the event borrows the engine.
        let layout = *self.frames.layout_ref();
        let event = self.frames.next_event(input)?;
        Some(packet_event(&layout, event))
    }

    /// Declares the end of the input and returns the next event among the pending bytes; call
    /// until `None` (see [`StreamDecoder::flush`]).
    pub fn flush_packet(&mut self) -> Option<PacketEvent<L::Packet, L::Error>> {
        let layout = *self.frames.layout_ref();
        let event = self.frames.flush_event()?;
        Some(packet_event(&layout, event))
    }

    /// The events of `chunk`, as an iterator: [`next_packet`](Self::next_packet) until the
    /// chunk is used up. Bytes of the chunk the iterator has not reached when it is dropped are
    /// not fed.
    pub fn packets<'d, 'i>(&'d mut self, chunk: &'i [u8]) -> Packets<'d, 'i, L, N> {
        Packets {
            decoder: self,
            input: chunk,
        }
    }

    /// What the engine counted.
    pub fn stats(&self) -> &Stats {
        self.frames.stats()
    }

    /// The stream engine (its position, pending bytes, reset).
    pub fn frames(&mut self) -> &mut StreamDecoder<L, N> {
        &mut self.frames
    }

    /// The frame format.
    pub fn packet_layout(&self) -> &L {
        self.frames.layout_ref()
    }
}

impl<L: PacketLayout, const N: usize> core::fmt::Debug for PacketDecoder<L, N> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("PacketDecoder")
            .field("frames", &self.frames)
            .finish_non_exhaustive()
    }
}

/// The events of one chunk of input ([`PacketDecoder::packets`]).
pub struct Packets<'d, 'i, L: PacketLayout, const N: usize> {
    decoder: &'d mut PacketDecoder<L, N>,
    input: &'i [u8],
}

impl<L: PacketLayout, const N: usize> Iterator for Packets<'_, '_, L, N> {
    type Item = PacketEvent<L::Packet, L::Error>;

    fn next(&mut self) -> Option<Self::Item> {
        self.decoder.next_packet(&mut self.input)
    }
}
