//! Decoding a byte stream: the runtime's [`StreamDecoder`] on a format's layout finds the
//! frames, rejections and skipped bytes, and the codec decodes each frame it finds.
//!
//! This module owns the engine's buffer size: a const generic, chosen at run time as the
//! smallest of a few sizes that holds the format's largest frame, so that no valid frame is
//! refused for want of room, and at least the generated decoders' host default (2 KiB).
//! Finding and verifying frames is the engine's business.

use protocol_runtime::decoder::HOST_BUFFER_LEN;
use protocol_runtime::layout::LayoutRef;
use protocol_runtime::{Event, Frame, FrameLayout, PacketLayout, Reject, Stats, StreamDecoder};

use crate::{Codec, DecodeIssue, Decoded};

/// The most frame formats a [`Stream`] decodes at once: a link's command formats.
pub const LINK_FORMATS: usize = 8;

/// The layouts of a stream's formats held by value, so that a [`Stream`] owns what its engine
/// reads: the first, and the others of a link of several formats (`others[..n]`; the rest
/// repeat the first and are never read).
#[derive(Clone, Copy)]
struct Held<'c> {
    first: FrameLayout<'c>,
    others: [FrameLayout<'c>; LINK_FORMATS - 1],
    n: usize,
}

impl<'c> Held<'c> {
    /// `layouts` (at least one; at most [`LINK_FORMATS`] are held).
    fn new(first: FrameLayout<'c>, more: &[FrameLayout<'c>]) -> Self {
        let mut others = [first; LINK_FORMATS - 1];
        let n = more.len().min(others.len());
        for (slot, layout) in others.iter_mut().zip(more) {
            *slot = *layout;
        }
        Held { first, others, n }
    }
}

impl LayoutRef for Held<'_> {
    fn layout(&self) -> &FrameLayout<'_> {
        &self.first
    }

    fn others(&self) -> &[FrameLayout<'_>] {
        self.others.get(..self.n).unwrap_or_default()
    }
}

/// A frame format of a codec as the runtime's [`PacketLayout`]: its frames decode into
/// [`Decoded`] values, so that the runtime's `PacketDecoder` and the integrations built on it
/// (the `tokio` codec, the `embedded-io-async` reader) drive the run-time codec as they drive
/// generated code. Made by [`Codec::packet_layout`].
#[derive(Clone, Copy)]
pub struct Format<'c> {
    codec: &'c Codec<'c>,
    format: usize,
    layout: FrameLayout<'c>,
}

impl<'c> Format<'c> {
    pub(crate) fn new(codec: &'c Codec<'c>, format: usize, layout: FrameLayout<'c>) -> Self {
        Format {
            codec,
            format,
            layout,
        }
    }
}

impl LayoutRef for Format<'_> {
    fn layout(&self) -> &FrameLayout<'_> {
        &self.layout
    }
}

impl PacketLayout for Format<'_> {
    type Packet = Decoded;
    type Error = DecodeIssue;

    fn decode_packet(&self, frame: &Frame<'_>) -> Result<Decoded, DecodeIssue> {
        self.codec.decode_frame(self.format, frame.bytes)
    }
}

/// The engine with a buffer of one of the sizes a frame format may need. Boxed: the largest
/// buffer is a megabyte.
enum Engine<'c> {
    /// The host default of generated decoders ([`HOST_BUFFER_LEN`]): small chunks appended
    /// behind a pending frame for a few dozen chunks before the pending bytes move.
    B2048(Box<StreamDecoder<Held<'c>, HOST_BUFFER_LEN>>),
    B4096(Box<StreamDecoder<Held<'c>, 4096>>),
    B65600(Box<StreamDecoder<Held<'c>, 65_600>>),
    B1M(Box<StreamDecoder<Held<'c>, { 1 << 20 }>>),
}

/// What a [`Stream`] reports: the runtime's [`Event`]s, with each frame decoded.
#[derive(Debug, Clone, PartialEq)]
pub enum Item<'s> {
    /// A frame the engine accepted, and what the codec made of it.
    Frame {
        /// Offset of its first byte in the whole stream.
        offset: u64,
        /// The frame's bytes.
        bytes: &'s [u8],
        /// The decoded frame, or why the frame holds no message of the spec.
        decoded: Result<Decoded, DecodeIssue>,
    },
    /// A candidate starting at `offset` was rejected (as [`Event::Rejected`]).
    Rejected {
        /// Offset of the candidate's first byte in the stream.
        offset: u64,
        /// Why it was rejected.
        reason: Reject,
    },
    /// A run of bytes where no candidate starts (as [`Event::Skipped`]).
    Skipped {
        /// Offset of the run's first byte in the stream.
        offset: u64,
        /// Bytes in the run.
        len: usize,
    },
}

/// A stream decoder of one frame format, or of the command formats of a link. Made by
/// [`Codec::stream`] and [`Codec::link_stream`].
pub struct Stream<'c> {
    codec: &'c Codec<'c>,
    /// The frame format (index into the protocol's frames) of each of the engine's formats.
    formats: Vec<usize>,
    engine: Engine<'c>,
}

impl<'c> Stream<'c> {
    /// A stream of the frame formats `formats` (at least one), whose layouts are `layouts`.
    pub(crate) fn new(
        codec: &'c Codec<'c>,
        formats: Vec<usize>,
        layouts: &[FrameLayout<'c>],
    ) -> Option<Self> {
        let (first, more) = layouts.split_first()?;
        if layouts.len() > LINK_FORMATS || formats.len() != layouts.len() {
            return None;
        }
        let held = Held::new(*first, more);
        let max_len = layouts.iter().map(|l| l.max_len).max().unwrap_or(0);
        let engine = if max_len <= HOST_BUFFER_LEN {
            Engine::B2048(Box::new(StreamDecoder::new(held)))
        } else if max_len <= 4096 {
            Engine::B4096(Box::new(StreamDecoder::new(held)))
        } else if max_len <= 65_600 {
            Engine::B65600(Box::new(StreamDecoder::new(held)))
        } else {
            Engine::B1M(Box::new(StreamDecoder::new(held)))
        };
        Some(Stream {
            codec,
            formats,
            engine,
        })
    }

    /// The largest frame the engine's buffer holds. A format whose frames may be longer (more
    /// than a megabyte) has its longer frames rejected as bad lengths.
    pub fn capacity(&self) -> usize {
        match self.engine {
            Engine::B2048(_) => HOST_BUFFER_LEN,
            Engine::B4096(_) => 4096,
            Engine::B65600(_) => 65_600,
            Engine::B1M(_) => 1 << 20,
        }
    }

    /// The next item of the stream, consuming `input` as the engine reads it
    /// ([`StreamDecoder::next_event`]); `None` when `input` is used up and more is needed.
    pub fn next_item<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Item<'s>> {
        let (codec, formats) = (self.codec, &self.formats);
        let event = match &mut self.engine {
            Engine::B2048(d) => d.next_event(input),
            Engine::B4096(d) => d.next_event(input),
            Engine::B65600(d) => d.next_event(input),
            Engine::B1M(d) => d.next_event(input),
        }?;
        Some(item(codec, formats, event))
    }

    /// The items left in the engine's buffer at the end of the input
    /// ([`StreamDecoder::flush_event`]); `None` when none is left.
    pub fn flush_item(&mut self) -> Option<Item<'_>> {
        let (codec, formats) = (self.codec, &self.formats);
        let event = match &mut self.engine {
            Engine::B2048(d) => d.flush_event(),
            Engine::B4096(d) => d.flush_event(),
            Engine::B65600(d) => d.flush_event(),
            Engine::B1M(d) => d.flush_event(),
        }?;
        Some(item(codec, formats, event))
    }

    /// The engine's counts so far.
    pub fn stats(&self) -> &Stats {
        match &self.engine {
            Engine::B2048(d) => d.stats(),
            Engine::B4096(d) => d.stats(),
            Engine::B65600(d) => d.stats(),
            Engine::B1M(d) => d.stats(),
        }
    }
}

/// An event of the engine, its frame decoded by the format it came in (`formats[f.format]`).
fn item<'s>(codec: &Codec<'_>, formats: &[usize], event: Event<'s>) -> Item<'s> {
    match event {
        Event::Frame(f) => Item::Frame {
            offset: f.offset,
            bytes: f.bytes,
            decoded: codec.decode_frame(
                formats.get(f.format).copied().unwrap_or(usize::MAX),
                f.bytes,
            ),
        },
        Event::Rejected { offset, reason } => Item::Rejected { offset, reason },
        Event::Skipped { offset, len } => Item::Skipped { offset, len },
    }
}
