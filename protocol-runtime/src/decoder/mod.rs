//! The one frame engine: deciding whether bytes are a frame ([`FrameLayout::probe`],
//! [`FrameLayout::parse`]) and finding frames in a byte stream that arrives in chunks
//! ([`StreamDecoder`]).
//!
//! This module owns the decoding rules of every frame format: the order of the checks, what a
//! rejection costs (one byte: the search resumes right after the rejected start), and the
//! accounting of every byte fed ([`Stats`]). It does not know what a payload means; generated
//! code dispatches on the frames it yields.
//!
//! # How a candidate is decided
//!
//! A candidate starts where the sync bytes (or, at the very end of the input, a prefix of
//! them) are found. Then, as soon as enough bytes are there:
//!
//! 1. with the header (`max(header_len, sync.len())` bytes): the [`Constant`]s
//!    ([`Reject::BadHeader`]), the header checks ([`Reject::BadHeaderCheck`]), and the length
//!    from the [`LengthRule`], which must lie in `min_len..=max_len` and fit the decoder's buffer
//!    ([`Reject::BadLength`]) — an impossible length is rejected before its bytes are awaited;
//! 2. with the whole frame: the frame checks in order ([`Reject::BadChecksum`]), then the
//!    [`Marker`]s ([`Reject::BadTrailer`]).
//!
//! A candidate whose bytes have not all arrived when the input runs out waits for more, with
//! one exception: if a complete valid frame starts among the bytes it already holds, the
//! candidate is taken for a truncated frame ([`Reject::Truncated`]) and the valid frame is
//! yielded at once, instead of being held back until the candidate's claimed length has
//! arrived (on a request/response link, that may be never). The price: a valid frame whose
//! payload holds another complete valid frame, cut by a chunk boundary just after the inner
//! one, yields the inner frame instead. With a CRC that needs a forged frame inside a payload;
//! with a weak sum it is rare (the sync bytes, a plausible length and a matching sum).
//!
//! Items of the header (constants, header checks, a length field) resolve their positions
//! against the header alone, so they use [`Pos::Start`](crate::layout::Pos::Start); frame checks
//! and markers resolve against the whole frame.
//!
//! # Target and build switches
//!
//! The frames and the stats are the same in every build but the ablated one; what
//! the target and the build choose is how the engine finds them: code size against speed. Each
//! switch is decided at compile time, so a build carries one side of it and tests nothing at
//! run time. The decoder's modules read theirs from one place (`decoder/target.rs`: `HOST`,
//! `SCAN_IN_PLACE`, `EARLY_TRUNCATION`); the checksums, which own theirs, test their `cfg`
//! where they use it. `BENCHMARKS.md` and `docs/performance.md` measure each.
//!
//! | switch | set by | what it changes | where |
//! | --- | --- | --- | --- |
//! | `target_pointer_width = "64"` (`HOST`) | the target | a host's choices, below | `decoder/`, `checksum/sum.rs` |
//! | `stage-input` feature | the user; CI on hosts | every chunk staged in the buffer first, as without `HOST`, to test that path on a host | `SCAN_IN_PLACE` |
//! | `crc-fast` feature | the user, on hosts (it needs `std`) | CRCs the `crc-fast` crate catalogues, over 128 bytes or more, computed by it ([`Slicing16::uses_crc_fast`]) | `checksum/fast.rs`, `checksum/slicing.rs` |
//! | `clmul` feature, with `target_arch = "x86_64"` and `target_feature = "pclmulqdq"` | the user, and `-C target-feature=+pclmulqdq` or `-C target-cpu=native` (no run-time detection: `safe_arch` offers the intrinsic only to such builds) | reflected CRCs of up to 32 bits over more than 8 bytes folded with carry-less multiplication ([`Slicing16::uses_clmul`]) | `checksum/clmul.rs`, `checksum/slicing.rs` |
//! | `protocol_ablate_early_truncation` cfg | the benchmark scripts only (`RUSTFLAGS="--cfg protocol_ablate_early_truncation"`) | the early-truncation rule left out, to measure what it costs: a candidate waits for its claimed length even when a frame is complete inside it. Never for use: it changes when frames are delivered and, on a link that goes quiet, whether (the rule's tests fail) | `EARLY_TRUNCATION` |
//!
//! A host is a target with 64-bit pointers: time counts for more than code size, and 64-bit
//! words and vector registers make wide compares cheap. Elsewhere (microcontrollers, and 32-bit
//! hosts with them) the smaller code wins: flash is scarce, a UART brings a few bytes at a
//! time, and a 64-bit word is a pair of registers. On a host:
//!
//! - the caller's chunk is scanned in place while nothing is pending, and frames found whole
//!   there borrow it; elsewhere every chunk is staged first, which saves a second copy of the
//!   scan (`SCAN_IN_PLACE`, `stream.rs`);
//! - the buffer holds at least [`HOST_BUFFER_LEN`] bytes, so the pending bytes seldom move to
//!   its front ([`decoder_buffer_len`]);
//! - 128 bytes stay free behind staged input, so that a window checksum reads a fixed-size
//!   block there (`STAGE_SLACK`, `buffer.rs`); chunks of 16 to 64 bytes are copied as two
//!   overlapping fixed-size moves instead of a call to `memcpy` (`copy_chunk`);
//! - the early-truncation search asks a block test first, 64 offsets at a time, reading whole
//!   blocks unmasked behind a staged chunk, where a filler is written for it (`stage`,
//!   `frame_may_be_inside`, `FILL`, `filler`); inlined, as the test usually answers. Elsewhere
//!   the exact search alone, out of line: it is called from two places (`frame_inside`);
//! - the search for a candidate tests the first offset before searching (on a clean stream the
//!   next frame starts there) and then calls `memchr`; elsewhere a byte loop, smaller than
//!   `memchr`'s word-at-a-time code (`find_sync`, `find_byte`, `search.rs`); inside a waiting
//!   candidate the sync's first byte is looked for eight bytes a step (`find_first_byte`);
//! - sums and xor over at most 128 bytes read a whole window under a mask, in 64-bit
//!   accumulators (`WINDOWS`, `ShortSum`, `checksum/sum.rs`).
//!
//! [`LengthRule`]: crate::layout::LengthRule
//! [`Slicing16::uses_crc_fast`]: crate::checksum::Slicing16::uses_crc_fast
//! [`Slicing16::uses_clmul`]: crate::checksum::Slicing16::uses_clmul

mod buffer;
mod conditional;
mod escaped;
mod event;
mod scan;
mod search;
mod stream;
mod target;

pub use buffer::{
    DecoderRam, HOST_BUFFER_LEN, decoder_buffer_len, decoder_buffer_len_for, decoder_ram,
    decoder_state_len,
};
pub use conditional::{flag_trailer, frame_body, frame_body_mut, write_flag_trailer};
pub use event::{Event, Frame, Reject, Stats};
pub use stream::StreamDecoder;

use crate::error::DecodeError;
use crate::layout::{
    Check, Constant, EveryKind, FrameLayout, LayoutRef, LengthRule, Marker, all_hold,
};
use crate::wire::{read_uint, write_uint};

/// Whether every byte that `data` and `expected` both have (the shorter's length) agrees: a
/// prefix of a sync cut by the end of the input matches.
///
/// A loop over indices, not `==` on slices nor an iterator adapter: sync words are a few
/// bytes, and a call (to `memcmp`, or to `Zip::next`, which the compiler may leave out of line
/// in a large caller) would cost more than the comparison, and hide that a constant sync of
/// one byte leaves nothing to compare.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn bytes_agree(data: &[u8], expected: &[u8]) -> bool {
    let mut i = 0;
    while let (Some(a), Some(b)) = (data.get(i), expected.get(i)) {
        if a != b {
            return false;
        }
        i = i.wrapping_add(1);
    }
    true
}

/// What [`FrameLayout::probe`] found at the start of some bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Probe {
    /// A valid frame of this total length starts here.
    Frame(usize),
    /// At least this many bytes (counted from the candidate's start) are needed to decide.
    Need(usize),
    /// No valid frame starts here.
    Reject(Reject),
}

impl Check<'_> {
    /// The covered range and the stored value's offset in a frame of `len` bytes.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn resolve(&self, len: usize) -> Option<(core::ops::Range<usize>, usize)> {
        let from = self.from.resolve(len)?;
        let to = self.to.resolve(len)?;
        Some((from..to, self.at.resolve(len)?))
    }

    /// Whether the value stored in `frame` is the check of the bytes it covers. Positions
    /// resolve against `frame.len()`; a range outside the frame does not verify.
    #[inline]
    pub fn verify(&self, frame: &[u8]) -> bool {
        self.verify_prefix(frame, frame.len())
    }

    /// [`verify`](Self::verify) for the `len`-byte frame at the start of `bytes`, which may run
    /// past it. The bytes after the frame are in reach of a window checksum
    /// ([`Checksum::compute_prefix`](crate::Checksum::compute_prefix): a fixed-size read
    /// instead of a loop whose trip count follows the frame length) but never change the
    /// verdict.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn verify_prefix(&self, bytes: &[u8], len: usize) -> bool {
        self.verify_prefix_of::<EveryKind>(bytes, len)
    }

    /// [`verify_prefix`](Self::verify_prefix) on a link of layout type `L`, which computes
    /// only the kinds of check `L` declares ([`LayoutRef::CRC_CHECKED`]).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn verify_prefix_of<L: LayoutRef>(&self, bytes: &[u8], len: usize) -> bool {
        let (Some(frame), Some((covered, at))) = (bytes.get(..len), self.resolve(len)) else {
            return false;
        };
        // No closures here: the compiler leaves a closure out of line, and with it the match on
        // the (constant) algorithm.
        let (Some(n), Some(from)) = (
            covered.end.checked_sub(covered.start),
            bytes.get(covered.start..),
        ) else {
            return false;
        };
        let Some(value) = self.checksum.compute_prefix_of::<L>(from, n) else {
            return false;
        };
        let width = self.checksum.width() as u8;
        read_uint(frame, at, width, self.order) == Some(value)
    }

    /// Computes the check of the bytes it covers and stores it in `frame`.
    ///
    /// Returns `None`, writing nothing, if a position lies outside the frame.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn store(&self, frame: &mut [u8]) -> Option<()> {
        self.store_of::<EveryKind>(frame)
    }

    /// [`store`](Self::store) on a link of layout type `L`, as
    /// [`verify_prefix_of`](Self::verify_prefix_of).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(crate) fn store_of<L: LayoutRef>(&self, frame: &mut [u8]) -> Option<()> {
        let (covered, at) = self.resolve(frame.len())?;
        let value = self.checksum.compute_written_of::<L>(frame.get(covered)?)?;
        write_uint(frame, at, self.checksum.width() as u8, self.order, value)
    }
}

impl Marker<'_> {
    /// Whether `frame` holds the marker's bytes at its position.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn matches(&self, frame: &[u8]) -> bool {
        let Some(at) = self.at.resolve(frame.len()) else {
            return false;
        };
        let end = at.checked_add(self.bytes.len());
        end.and_then(|end| frame.get(at..end)) == Some(self.bytes)
    }

    /// Writes the marker's bytes into `frame`; `None`, writing nothing, if they do not fit.
    #[inline]
    pub fn write(&self, frame: &mut [u8]) -> Option<()> {
        let at = self.at.resolve(frame.len())?;
        let dst = frame.get_mut(at..at.checked_add(self.bytes.len())?)?;
        dst.copy_from_slice(self.bytes);
        Some(())
    }
}

impl Constant {
    /// Whether `header` holds the value.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn matches(&self, header: &[u8]) -> bool {
        self.field.read(header) == Some(self.value)
    }
}

impl FrameLayout<'_> {
    /// Bytes needed before the length is known and the header verified:
    /// `max(header_len, sync.len())`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn header_span(&self) -> usize {
        if self.header_len > self.sync_len() {
            self.header_len
        } else {
            self.sync_len()
        }
    }

    /// Bytes of the sync: the byte of [`sync_set`](Self::sync_set), if any, and
    /// [`sync`](Self::sync).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn sync_len(&self) -> usize {
        if self.sync_set.is_empty() {
            self.sync.len()
        } else {
            self.sync.len().saturating_add(1)
        }
    }

    /// Whether `bytes`, the start of a candidate, match the sync as far as they go (a prefix cut
    /// by the end of `bytes` matches).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn sync_matches(&self, bytes: &[u8]) -> bool {
        let rest = match (self.sync_set, bytes) {
            ([], _) => bytes,
            (_, []) => return true,
            (set, [lead, rest @ ..]) => {
                if !set.contains(lead) {
                    return false;
                }
                rest
            }
        };
        bytes_agree(rest, self.sync)
    }

    /// The total length of a frame from its header, by the length rule.
    ///
    /// Only the first [`header_span`](Self::header_span) bytes of `header` are looked at.
    /// Returns `None` if `header` is shorter, or the length is negative or overflows. The
    /// bounds `min_len..=max_len` are not checked here.
    ///
    /// ```
    /// # use protocol_runtime::layout::*;
    /// # use protocol_runtime::Checksum;
    /// # let hflink = FrameLayout {
    /// #     sync: &[0xFF, 0xFF], sync_set: &[], header_len: 6, min_len: 8, max_len: 127,
    /// #     length: LengthRule::Field {
    /// #         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
    /// #         adjust: 7,
    /// #     },
    /// #     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
    /// # };
    /// // HFLink: a big-endian u16 at offset 4 counts command and payload; 7 bytes of framing.
    /// assert_eq!(hflink.frame_len(&[0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01]), Some(8));
    /// assert_eq!(hflink.frame_len(&[0xFF, 0xFF, 0x11]), None);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn frame_len(&self, header: &[u8]) -> Option<usize> {
        match self.length {
            // Out of line, so that the other rules' frame length stays as small as it is
            // without this rule wherever it is inlined (`benches/count.sh` counts it).
            LengthRule::Conditional { .. } => {
                conditional_frame_len(self, header.get(..self.header_span())?)
            }
            _ => self.counted_frame_len(header),
        }
    }

    /// [`frame_len`](Self::frame_len) by the rules that a length field or a constant decides
    /// alone: `None` for [`LengthRule::Conditional`].
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn counted_frame_len(&self, header: &[u8]) -> Option<usize> {
        let header = header.get(..self.header_span())?;
        match self.length {
            LengthRule::Fixed(len) => Some(len),
            LengthRule::Field { field, adjust } | LengthRule::FieldOrBare { field, adjust, .. } => {
                let value = i64::try_from(field.read(header)?).ok()?;
                usize::try_from(value.checked_add(adjust)?).ok()
            }
            LengthRule::Conditional { .. } => None,
        }
    }

    /// Examines `bytes`, which start at a candidate frame start (where the sync bytes, or a
    /// prefix of them, were found).
    ///
    /// Frames longer than `max_len` are rejected as [`Reject::BadLength`].
    ///
    /// ```
    /// # use protocol_runtime::layout::*;
    /// # use protocol_runtime::{Checksum, decoder::{Probe, Reject}};
    /// # let hflink = FrameLayout {
    /// #     sync: &[0xFF, 0xFF], sync_set: &[], header_len: 6, min_len: 8, max_len: 127,
    /// #     length: LengthRule::Field {
    /// #         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
    /// #         adjust: 7,
    /// #     },
    /// #     constants: &[], header_checks: &[],
    /// #     frame_checks: &[Check {
    /// #         checksum: Checksum::SumMod255, from: Pos::Start(0), to: Pos::End(1), at: Pos::End(1),
    /// #         order: ByteOrder::Big,
    /// #     }],
    /// #     markers: &[],
    /// #     escape: None,
    /// # };
    /// let frame = [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x13];
    /// assert_eq!(hflink.probe(&frame), Probe::Frame(8));
    /// assert_eq!(hflink.probe(&frame[..3]), Probe::Need(6));
    /// assert_eq!(hflink.probe(&frame[..6]), Probe::Need(8));
    /// assert_eq!(hflink.probe(&[0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x14]), Probe::Reject(Reject::BadChecksum));
    /// assert_eq!(hflink.probe(&[0xFF, 0xFF, 0x11, 0x01, 0xFF, 0xFF]), Probe::Reject(Reject::BadLength));
    /// ```
    #[inline]
    pub fn probe(&self, bytes: &[u8]) -> Probe {
        probe(&self, bytes, bytes.len(), self.max_len)
    }

    /// Parses exactly one frame at the start of `bytes` (bytes after it are ignored).
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if more bytes are needed to decide,
    /// [`DecodeError::Frame`] if no valid frame starts here.
    ///
    /// ```
    /// # use protocol_runtime::layout::*;
    /// # use protocol_runtime::{Checksum, DecodeError, decoder::Reject};
    /// # let hflink = FrameLayout {
    /// #     sync: &[0xFF, 0xFF], sync_set: &[], header_len: 6, min_len: 8, max_len: 127,
    /// #     length: LengthRule::Field {
    /// #         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
    /// #         adjust: 7,
    /// #     },
    /// #     constants: &[], header_checks: &[],
    /// #     frame_checks: &[Check {
    /// #         checksum: Checksum::SumMod255, from: Pos::Start(0), to: Pos::End(1), at: Pos::End(1),
    /// #         order: ByteOrder::Big,
    /// #     }],
    /// #     markers: &[],
    /// #     escape: None,
    /// # };
    /// let bytes = [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x01, 0x00, 0x13, 0xAA];
    /// assert_eq!(hflink.parse(&bytes)?, &bytes[..8]);
    /// assert_eq!(hflink.parse(&bytes[..7]), Err(DecodeError::Truncated { needed: 8, available: 7 }));
    /// assert_eq!(hflink.parse(&bytes[1..]), Err(DecodeError::Frame(Reject::BadHeader)));
    /// # Ok::<(), DecodeError>(())
    /// ```
    pub fn parse<'b>(&self, bytes: &'b [u8]) -> Result<&'b [u8], DecodeError> {
        match self.probe(bytes) {
            Probe::Frame(len) => bytes
                .get(..len)
                .ok_or(DecodeError::Frame(Reject::BadLength)),
            Probe::Need(needed) => Err(DecodeError::Truncated {
                needed,
                available: bytes.len(),
            }),
            Probe::Reject(reason) => Err(DecodeError::Frame(reason)),
        }
    }
}

/// [`FrameLayout::probe`] on `readable[..avail]`, with frames longer than `limit` rejected as
/// too long. The bytes of `readable` past `avail` (the rest of the input or of the buffer) are
/// in reach of window checksums ([`Check::verify_prefix`]) and decide nothing.
///
/// Generic over where the layout comes from: for a layout known at compile time
/// ([`LayoutRef`]), every read of it is a constant, and this compiles to code for the one
/// format. Always inlined: it is the body of the engine's inner loops.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn probe<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    avail: usize,
    limit: usize,
) -> Probe {
    let layout_ref = layout;
    let layout = layout.layout();
    let bytes = readable.get(..avail).unwrap_or(readable);
    if !layout.sync_matches(bytes) {
        return Probe::Reject(Reject::BadHeader);
    }
    probe_synced(layout_ref, readable, avail, limit)
}

/// The format of `link` that the candidate `bytes` start with, and its index (0: the first):
/// the first whose sync they match (as far as they go). The first format when none does, and
/// always for a link of one format (the test then folds away).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn select<'a, L: LayoutRef>(link: &'a L, bytes: &[u8]) -> (usize, &'a FrameLayout<'a>) {
    let first = link.layout();
    let others = link.others();
    if others.is_empty() || first.sync_matches(bytes) {
        return (0, first);
    }
    match others.iter().position(|f| f.sync_matches(bytes)) {
        Some(i) => (i.wrapping_add(1), others.get(i).unwrap_or(first)),
        None => (0, first),
    }
}

/// The longest frame of any format of `link`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn link_max_len<L: LayoutRef>(link: &L) -> usize {
    let first = link.layout().max_len;
    link.others().iter().fold(first, |m, f| m.max(f.max_len))
}

/// [`probe`] for a link of one or several formats: the candidate is probed by the format its
/// sync selects ([`select`]), with frames longer than that format's `max_len` or `limit`
/// rejected. Returns the format's index with the verdict.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn probe_link<L: LayoutRef>(
    link: &L,
    readable: &[u8],
    avail: usize,
    limit: usize,
) -> (usize, Probe) {
    if !L::SEVERAL_FORMATS || link.others().is_empty() {
        return (0, probe(link, readable, avail, limit));
    }
    let bytes = readable.get(..avail).unwrap_or(readable);
    let (index, format) = select(link, bytes);
    let limit = limit.min(format.max_len);
    (index, probe(&format, readable, avail, limit))
}

/// [`probe_synced`] for a link of one or several formats, once the candidate's bytes are known
/// to match some format's sync (the engine's search for a candidate has just compared them).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn probe_link_synced<L: LayoutRef>(
    link: &L,
    readable: &[u8],
    avail: usize,
    limit: usize,
) -> (usize, Probe) {
    if !L::SEVERAL_FORMATS || link.others().is_empty() {
        return (0, probe_synced(link, readable, avail, limit));
    }
    let bytes = readable.get(..avail).unwrap_or(readable);
    let (index, format) = select(link, bytes);
    let limit = limit.min(format.max_len);
    (index, probe_synced(&format, readable, avail, limit))
}

/// [`probe`] once the candidate's bytes are known to match the sync bytes, as many of them as
/// there are (the engine's search for a candidate has just compared them): every other rule.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(crate) fn probe_synced<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    avail: usize,
    limit: usize,
) -> Probe {
    let layout_ref = layout;
    let layout = layout.layout();
    let bytes = readable.get(..avail).unwrap_or(readable);
    let span = layout.header_span();
    if span > limit {
        // No frame fits; but a sync prefix cut by the end of the bytes may not be a
        // candidate at all: decide that first, so that the verdict does not depend on
        // where the input was cut.
        if bytes.len() < layout.sync_len() {
            return Probe::Need(layout.sync_len());
        }
        return Probe::Reject(Reject::BadLength);
    }
    let Some(header) = bytes.get(..span) else {
        return Probe::Need(span);
    };
    if !all_hold!(layout.constants, |c| c.matches(header)) {
        return Probe::Reject(Reject::BadHeader);
    }
    if !all_hold!(layout.header_checks, |c| c
        .verify_prefix_of::<L>(readable, span))
    {
        return Probe::Reject(Reject::BadHeaderCheck);
    }
    let bare = layout.length.bare_len();
    let shortest = span.max(layout.min_len).max(1);
    // A frame whose parts depend on its header (decided at compile time for a generated
    // layout): out of line, so that the other frames' path is the same code as without it.
    if L::HEADER_DECIDED {
        if let LengthRule::Conditional { .. } = layout.length {
            return probe_conditional(layout_ref, readable, avail, header, shortest, limit);
        }
    }
    let total = match frame_len_of::<L>(layout, header) {
        // A bare header is complete and verified once its header checks hold and its bytes
        // have come (fields after the length may lie in it, beyond the header span).
        Some(t) if Some(t) == bare && t >= span && t > 0 && t <= limit => {
            return if bytes.len() < t {
                Probe::Need(t)
            } else {
                Probe::Frame(t)
            };
        }
        // `shortest..=limit` in one comparison (empty when `limit < shortest`).
        Some(t)
            if limit >= shortest && t.wrapping_sub(shortest) <= limit.wrapping_sub(shortest) =>
        {
            t
        }
        _ => return Probe::Reject(Reject::BadLength),
    };
    let Some(frame) = bytes.get(..total) else {
        return Probe::Need(total);
    };
    if !all_hold!(layout.frame_checks, |c| c
        .verify_prefix_of::<L>(readable, total))
    {
        return Probe::Reject(Reject::BadChecksum);
    }
    if !all_hold!(layout.markers, |m| m.matches(frame)) {
        return Probe::Reject(Reject::BadTrailer);
    }
    Probe::Frame(total)
}

/// [`FrameLayout::frame_len`] where the link's [`LayoutRef`] says whether its formats may
/// decide their length by header values: where they may not, the rule's path is not linked
/// (a frame of that rule has no length then).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn frame_len_of<L: LayoutRef>(layout: &FrameLayout<'_>, header: &[u8]) -> Option<usize> {
    if L::HEADER_DECIDED {
        layout.frame_len(header)
    } else {
        layout.counted_frame_len(header)
    }
}

/// [`FrameLayout::frame_len`] for [`LengthRule::Conditional`]: only the header is looked at,
/// so a wider length after it is not known here.
#[inline(never)]
fn conditional_frame_len(layout: &FrameLayout<'_>, header: &[u8]) -> Option<usize> {
    let LengthRule::Conditional {
        field,
        adjust,
        extension,
        trailer,
    } = layout.length
    else {
        return None;
    };
    conditional::measure(
        field,
        adjust,
        extension,
        trailer,
        header,
        header,
        usize::MAX,
    )
    .ok()
    .map(|(total, _)| total)
}

/// [`probe_synced`] for [`LengthRule::Conditional`] once the header is verified: the length
/// from the header (and a wider length after it), then the frame checks and markers, which
/// resolve against the frame without its flag trailer.
///
/// Generic over where the layout comes from, as [`probe`] is: for a generated layout (MAVLink
/// 2) every read of it is a constant, and the frame checks compile to the one check.
#[inline(never)]
fn probe_conditional<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    avail: usize,
    header: &[u8],
    shortest: usize,
    limit: usize,
) -> Probe {
    let layout = layout.layout();
    let bytes = readable.get(..avail).unwrap_or(readable);
    let LengthRule::Conditional {
        field,
        adjust,
        extension,
        trailer,
    } = layout.length
    else {
        return Probe::Reject(Reject::BadLength);
    };
    let (total, body) =
        match conditional::measure(field, adjust, extension, trailer, header, bytes, limit) {
            Ok((total, body)) if total >= shortest && total <= limit => (total, body),
            Ok(_) => return Probe::Reject(Reject::BadLength),
            Err(verdict) => return verdict,
        };
    let Some(frame) = bytes.get(..body).filter(|_| total <= bytes.len()) else {
        return Probe::Need(total);
    };
    if !all_hold!(layout.frame_checks, |c| c
        .verify_prefix_of::<L>(readable, body))
    {
        return Probe::Reject(Reject::BadChecksum);
    }
    if !all_hold!(layout.markers, |m| m.matches(frame)) {
        return Probe::Reject(Reject::BadTrailer);
    }
    Probe::Frame(total)
}
