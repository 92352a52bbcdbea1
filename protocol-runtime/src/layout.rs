//! The description of a frame format as data: where the sync bytes, the length, the checks and
//! the trailers are. Generated code builds one as a `static`; the run-time codec builds one
//! at run time from a spec. Both hand it to the same engine ([`crate::decoder`]) and the same
//! sealing step ([`FrameLayout::seal`]), so the wire rules exist once.

use crate::checksum::Checksum;
use crate::escape::Escape;

/// Byte order of a multi-byte value on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ByteOrder {
    /// Least significant byte first.
    Little,
    /// Most significant byte first.
    Big,
}

/// A position in a frame, counted from its first byte or back from its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pos {
    /// Offset from the first byte of the frame.
    Start(usize),
    /// Distance back from the end of the frame: `End(2)` is where the last two bytes start.
    End(usize),
}

impl Pos {
    /// The absolute offset of this position in a frame of `frame_len` bytes, or `None` if it
    /// falls outside the frame.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn resolve(self, frame_len: usize) -> Option<usize> {
        match self {
            Pos::Start(n) => {
                if n <= frame_len {
                    Some(n)
                } else {
                    None
                }
            }
            Pos::End(n) => frame_len.checked_sub(n),
        }
    }
}

/// An unsigned integer of 1, 2, 4 or 8 bytes at a position of the frame, optionally narrowed to
/// some of its bits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct WordField {
    /// Where the word starts.
    pub at: Pos,
    /// Bytes of the word: 1, 2, 4 or 8.
    pub size: u8,
    /// Byte order of the word.
    pub order: ByteOrder,
    /// Lowest bit of the value inside the word.
    pub shift: u8,
    /// Number of bits of the value (1 ..= 8 * size).
    pub width: u8,
}

impl WordField {
    /// A whole little-endian word of `size` bytes at `at` bytes from the frame's start (a
    /// single byte has no byte order; it is written as little-endian).
    #[must_use]
    pub const fn le(at: usize, size: u8) -> Self {
        Self::whole(Pos::Start(at), size, ByteOrder::Little)
    }

    /// A whole big-endian word of `size` bytes at `at` bytes from the frame's start.
    #[must_use]
    pub const fn be(at: usize, size: u8) -> Self {
        Self::whole(Pos::Start(at), size, ByteOrder::Big)
    }

    /// A whole word of `size` bytes at `at`, in byte order `order`.
    #[must_use]
    pub const fn whole(at: Pos, size: u8, order: ByteOrder) -> Self {
        Self {
            at,
            size,
            order,
            shift: 0,
            width: size.saturating_mul(8),
        }
    }

    /// The same word narrowed to `width` bits starting at bit `shift`.
    #[must_use]
    pub const fn bits(self, shift: u8, width: u8) -> Self {
        Self {
            shift,
            width,
            ..self
        }
    }
}

/// How the total length of a frame is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LengthRule {
    /// Every frame has this length.
    Fixed(usize),
    /// `total = field value + adjust`. The field must lie in the header.
    Field {
        /// The length field.
        field: WordField,
        /// Added to the field's value to give the total frame length.
        adjust: i64,
    },
    /// As [`LengthRule::Field`], except that a frame of exactly `bare` bytes is a bare header:
    /// no payload, no frame checks, no markers (a RoboRTS acknowledgement without data is the
    /// 12-byte header alone). `min_len` then applies to the other frames.
    FieldOrBare {
        /// The length field.
        field: WordField,
        /// Added to the field's value to give the total frame length.
        adjust: i64,
        /// Length of a bare header.
        bare: usize,
    },
    /// As [`LengthRule::Field`], with parts that header values decide: a wider length that a
    /// marker value of the field announces, and bytes after the checks that a flag announces.
    /// The field and the flag lie in the header; the wider field right after it.
    Conditional {
        /// The length field.
        field: WordField,
        /// Added to the count to give the total frame length (without the extension's and the
        /// flag trailer's bytes).
        adjust: i64,
        /// The wider length a marker value announces, if any.
        extension: Option<LengthExtension>,
        /// The bytes a flag announces, if any.
        trailer: Option<FlagTrailer>,
    },
}

/// A wider length announced by a marker value of the length field (MSP v1 jumbo frames: a size
/// byte of 255, then the size as a `u16le` after the command byte).
///
/// When the length field holds `marker`, the `wide` field, `len` bytes right after the header,
/// holds the count instead, and the payload starts `len` bytes later. The marker form is used
/// exactly when the count does not fit below the marker: a marker frame whose wide count is
/// below `marker` is not a valid frame ([`Reject::BadLength`](crate::decoder::Reject)), so
/// every frame has one encoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LengthExtension {
    /// The value of the length field that announces the wider length.
    pub marker: u64,
    /// The wider length field, which counts what the length field counts.
    pub wide: WordField,
    /// Bytes the wider field adds before the payload.
    pub len: usize,
}

/// Bytes at the very end of a frame, after its checks and trailers, present when a header flag
/// is set (the 13-byte MAVLink 2 signature when incompatibility flag `0x01` is set). The
/// checks and markers resolve their [`Pos::End`] positions against the frame without them.
/// The flag lies within the layout's `header_len` bytes: it decides the frame's length.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FlagTrailer {
    /// The flag: the bytes are present when it is not 0.
    pub flag: WordField,
    /// How many bytes.
    pub len: usize,
}

impl LengthRule {
    /// The length of a bare header, for [`LengthRule::FieldOrBare`].
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn bare_len(&self) -> Option<usize> {
        match *self {
            LengthRule::FieldOrBare { bare, .. } => Some(bare),
            _ => None,
        }
    }
}

/// A value the frame must hold: checked on decode, written on encode (reserved bytes, version
/// bits, a constant instruction, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Constant {
    /// Where the value is.
    pub field: WordField,
    /// The value it must have.
    pub value: u64,
}

/// A constant byte run at a fixed position (a trailer such as an end word).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Marker<'a> {
    /// Where it starts.
    pub at: Pos,
    /// The bytes.
    pub bytes: &'a [u8],
}

/// A check stored in the frame: an algorithm over a range of bytes, stored at a position.
#[derive(Debug, Clone, Copy)]
pub struct Check<'a> {
    /// The algorithm.
    pub checksum: Checksum<'a>,
    /// First byte covered.
    pub from: Pos,
    /// One past the last byte covered.
    pub to: Pos,
    /// Where the check value is stored.
    pub at: Pos,
    /// Byte order of the stored value (its size is the checksum's width).
    pub order: ByteOrder,
}

/// A frame format, as data.
#[derive(Debug, Clone, Copy)]
pub struct FrameLayout<'a> {
    /// Bytes every frame starts with (at least one, unless `sync_set` is not empty); after the
    /// byte of `sync_set`, if there is one.
    pub sync: &'a [u8],
    /// Bytes one of which every frame starts with (before `sync`): the frame's first header
    /// value is then the sync the decoder searches for (a CRSF device address: `C8`, `EA`,
    /// ...). Empty: the frame starts with `sync` alone.
    pub sync_set: &'a [u8],
    /// Bytes needed to know the frame's length and verify its header checks.
    pub header_len: usize,
    /// Smallest valid total length.
    pub min_len: usize,
    /// Largest valid total length.
    pub max_len: usize,
    /// How the total length is known.
    pub length: LengthRule,
    /// Values that must hold, all inside the header.
    pub constants: &'a [Constant],
    /// Checks entirely inside the header (covered bytes and stored value): verified before the
    /// length is trusted, computed on encode before the frame checks.
    pub header_checks: &'a [Check<'a>],
    /// Checks over the whole frame, verified once the frame is complete, computed on encode in
    /// this order.
    pub frame_checks: &'a [Check<'a>],
    /// Constant byte runs after the payload.
    pub markers: &'a [Marker<'a>],
    /// The bytes between the frame's flags are escaped on the wire (HDLC, SLIP, SHDLC): the
    /// rest of the layout describes the frame unescaped, whose sync and last marker are the
    /// flag. The stream engine unescapes as the bytes come and ends a candidate at the next
    /// flag (`decoder/escaped.rs`); the encoder escapes after sealing. [`probe`](Self::probe)
    /// and [`parse`](Self::parse) take a frame unescaped, as the engine yields it;
    /// [`parse_wire`](Self::parse_wire) takes it as it is on the wire.
    pub escape: Option<Escape<'a>>,
}

/// Where the engine finds a frame format: a [`FrameLayout`] reference built at run time (the
/// run-time codec), or a zero-sized type whose [`layout`](Self::layout) returns a `static`
/// (generated code).
///
/// Why a trait and not always a reference: the engine reads the layout for every candidate
/// (the sync bytes, the length field, each check's positions and algorithm). Through a
/// reference held in a field those reads stay reads, and the engine interprets the layout
/// frame after frame; through a zero-sized type they are reads of a constant, which the
/// compiler folds: the generic engine compiles to the code one would write for the one format,
/// and links only the checksums it uses.
///
/// ```
/// use protocol_runtime::layout::{FrameLayout, LayoutRef, LengthRule};
///
/// static FIXED: FrameLayout<'static> = FrameLayout {
///     sync: &[0xAA], sync_set: &[], header_len: 1, min_len: 4, max_len: 4, length: LengthRule::Fixed(4),
///     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
/// };
///
/// #[derive(Clone, Copy)]
/// struct Fixed;
/// impl LayoutRef for Fixed {
///     #[inline(always)]
///     fn layout(&self) -> &FrameLayout<'_> {
///         &FIXED
///     }
/// }
/// assert_eq!(Fixed.layout().max_len, (&FIXED).layout().max_len);
/// ```
pub trait LayoutRef: Copy {
    /// Whether a format of the link may escape its bytes ([`FrameLayout::escape`]). The
    /// engine tests it before it reads the layout: where it is `false` the escaped path
    /// (`decoder/escaped.rs`) is neither compiled nor linked, even at `opt-level = 0`, where
    /// a test of a constant layout's value is not folded. `true` by default: a layout read
    /// at run time keeps every path. Generated code sets it from its spec.
    const ESCAPED: bool = true;

    /// Whether a format of the link may decide parts of its frames by header values
    /// ([`LengthRule::Conditional`]); as [`ESCAPED`](Self::ESCAPED), for the decoder's path
    /// of those frames.
    const HEADER_DECIDED: bool = true;

    /// Whether the link may have [`others`](Self::others); as [`ESCAPED`](Self::ESCAPED),
    /// for the engine's selection of a format by its sync, which probes a format read at run
    /// time and so holds every rule.
    const SEVERAL_FORMATS: bool = true;

    /// Whether a format of the link checks with a CRC (of any width, with or without a
    /// per-command byte) or a checksum object; as [`ESCAPED`](Self::ESCAPED), for the code
    /// of those checks on the decoder's and the encoder's paths: where it is `false`, only
    /// the sums, xors and Fletcher checks are compiled and linked, and a check of another kind
    /// neither verifies nor is written.
    const CRC_CHECKED: bool = true;

    /// The frame format (the link's first, when it has several).
    fn layout(&self) -> &FrameLayout<'_>;

    /// The link's other frame formats, after [`layout`](Self::layout): a candidate is probed
    /// by the first format whose sync it starts with, and the frame found says which
    /// ([`Frame::format`](crate::decoder::Frame::format): 0 for `layout`, 1 for the first of
    /// these, ...). None by default: a link of one format, for which every branch on the
    /// others folds away. The formats' syncs must tell them apart (none matches a prefix of
    /// another's).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn others(&self) -> &[FrameLayout<'_>] {
        &[]
    }
}

/// The frame formats of a link that has several (MAVLink 1 and 2, found by their start
/// markers `FE` and `FD`), held by reference: what the run-time codec hands the engine.
/// Generated code implements [`LayoutRef::others`] on its own zero-sized type instead.
#[derive(Debug, Clone, Copy)]
pub struct Formats<'l> {
    /// The first format.
    pub first: &'l FrameLayout<'l>,
    /// The others, in order.
    pub others: &'l [FrameLayout<'l>],
}

impl LayoutRef for Formats<'_> {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn layout(&self) -> &FrameLayout<'_> {
        self.first
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn others(&self) -> &[FrameLayout<'_>] {
        self.others
    }
}

/// The layout type of a layout read at run time: it declares every rule kind, so the engine
/// keeps every path. What the functions that take a layout by value run as.
pub(crate) type EveryKind = &'static FrameLayout<'static>;

impl<'l> LayoutRef for &'l FrameLayout<'l> {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn layout(&self) -> &FrameLayout<'_> {
        self
    }
}

/// Whether `$body` (with `$item` bound to each item of `$items`, in order) holds for every
/// item, stopping at the first that fails.
///
/// A lone item (the common case: one header check, one frame check) is matched apart: with a
/// layout known at compile time it is then a constant the compiler folds, which a loop only
/// gives where the compiler unrolls it (not at `opt-level = "s"`, where a loop over the checks
/// kept every checksum algorithm in firmware). Only one item is: every arm copies `$body`,
/// and with a layout read at run time (the interpreter) every copy holds every algorithm.
/// A macro, not a function taking a closure: a closure holding a checksum is large, and left
/// out of line its item is no longer a constant.
macro_rules! all_hold {
    ($items:expr, |$item:ident| $body:expr) => {
        match $items {
            [] => true,
            [$item] => $body,
            more => more.iter().all(|$item| $body),
        }
    };
}
pub(crate) use all_hold;
