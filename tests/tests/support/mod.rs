//! The harness shared by the robustness suites (properties, fault injection, resource bounds,
//! no-alloc, the fuzz corpus) and by the `cargo fuzz` targets, which include this directory by
//! path so that CI replays the fuzz corpus through exactly the code the fuzzers run.
//!
//! It owns the list of specs under test ([`for_each_spec!`], written from the registry of
//! bundled specs by the build script), the [`Spec`]
//! trait that makes a generated module usable by generic code, a spec-driven generator of valid
//! frames ([`model`]) and of canonical payloads ([`payload`]), the checked stream driver ([`stream`]), the fault injector ([`fault`])
//! and the fuzz entry points ([`fuzz`]). It does not know any spec's structs by name: every
//! value is generated from the spec's checked IR, so a new spec needs no new generator code.
#![allow(dead_code, unused_macros, unused_imports)]

pub mod fault;
pub mod fuzz;
pub mod model;
pub mod oracle;
pub mod payload;
pub mod stream;

use std::fmt::Debug;

use protocol_kit::layout::LayoutRef;
use protocol_kit::{DecodeError, EncodeError, Event, Frame, FrameLayout, Stats, StreamDecoder};

// `for_each_spec!`: calls `$callback!(module, "path relative to the crate")` for every spec
// under test. The build script writes it from the registry of bundled specs
// (`tests/catalogue.toml`): adding a spec to every robustness suite (properties, faults,
// bounds, no-alloc, fuzz corpus) is its entry there. A spec whose directions are given to the
// decoder (no header field tells them) names the direction the suites decode and its decoders,
// after the path. A spec whose link has several frame formats says `link` after the path: the
// suites then run its link decoder (`any_decoder()`, `AnyPacket`) on frames of every format.
include!(concat!(env!("OUT_DIR"), "/for_each_spec.rs"));
pub(crate) use for_each_spec;

/// The packet type the suites test for a line of [`for_each_spec!`]: the link's `AnyPacket` for
/// a spec marked `link`, its `Packet` otherwise.
macro_rules! packet {
    ($name:ident, link) => {
        $crate::support::$name::AnyPacket
    };
    ($name:ident $(, $given:tt)*) => {
        $crate::support::$name::Packet
    };
}
pub(crate) use packet;

/// The largest frame of a link's formats (for [`Spec::MAX_FRAME_LEN`]).
pub const fn link_max_len(first: &FrameLayout<'_>, others: &[FrameLayout<'_>]) -> usize {
    let mut max = first.max_len;
    let mut i = 0;
    while i < others.len() {
        if others[i].max_len > max {
            max = others[i].max_len;
        }
        i += 1;
    }
    max
}

/// Whether `bytes` start as a frame of `layout` does (its sync, a value of its sync set): the
/// format a link's decoder would try them as. Fewer bytes than the sync match when they are a
/// prefix of it.
pub fn starts_as(layout: &FrameLayout<'_>, bytes: &[u8]) -> bool {
    let (lead, rest) = match (layout.sync_set.is_empty(), bytes.split_first()) {
        (false, Some((b, rest))) => (layout.sync_set.contains(b), rest),
        (false, None) => (true, bytes),
        (true, _) => (true, bytes),
    };
    lead && rest.iter().zip(layout.sync).all(|(a, b)| a == b)
}

/// Expands a spec with `protocol!` and implements [`Spec`] for its `Packet` (for its link's
/// `AnyPacket` when the line says `link`).
macro_rules! expand_spec {
    ($name:ident, $path:literal) => {
        expand_spec!(@ $name, $path, None, from_frame, decode);
    };
    ($name:ident, $path:literal, link) => {
        protocol_kit::protocol!($path);

        impl $crate::support::Spec for $name::AnyPacket {
            const NAME: &'static str = stringify!($name);
            const DIRECTION: Option<&'static str> = None;
            const PATH: &'static str = $path;
            const TEXT: &'static str =
                include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $path));
            const MAX_FRAME_LEN: usize =
                $crate::support::link_max_len(&$name::LAYOUT, &$name::ANY_OTHER_LAYOUTS);
            const DECODER_BUFFER_LEN: usize = $name::ANY_DECODER_BUFFER_LEN;
            type Decoder = $name::AnyDecoder;

            fn layout() -> &'static protocol_kit::FrameLayout<'static> {
                &$name::LAYOUT
            }
            fn layouts() -> Vec<&'static protocol_kit::FrameLayout<'static>> {
                std::iter::once(&$name::LAYOUT)
                    .chain($name::ANY_OTHER_LAYOUTS.iter())
                    .collect()
            }
            fn format_of(bytes: &[u8]) -> usize {
                // Without `layouts()`'s vector: decoding must not allocate (`no_alloc.rs`).
                std::iter::once(&$name::LAYOUT)
                    .chain($name::ANY_OTHER_LAYOUTS.iter())
                    .position(|l| $crate::support::starts_as(l, bytes))
                    .unwrap_or(0)
            }
            fn decoder() -> Self::Decoder {
                $name::any_decoder()
            }
            fn from_frame(frame: &[u8]) -> Result<Self, protocol_kit::DecodeError> {
                $name::AnyPacket::from_frame(&protocol_kit::Frame {
                    bytes: frame,
                    offset: 0,
                    format: <Self as $crate::support::Spec>::format_of(frame),
                })
            }
            fn decode(bytes: &[u8]) -> Result<Self, protocol_kit::DecodeError> {
                let format = <Self as $crate::support::Spec>::format_of(bytes);
                let layout = match format.checked_sub(1) {
                    Some(k) => &$name::ANY_OTHER_LAYOUTS[k],
                    None => &$name::LAYOUT,
                };
                $name::AnyPacket::from_frame(&protocol_kit::Frame {
                    bytes: layout.parse(bytes)?,
                    offset: 0,
                    format,
                })
            }
            fn encode(&self, buf: &mut [u8]) -> Result<usize, protocol_kit::EncodeError> {
                $name::AnyPacket::encode(self, buf)
            }
            fn encoded_len(&self) -> usize {
                $name::AnyPacket::encoded_len(self)
            }
        }
    };
    ($name:ident, $path:literal, $direction:literal, $from_frame:ident, $decode:ident) => {
        expand_spec!(@ $name, $path, Some($direction), $from_frame, $decode);
    };
    (@ $name:ident, $path:literal, $direction:expr, $from_frame:ident, $decode:ident) => {
        protocol_kit::protocol!($path);

        impl $crate::support::Spec for $name::Packet {
            const NAME: &'static str = stringify!($name);
            const DIRECTION: Option<&'static str> = $direction;
            const PATH: &'static str = $path;
            const TEXT: &'static str =
                include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/", $path));
            const MAX_FRAME_LEN: usize = $name::MAX_FRAME_LEN;
            const DECODER_BUFFER_LEN: usize = $name::DECODER_BUFFER_LEN;
            type Decoder = $name::Decoder;

            fn layout() -> &'static protocol_kit::FrameLayout<'static> {
                &$name::LAYOUT
            }
            fn decoder() -> Self::Decoder {
                $name::decoder()
            }
            fn from_frame(frame: &[u8]) -> Result<Self, protocol_kit::DecodeError> {
                $name::Packet::$from_frame(frame)
            }
            fn decode(bytes: &[u8]) -> Result<Self, protocol_kit::DecodeError> {
                $name::Packet::$decode(bytes)
            }
            fn encode(&self, buf: &mut [u8]) -> Result<usize, protocol_kit::EncodeError> {
                $name::Packet::encode(self, buf)
            }
            fn encoded_len(&self) -> usize {
                $name::Packet::encoded_len(self)
            }
        }
    };
}

for_each_spec!(expand_spec);

/// A generated protocol module, seen through its `Packet` type.
pub trait Spec: Sized + Debug + Clone + PartialEq + 'static {
    /// The module name.
    const NAME: &'static str;
    /// For a spec whose directions are given to the decoder: the direction the suites decode
    /// (`from_frame` and `decode` are that direction's decoders, and generated frames are of
    /// it).
    const DIRECTION: Option<&'static str>;
    /// The spec path, relative to the tests crate.
    const PATH: &'static str;
    /// The spec text (for the IR the generators work from).
    const TEXT: &'static str;
    /// The generated `MAX_FRAME_LEN`.
    const MAX_FRAME_LEN: usize;
    /// The generated `DECODER_BUFFER_LEN`.
    const DECODER_BUFFER_LEN: usize;
    /// The generated `Decoder` type.
    type Decoder: Dec;
    /// The generated `LAYOUT`.
    fn layout() -> &'static FrameLayout<'static>;
    /// The layouts of the frame formats the decoder finds, in the order of `Frame::format`:
    /// the first format's alone, or a link's formats.
    fn layouts() -> Vec<&'static FrameLayout<'static>> {
        vec![Self::layout()]
    }
    /// The format (index into [`Self::layouts`]) whose sync `bytes` start with (0 if none).
    fn format_of(bytes: &[u8]) -> usize {
        Self::layouts()
            .iter()
            .position(|l| starts_as(l, bytes))
            .unwrap_or(0)
    }
    /// The generated `decoder()`.
    fn decoder() -> Self::Decoder;
    /// `Packet::from_frame`.
    fn from_frame(frame: &[u8]) -> Result<Self, DecodeError>;
    /// `Packet::decode`.
    fn decode(bytes: &[u8]) -> Result<Self, DecodeError>;
    /// `Packet::encode`.
    fn encode(&self, buf: &mut [u8]) -> Result<usize, EncodeError>;
    /// `Packet::encoded_len`.
    fn encoded_len(&self) -> usize;

    /// The longest frame on the wire: `MAX_FRAME_LEN`, or, for a format that escapes its
    /// frames, the bound its escaped frames keep: twice `MAX_FRAME_LEN` less the two flags,
    /// which go as they are.
    fn wire_max_len() -> usize {
        match Self::layout().escape {
            Some(_) => 2 * Self::MAX_FRAME_LEN - 2,
            None => Self::MAX_FRAME_LEN,
        }
    }

    /// The packet encoded into a fresh buffer of exactly [`Self::wire_max_len`] bytes.
    fn to_vec(&self) -> Result<Vec<u8>, EncodeError> {
        let mut buf = vec![0u8; Self::wire_max_len()];
        let n = self.encode(&mut buf)?;
        buf.truncate(n);
        Ok(buf)
    }
}

/// The stream decoder API, for any buffer size (generated decoders differ only in `N`).
pub trait Dec {
    /// The buffer size `N`.
    const CAPACITY: usize;
    /// `StreamDecoder::next_event`.
    fn next_event<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Event<'s>>;
    /// `StreamDecoder::decode`.
    fn decode<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Frame<'s>>;
    /// `StreamDecoder::feed`.
    fn feed(&mut self, chunk: &[u8], sink: impl FnMut(Frame<'_>));
    /// `StreamDecoder::flush_event`.
    fn flush_event(&mut self) -> Option<Event<'_>>;
    /// `StreamDecoder::flush`.
    fn flush(&mut self) -> Option<Frame<'_>>;
    /// `StreamDecoder::pending`.
    fn pending(&self) -> usize;
    /// `StreamDecoder::position`.
    fn position(&self) -> u64;
    /// `StreamDecoder::stats`.
    fn stats(&self) -> Stats;
}

impl<L: LayoutRef, const N: usize> Dec for StreamDecoder<L, N> {
    const CAPACITY: usize = N;
    fn next_event<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Event<'s>> {
        StreamDecoder::next_event(self, input)
    }
    fn decode<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Frame<'s>> {
        StreamDecoder::decode(self, input)
    }
    fn feed(&mut self, chunk: &[u8], sink: impl FnMut(Frame<'_>)) {
        StreamDecoder::feed(self, chunk, sink)
    }
    fn flush_event(&mut self) -> Option<Event<'_>> {
        StreamDecoder::flush_event(self)
    }
    fn flush(&mut self) -> Option<Frame<'_>> {
        StreamDecoder::flush(self)
    }
    fn pending(&self) -> usize {
        StreamDecoder::pending(self)
    }
    fn position(&self) -> u64 {
        StreamDecoder::position(self)
    }
    fn stats(&self) -> Stats {
        *StreamDecoder::stats(self)
    }
}

/// Where random choices come from: a seeded generator ([`Rng`]) for the fault streams, or the
/// bytes of a proptest case or a fuzz input ([`Entropy`]), so that one generator serves all.
pub trait Source {
    /// 64 random bits.
    fn next_u64(&mut self) -> u64;

    /// A value in `0..n` (0 when `n` is 0). Takes only as many bytes as `n` needs, so that
    /// [`Entropy`] shrinks well.
    fn below(&mut self, n: u64) -> u64 {
        if n <= 1 {
            return 0;
        }
        self.next_u64() % n
    }

    /// A value in `lo..=hi`.
    fn range(&mut self, lo: u64, hi: u64) -> u64 {
        lo + self.below(hi - lo + 1)
    }

    /// A random byte.
    fn byte(&mut self) -> u8 {
        self.below(256) as u8
    }

    /// A length in `0..=max`, often an edge: 0, 1, `max - 1`, `max`, or small.
    fn len(&mut self, max: usize) -> usize {
        let max = max as u64;
        (match self.below(8) {
            0 => 0,
            1 => 1.min(max),
            2 => max.saturating_sub(1),
            3 => max,
            4 | 5 => self.below(max.min(16) + 1),
            _ => self.below(max + 1),
        }) as usize
    }

    /// True with probability `1 / n`.
    fn one_in(&mut self, n: u64) -> bool {
        self.below(n) == 0
    }

    /// `n` random bytes.
    fn bytes(&mut self, n: usize) -> Vec<u8> {
        (0..n).map(|_| self.byte()).collect()
    }
}

/// SplitMix64: small, seedable, and good enough to place faults.
#[derive(Debug, Clone)]
pub struct Rng(pub u64);

impl Source for Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

/// Choices read from given bytes (zeros once they run out).
#[derive(Debug, Clone)]
pub struct Entropy<'a>(pub &'a [u8]);

impl Entropy<'_> {
    fn take(&mut self, n: usize) -> u64 {
        let (head, rest) = self.0.split_at(n.min(self.0.len()));
        self.0 = rest;
        head.iter().fold(0, |acc, &b| (acc << 8) | u64::from(b))
    }
}

impl Source for Entropy<'_> {
    fn next_u64(&mut self) -> u64 {
        self.take(8)
    }

    fn below(&mut self, n: u64) -> u64 {
        if n <= 1 {
            return 0;
        }
        let bytes = (64 - (n - 1).leading_zeros()).div_ceil(8) as usize;
        self.take(bytes) % n
    }
}

/// The frame a decoder yields for `wire`, the bytes of one frame of `layout` as they go on the
/// wire: unescaped where the format escapes its frames ([`FrameLayout::escape`]), else `wire`
/// as it is.
///
/// # Panics
/// If `wire` is no escaped frame of such a format.
pub fn unescaped(layout: &FrameLayout<'_>, wire: &[u8]) -> Vec<u8> {
    let Some(escape) = layout.escape else {
        return wire.to_vec();
    };
    let mut out = vec![0u8; wire.len()];
    let n = escape
        .unescape(wire, &mut out)
        .unwrap_or_else(|e| panic!("{}: no escaped frame: {e:?}", hex(wire)));
    out.truncate(n);
    out
}

/// The bytes the unescaped `frame` of `layout` (as a decoder yields it) takes on the wire: its
/// escaped length where the format escapes its frames, else its length.
pub fn wire_len(layout: &FrameLayout<'_>, frame: &[u8]) -> usize {
    layout
        .escape
        .map_or(frame.len(), |escape| escape.escaped_len(frame))
}

/// The frame at the start of `wire` as `layout` parses it ([`FrameLayout::parse_wire`]:
/// unescaped first where the format escapes its frames).
pub fn parse_wire(layout: &FrameLayout<'_>, wire: &[u8]) -> Result<Vec<u8>, DecodeError> {
    let mut out = vec![0u8; layout.max_len];
    layout.parse_wire(wire, &mut out).map(<[u8]>::to_vec)
}

/// Bytes as hex, for assertion messages (the first 64 bytes of longer runs).
pub fn hex(bytes: &[u8]) -> String {
    let shown: String = bytes.iter().take(64).map(|b| format!("{b:02x}")).collect();
    if bytes.len() > 64 {
        format!("{shown}... ({} bytes)", bytes.len())
    } else {
        shown
    }
}
