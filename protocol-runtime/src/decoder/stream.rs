//! The streaming half of the engine: [`StreamDecoder`] finds frames in input that arrives in
//! chunks, and accounts for every byte ([`Stats`]) and every decision ([`Event`]).
//!
//! This module owns the search for candidates, the fixed buffer that holds a candidate cut by
//! the end of a chunk, and the rule that a rejection costs one byte. Whether a candidate is a
//! frame is decided by [`FrameLayout::probe`]'s rules, in the parent module.

use core::fmt;

use super::{Probe, Reject, probe, probe_synced};
use crate::layout::{FrameLayout, LayoutRef};

/// Where the first candidate of `data` starts: the first offset where `data` holds the sync
/// bytes, or a prefix of them that runs to the end of `data`; `data.len()` if there is none.
#[inline]
fn find_candidate(sync: &[u8], data: &[u8]) -> usize {
    let Some((&first, more)) = sync.split_first() else {
        return 0;
    };
    let continues = |at: usize| {
        let after = data.get(at.wrapping_add(1)..).unwrap_or_default();
        after.iter().zip(more).all(|(a, b)| a == b)
    };
    let mut from = 0;
    // On a clean stream the next frame starts right here. (A shortcut for hosts: the loop
    // below finds it too, and on microcontrollers a second copy of the test costs flash.)
    if cfg!(target_pointer_width = "64") {
        // Whether a candidate starts here, and whether a `false` is final (a two-byte sync
        // compared whole needs two bytes; its prefix at the very end is left to the loop).
        let (here, settled) = match *sync {
            // A two-byte sync (HFLink's `FF FF`) as one 16-bit comparison.
            [a, b] => (data.first_chunk::<2>() == Some(&[a, b]), data.len() >= 2),
            _ => (data.first() == Some(&first) && continues(0), true),
        };
        if here {
            return 0;
        }
        if settled {
            // After a rejected candidate the search resumes at its second byte, which often is
            // the sync's first again (`FF` of `FF FF`): not a start, and no call to find it.
            from = 1;
        }
    }
    while let Some(hit) = data.get(from..).and_then(|rest| find_byte(first, rest)) {
        let at = from.wrapping_add(hit);
        if continues(at) {
            return at;
        }
        from = at.wrapping_add(1);
    }
    data.len()
}

/// The first offset of `byte` in `data`: `memchr` (vector compares) on 64-bit targets; a plain
/// loop on 32-bit ones (microcontrollers), where `memchr`'s word-at-a-time code costs more
/// flash than it saves time on a UART's chunks.
#[inline(always)]
fn find_byte(byte: u8, data: &[u8]) -> Option<usize> {
    if cfg!(target_pointer_width = "64") {
        memchr::memchr(byte, data)
    } else {
        data.iter().position(|&b| b == byte)
    }
}

/// Takes the first `len` bytes off `input` (all of it if shorter).
#[inline(always)]
fn take<'i>(input: &mut &'i [u8], len: usize) -> &'i [u8] {
    let data: &'i [u8] = input;
    let (head, rest) = data.split_at_checked(len).unwrap_or((data, &[]));
    *input = rest;
    head
}

/// Whether the engine scans the caller's input in place when nothing is pending (frames found
/// whole there borrow it: zero copy), or stages every chunk in its buffer first. In place is
/// faster on hosts; staging is the default on targets without 64-bit pointers
/// (microcontrollers), where a second copy of the scan costs more flash than the copy of a
/// UART chunk costs time (measured on the HFLink firmware, thumbv7em: 9,452 -> 8,972 bytes,
/// together with `find_first_byte`'s byte loop there).
/// The `stage-input` feature selects it anywhere, so that hosts test that path too. The frames
/// and stats do not depend on it.
const SCAN_IN_PLACE: bool = cfg!(all(
    target_pointer_width = "64",
    not(feature = "stage-input")
));

/// Bytes kept free behind staged input: a window checksum reads a fixed-size block from a
/// candidate's start (up to 128 bytes), which then stays inside the buffer instead of falling
/// back to an exact loop.
const STAGE_SLACK: usize = if cfg!(target_pointer_width = "64") {
    128
} else {
    // No window checksums there.
    0
};

/// Every byte of a word set to one: the zero-byte test's constants.
const LOW: u64 = 0x0101_0101_0101_0101;
const HIGH: u64 = 0x8080_8080_8080_8080;

/// The high bit of every zero byte of `x` set, and maybe of bytes above a zero byte (a borrow
/// runs upwards): the lowest flag is exact, and no zero byte goes unflagged.
#[inline(always)]
const fn zero_byte_flags(x: u64) -> u64 {
    x.wrapping_sub(LOW) & !x & HIGH
}

/// Bytes [`may_start_sync`] compares at once.
const SCAN: usize = 64;

/// `SCAN_MASK[SCAN - k..][..SCAN]` keeps the first `k` bytes of a block.
const SCAN_MASK: [u8; 2 * SCAN] = {
    let mut mask = [0; 2 * SCAN];
    let mut i = 0;
    while i < SCAN {
        // In a const initialiser: an index out of bounds fails to compile.
        #[allow(clippy::indexing_slicing)]
        {
            mask[i] = 0xFF;
        }
        i = i.wrapping_add(1);
    }
    mask
};

/// Whether some offset of `data[..n]` may start `sync`: holds its first byte followed by its
/// second (its first byte alone, for a one-byte sync). The question asked of a pending
/// candidate every time the input runs out, whose answer is nearly always no. A `true` may be
/// wrong (the caller searches exactly then), a `false` never is.
///
/// Whole 64-byte blocks are compared under a mask, without a branch per byte or per word (the
/// compiler turns this into a few vector compares); a search that stops at the first match
/// mispredicts its exit once per call, at a length that changes every time. Testing pairs
/// rather than the first byte alone makes a `true` rare for two-byte syncs (`FF FF`: a random
/// payload byte is `FF` once in 256, a pair once in 65,536), so the branch on it predicts well.
#[inline(always)]
fn may_start_sync(sync: &[u8], data: &[u8], n: usize) -> bool {
    let (first, second) = match *sync {
        [] => return n > 0,
        [first] => (first, None),
        [first, second, ..] => (first, Some(second)),
    };
    let pattern = LOW.wrapping_mul(u64::from(first));
    let next_pattern = LOW.wrapping_mul(u64::from(second.unwrap_or(0)));
    let mut from = 0usize;
    while from < n {
        let rest = data.get(from..).unwrap_or_default();
        let left = n.wrapping_sub(from);
        // The block and, for the second byte, the block one byte further.
        let Some(block) = rest.first_chunk::<{ SCAN + 8 }>() else {
            // The end of the buffer: fewer bytes left to read than a block.
            return (0..left).any(|i| {
                rest.get(i) == Some(&first)
                    && second.is_none_or(|s| rest.get(i.wrapping_add(1)).is_none_or(|&b| b == s))
            });
        };
        let keep = SCAN_MASK
            .get(SCAN.saturating_sub(left)..)
            .and_then(<[u8]>::first_chunk::<SCAN>)
            .unwrap_or(&[0; SCAN]);
        let mut hits = 0u64;
        for k in 0..SCAN / 8 {
            let at = k.wrapping_mul(8);
            let word_at = |bytes: &[u8], at: usize| {
                bytes
                    .get(at..)
                    .and_then(<[u8]>::first_chunk::<8>)
                    .map_or(0, |w| u64::from_le_bytes(*w))
            };
            // A flag below a zero byte of `x` is exact; above one it may be a borrow's, but
            // then a masked-in zero byte lies below it (the mask keeps a prefix): a false
            // `true` at worst.
            let mut flags = zero_byte_flags(word_at(block, at) ^ pattern);
            if second.is_some() {
                flags &= zero_byte_flags(word_at(block, at.wrapping_add(1)) ^ next_pattern);
            }
            hits |= flags & word_at(keep, at);
        }
        if hits != 0 {
            return true;
        }
        from = from.wrapping_add(SCAN);
    }
    false
}

/// The first offset of `data` holding `sync`'s first byte, or `data.len()`: the search inside
/// a pending candidate, a few dozen bytes. Eight bytes per step (a zero-byte test on a word
/// xored with the byte repeated); a call to `memchr` costs more on so few bytes.
#[inline(always)]
fn find_first_byte(sync: &[u8], data: &[u8]) -> usize {
    let Some(&first) = sync.first() else {
        return 0;
    };
    if cfg!(not(target_pointer_width = "64")) {
        // Words of 64 bits are pairs of registers there: a byte loop is smaller.
        return data.iter().position(|&b| b == first).unwrap_or(data.len());
    }
    let pattern = LOW.wrapping_mul(u64::from(first));
    let words = data.chunks_exact(8);
    let tail = words.remainder();
    for (k, word) in words.enumerate() {
        let Ok(word) = <[u8; 8]>::try_from(word) else {
            break;
        };
        let x = u64::from_le_bytes(word) ^ pattern;
        // The lowest flagged byte is exactly the first zero byte of `x`.
        let zero = zero_byte_flags(x);
        if zero != 0 {
            return k
                .wrapping_mul(8)
                .wrapping_add((zero.trailing_zeros() / 8) as usize);
        }
    }
    let base = data.len().wrapping_sub(tail.len());
    tail.iter()
        .position(|&b| b == first)
        .map_or(data.len(), |at| base.wrapping_add(at))
}

/// What a [`StreamDecoder`] counted, for link-quality reports.
///
/// Every byte fed is accounted for once: `frame_bytes + skipped_bytes` plus the bytes still
/// pending equals the bytes fed ([`StreamDecoder::position`]). A rejected candidate's first
/// byte counts as skipped (the search resumes right after it).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Valid frames yielded.
    pub frames: u64,
    /// Bytes of the valid frames.
    pub frame_bytes: u64,
    /// Bytes that belong to no valid frame.
    pub skipped_bytes: u64,
    /// Candidates rejected as [`Reject::BadHeader`].
    pub bad_header: u64,
    /// Candidates rejected as [`Reject::BadHeaderCheck`].
    pub bad_header_check: u64,
    /// Candidates rejected as [`Reject::BadLength`].
    pub bad_length: u64,
    /// Candidates rejected as [`Reject::BadChecksum`].
    pub bad_checksum: u64,
    /// Candidates rejected as [`Reject::BadTrailer`].
    pub bad_trailer: u64,
    /// Candidates rejected as [`Reject::Truncated`].
    pub truncated: u64,
}

impl Stats {
    const ZERO: Stats = Stats {
        frames: 0,
        frame_bytes: 0,
        skipped_bytes: 0,
        bad_header: 0,
        bad_header_check: 0,
        bad_length: 0,
        bad_checksum: 0,
        bad_trailer: 0,
        truncated: 0,
    };

    /// Candidates rejected, for any reason.
    pub const fn rejected(&self) -> u64 {
        self.bad_header
            .wrapping_add(self.bad_header_check)
            .wrapping_add(self.bad_length)
            .wrapping_add(self.bad_checksum)
            .wrapping_add(self.bad_trailer)
            .wrapping_add(self.truncated)
    }

    fn count_reject(&mut self, reason: Reject) {
        self.skipped_bytes = self.skipped_bytes.wrapping_add(1);
        let counter = match reason {
            Reject::BadHeader => &mut self.bad_header,
            Reject::BadHeaderCheck => &mut self.bad_header_check,
            Reject::BadLength => &mut self.bad_length,
            Reject::BadChecksum => &mut self.bad_checksum,
            Reject::BadTrailer => &mut self.bad_trailer,
            Reject::Truncated => &mut self.truncated,
        };
        *counter = counter.wrapping_add(1);
    }

    fn count_frame(&mut self, len: usize) {
        self.frames = self.frames.wrapping_add(1);
        self.frame_bytes = self.frame_bytes.wrapping_add(len as u64);
    }
}

/// A valid frame found in a stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Frame<'a> {
    /// The whole frame, sync to trailer.
    pub bytes: &'a [u8],
    /// Offset of its first byte in the whole stream.
    pub offset: u64,
}

/// What a [`StreamDecoder`] reports with [`StreamDecoder::next_event`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Event<'a> {
    /// A valid frame.
    Frame(Frame<'a>),
    /// A candidate starting at `offset` was rejected; the search resumes at `offset + 1`.
    Rejected {
        /// Offset of the candidate's first byte in the stream.
        offset: u64,
        /// Why it was rejected.
        reason: Reject,
    },
    /// A run of `len` bytes where no candidate starts. A long run of garbage may be reported
    /// in several pieces (one per chunk of input, for example).
    Skipped {
        /// Offset of the run's first byte in the stream.
        offset: u64,
        /// Bytes in the run.
        len: usize,
    },
}

/// One step of the engine: the data of an [`Event`], with frames as numbers: a buffered frame
/// as a range, so that the engine's buffer is borrowed only once the step is over, and a frame
/// of the input as its length, taken from the input by the caller. (A step holding a slice was
/// returned through memory and read back with one wide load from two narrow stores: a store
/// forwarding stall once per frame.)
enum Step {
    /// The next `len` bytes of the input are a frame (consumed by the caller).
    Input {
        len: usize,
        offset: u64,
    },
    Buffered {
        start: usize,
        end: usize,
        offset: u64,
    },
    Rejected {
        offset: u64,
        reason: Reject,
    },
    Skipped {
        offset: u64,
        len: usize,
    },
    Idle,
}

/// Finds the frames of a [`FrameLayout`] in a byte stream that arrives in chunks of any size.
///
/// The decoder owns a fixed buffer of `N` bytes and never allocates. On hosts, frames found
/// whole in the caller's input are returned borrowing that input (zero copy); a candidate cut
/// by the end of a chunk is copied into the buffer, and the following chunks are appended
/// behind it whole when they fit (leaving room for a checksum window), else only the bytes it
/// needs. On targets without 64-bit pointers (and with the `stage-input` feature) every chunk
/// is staged in the buffer first, which takes less code. Frames longer than `min(max_len, N)`
/// are rejected as [`Reject::BadLength`].
/// A rejected candidate costs one byte: the search resumes right after its start, so a corrupt
/// or truncated frame never costs the valid frame that follows it; and a valid frame is yielded
/// as soon as it is complete, even inside the claimed length of an earlier candidate still
/// waiting for its bytes (which is then rejected as [`Reject::Truncated`]; see the
/// [module docs](crate::decoder)).
///
/// Every byte fed is accounted for ([`Stats`]). The frames do not depend on how the input was
/// cut into chunks (but for the rare case in the module docs); the events hardly do: a skipped
/// run may come in pieces, and a candidate cut by a chunk boundary may be rejected as
/// truncated where, received whole, it would have failed a check.
///
/// ```
/// use protocol_runtime::layout::{ByteOrder, Check, LengthRule, Pos, WordField};
/// use protocol_runtime::{Checksum, FrameLayout, StreamDecoder};
///
/// static HFLINK: FrameLayout<'static> = FrameLayout {
///     sync: &[0xFF, 0xFF],
///     header_len: 6,
///     min_len: 8,
///     max_len: 127,
///     length: LengthRule::Field {
///         field: WordField { at: Pos::Start(4), size: 2, order: ByteOrder::Big, shift: 0, width: 16 },
///         adjust: 7,
///     },
///     constants: &[],
///     header_checks: &[],
///     frame_checks: &[Check {
///         checksum: Checksum::SumMod255,
///         from: Pos::Start(0),
///         to: Pos::End(1),
///         at: Pos::End(1),
///         order: ByteOrder::Big,
///     }],
///     markers: &[],
/// };
///
/// let mut decoder = StreamDecoder::<_, 128>::new(&HFLINK);
/// let mut offsets = Vec::new();
/// // Garbage, then a frame split across two chunks.
/// for chunk in [&[0x00, 0xFF, 0xFF, 0x11][..], &[0x01, 0x00, 0x01, 0x00, 0x13]] {
///     decoder.feed(chunk, |frame| offsets.push(frame.offset));
/// }
/// assert_eq!(offsets, [1]);
/// assert_eq!(decoder.stats().skipped_bytes, 1);
/// ```
// In declaration order (`repr(C)`), the words every step reads and writes first, ahead of the
// buffer. Measured on the HFLink firmware (thumbv7em): 140-156 bytes smaller than with the
// buffer first, nearly all of it in the inlined input step of the firmware's main loop; the
// cause was not isolated (the engine's own functions take as many 4-byte instructions either
// way).
#[repr(C)]
pub struct StreamDecoder<L: LayoutRef, const N: usize> {
    /// What [`Self::frame_inside`] learnt about the pending candidate starting at stream offset
    /// `inner_owner`: its first `inner_dead` bytes start no frame, now or later (at least its
    /// first byte, the candidate's own start).
    inner_dead: usize,
    /// The pending bytes are `buf[start..end]`; `start < end` or both are 0.
    start: usize,
    end: usize,
    buf: [u8; N],
    layout: L,
    /// Bytes consumed from all inputs.
    position: u64,
    stats: Stats,
    inner_owner: u64,
}

impl<L: LayoutRef, const N: usize> fmt::Debug for StreamDecoder<L, N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("StreamDecoder")
            .field("capacity", &N)
            .field("pending", &self.pending())
            .field("position", &self.position)
            .field("stats", &self.stats)
            .finish_non_exhaustive()
    }
}

impl<L: LayoutRef, const N: usize> StreamDecoder<L, N> {
    /// A decoder for `layout` with an empty buffer.
    pub const fn new(layout: L) -> Self {
        Self {
            layout,
            buf: [0; N],
            start: 0,
            end: 0,
            position: 0,
            stats: Stats::ZERO,
            inner_owner: u64::MAX,
            inner_dead: 1,
        }
    }

    /// The frame format.
    #[inline]
    pub fn layout(&self) -> &FrameLayout<'_> {
        self.layout.layout()
    }

    /// What was counted since the decoder was created or reset.
    #[inline]
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Bytes held in the buffer: the start of a candidate the input has not completed yet.
    #[inline]
    pub fn pending(&self) -> usize {
        self.end.saturating_sub(self.start)
    }

    /// The bytes held in the buffer.
    #[inline]
    pub fn pending_bytes(&self) -> &[u8] {
        self.buf.get(self.start..self.end).unwrap_or_default()
    }

    /// Bytes consumed from all inputs since the decoder was created or reset.
    #[inline]
    pub fn position(&self) -> u64 {
        self.position
    }

    /// Forgets the pending bytes, the position and the stats: the decoder is as new.
    pub fn reset(&mut self) {
        self.start = 0;
        self.end = 0;
        self.position = 0;
        self.stats = Stats::ZERO;
        self.inner_owner = u64::MAX;
        self.inner_dead = 1;
    }

    /// The next valid frame, consuming from `*input` as needed (the slice is advanced).
    ///
    /// Returns `None` when the input is exhausted; a partial frame at its end stays buffered
    /// for the next call. Rejections and garbage are counted in [`stats`](Self::stats).
    #[inline(always)]
    pub fn decode<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Frame<'s>> {
        self.next_frame(input, false)
    }

    /// Like [`decode`](Self::decode), but also reports rejected candidates and skipped runs.
    pub fn next_event<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Event<'s>> {
        self.event(input, false)
    }

    /// Declares the end of the input (end of a file, or an idle gap on the link) and returns
    /// the next frame among the pending bytes.
    ///
    /// The pending candidate will never be completed: it is rejected as [`Reject::Truncated`]
    /// and the bytes after its start are searched again (a sync prefix, a header cut short).
    /// Call until `None`; the buffer is then empty.
    pub fn flush(&mut self) -> Option<Frame<'_>> {
        self.next_frame(&mut &[][..], true)
    }

    /// Like [`flush`](Self::flush), but also reports rejected candidates and skipped runs.
    pub fn flush_event(&mut self) -> Option<Event<'_>> {
        self.event(&mut &[][..], true)
    }

    /// Feeds a chunk and calls `sink` with every frame completed by it.
    ///
    /// The same frames, stats and buffering as [`decode`](Self::decode) in a loop, and faster:
    /// while nothing is pending, the frames of the chunk are found in one loop that keeps the
    /// counters in registers and writes them back once (through `decode`, they are updated in
    /// the decoder for every frame, a chain of loads and stores from one frame to the next).
    #[inline]
    pub fn feed(&mut self, mut chunk: &[u8], mut sink: impl FnMut(Frame<'_>)) {
        loop {
            if self.start >= self.end && SCAN_IN_PLACE {
                self.scan_input(&mut chunk, &mut sink);
                if chunk.is_empty() {
                    return;
                }
                // A candidate runs to the end of the chunk and needs more: keep it and, unless
                // a frame is complete inside it, wait (what `step_input` and `step_buffered`
                // would decide, without probing the candidate twice more).
                if self.hold(&mut chunk) && !self.frame_inside(self.limit()) {
                    return;
                }
            } else {
                if !chunk.is_empty() {
                    self.stage(&mut chunk);
                }
                self.scan_buffered(&mut sink);
                if self.start >= self.end {
                    if chunk.is_empty() {
                        return;
                    }
                    // A chunk too large to stage, with nothing pending: scanned in place, or
                    // (when every chunk is staged) left to the general engine, which copies
                    // what each candidate needs.
                    if SCAN_IN_PLACE {
                        continue;
                    }
                } else if chunk.is_empty() && !self.frame_inside(self.limit()) {
                    // The pending candidate needs more bytes than the chunk brought: as above.
                    return;
                }
            }
            // A candidate that a frame inside it cuts short, or a chunk too large to stage:
            // one step of the general engine.
            match self.decode(&mut chunk) {
                Some(frame) => sink(frame),
                None => return,
            }
        }
    }

    /// Keeps the whole input, with nothing pending, as the pending bytes (the start of a
    /// candidate that needs more). Returns `false`, copying nothing, if it does not fit.
    #[inline(always)]
    fn hold(&mut self, input: &mut &[u8]) -> bool {
        let data: &[u8] = input;
        let Some(dst) = self.buf.get_mut(..data.len()) else {
            return false;
        };
        dst.copy_from_slice(data);
        self.start = 0;
        self.end = data.len();
        self.position = self.position.wrapping_add(data.len() as u64);
        *input = &[];
        true
    }

    /// [`step_buffered`](Self::step_buffered) in a loop, for [`feed`](Self::feed), once the
    /// chunk is staged: frames, rejected candidates and skipped runs of the pending bytes,
    /// until a candidate needs more bytes than are pending (left to the general engine).
    #[inline(always)]
    fn scan_buffered(&mut self, sink: &mut impl FnMut(Frame<'_>)) {
        let layout = self.layout;
        let layout = layout.layout();
        let limit = self.limit();
        let readable = self.buf.get(self.start..).unwrap_or_default();
        let pending = self.end.saturating_sub(self.start);
        let base = self.position.wrapping_sub(pending as u64);
        // Per frame, only a count and the offset change: a frame's bytes are what the scan
        // did not skip, added once at the end. Skipped bytes (rare on a good link) go straight
        // to the stats, out of the loop's registers.
        let skipped_before = self.stats.skipped_bytes;
        let (mut at, mut frames) = (0usize, 0u64);
        while at < pending {
            let from = readable.get(at..).unwrap_or_default();
            let avail = pending.wrapping_sub(at);
            let skip = find_candidate(layout.sync, from.get(..avail).unwrap_or(from));
            if skip > 0 {
                self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
                at = at.wrapping_add(skip);
                continue;
            }
            // The search has just compared the sync bytes (as many as there are).
            match probe_synced(&self.layout, from, avail, limit) {
                Probe::Frame(len) => {
                    sink(Frame {
                        bytes: from.get(..len).unwrap_or(from),
                        offset: base.wrapping_add(at as u64),
                    });
                    frames = frames.wrapping_add(1);
                    at = at.wrapping_add(len);
                }
                Probe::Reject(reason) => {
                    self.stats.count_reject(reason);
                    at = at.wrapping_add(1);
                }
                Probe::Need(_) => break,
            }
        }
        self.count_scan(frames, at, skipped_before);
        self.start = self.start.wrapping_add(at.min(pending));
        if self.start >= self.end {
            self.start = 0;
            self.end = 0;
        }
    }

    /// [`step_input`](Self::step_input) in a loop, for [`feed`](Self::feed): frames, rejected
    /// candidates and skipped runs of `input`, until a candidate needs more bytes than `input`
    /// holds (left to the general engine, which buffers it) or `input` is used up.
    ///
    /// Out of line: the loop gets registers of its own (inlined into `feed`, whose other paths
    /// keep their state live around it, it reloaded the input's pointer from the stack every
    /// frame; measured: HFLink clean, whole stream, 0.89x - 0.90x of the hand-written decoder
    /// inlined, 0.95x - 0.98x out of line).
    #[inline(never)]
    fn scan_input(&mut self, input: &mut &[u8], sink: &mut impl FnMut(Frame<'_>)) {
        let layout = self.layout;
        let layout = layout.layout();
        let limit = self.limit();
        let data: &[u8] = input;
        let base = self.position;
        // As in `scan_buffered`: a count and the offset per frame, skipped bytes in the stats.
        let skipped_before = self.stats.skipped_bytes;
        let (mut at, mut frames) = (0usize, 0u64);
        // One comparison per step (`at` never passes the end: every step advances it by at
        // most what is left).
        while at < data.len() {
            let rest = data.get(at..).unwrap_or_default();
            let skip = find_candidate(layout.sync, rest);
            if skip > 0 {
                self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
                at = at.wrapping_add(skip);
                continue;
            }
            // The search has just compared the sync bytes (as many as there are).
            match probe_synced(&self.layout, rest, rest.len(), limit) {
                Probe::Frame(len) => {
                    let offset = base.wrapping_add(at as u64);
                    sink(Frame {
                        bytes: rest.get(..len).unwrap_or(rest),
                        offset,
                    });
                    frames = frames.wrapping_add(1);
                    at = at.wrapping_add(len);
                }
                Probe::Reject(reason) => {
                    self.stats.count_reject(reason);
                    at = at.wrapping_add(1);
                }
                Probe::Need(_) => break,
            }
        }
        self.count_scan(frames, at, skipped_before);
        self.position = self.position.wrapping_add(at as u64);
        *input = data.get(at..).unwrap_or_default();
    }

    // Inlined into the caller's loop: the common step (a frame found in the input) is a few
    // dozen instructions, which a call and a return per frame would add to; the buffered
    // steps stay out of line.
    #[inline(always)]
    fn next_frame<'s, 'i: 's>(
        &'s mut self,
        input: &mut &'i [u8],
        at_end: bool,
    ) -> Option<Frame<'s>> {
        // The two kinds of step are matched apart, not through `step`: a step result that
        // comes from either an inlined or a called function is passed through memory, and
        // reading a frame back from there stalled on store forwarding, once per frame.
        let (start, end, offset) = loop {
            if self.start < self.end {
                match self.step_buffered(input, at_end) {
                    Step::Input { len, offset } => {
                        let bytes = take(input, len);
                        return Some(Frame { bytes, offset });
                    }
                    Step::Buffered { start, end, offset } => break (start, end, offset),
                    Step::Rejected { .. } | Step::Skipped { .. } => {}
                    Step::Idle => return None,
                }
            } else {
                self.start = 0;
                self.end = 0;
                match self.step_input(input, at_end) {
                    Step::Input { len, offset } => {
                        let bytes = take(input, len);
                        return Some(Frame { bytes, offset });
                    }
                    Step::Buffered { start, end, offset } => break (start, end, offset),
                    Step::Rejected { .. } | Step::Skipped { .. } => {}
                    Step::Idle => return None,
                }
            }
        };
        Some(Frame {
            bytes: self.buf.get(start..end).unwrap_or_default(),
            offset,
        })
    }

    fn event<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8], at_end: bool) -> Option<Event<'s>> {
        Some(match self.step(input, at_end) {
            Step::Input { len, offset } => Event::Frame(Frame {
                bytes: take(input, len),
                offset,
            }),
            Step::Buffered { start, end, offset } => Event::Frame(Frame {
                bytes: self.buf.get(start..end).unwrap_or_default(),
                offset,
            }),
            Step::Rejected { offset, reason } => Event::Rejected { offset, reason },
            Step::Skipped { offset, len } => Event::Skipped { offset, len },
            Step::Idle => return None,
        })
    }

    /// Adds what a scan loop counted: `frames` frames in `scanned` bytes; the bytes that belong
    /// to no frame (skipped runs and the first bytes of rejected candidates) were added to the
    /// skipped bytes since they were `skipped_before`.
    #[inline(always)]
    fn count_scan(&mut self, frames: u64, scanned: usize, skipped_before: u64) {
        let stats = &mut self.stats;
        stats.frames = stats.frames.wrapping_add(frames);
        let gaps = stats.skipped_bytes.wrapping_sub(skipped_before);
        let frame_bytes = (scanned as u64).wrapping_sub(gaps);
        stats.frame_bytes = stats.frame_bytes.wrapping_add(frame_bytes);
    }

    /// Frames longer than this are rejected.
    #[inline(always)]
    fn limit(&self) -> usize {
        self.layout.layout().max_len.min(N)
    }

    /// Advances `input` by `n` bytes (at most its length) and returns the bytes skipped.
    #[inline(always)]
    fn consume<'i>(&mut self, input: &mut &'i [u8], n: usize) -> &'i [u8] {
        let data: &'i [u8] = input;
        let (head, rest) = data.split_at_checked(n).unwrap_or((data, &[]));
        *input = rest;
        self.position = self.position.wrapping_add(head.len() as u64);
        head
    }

    /// One event's worth of work.
    #[inline(always)]
    fn step(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        if self.start < self.end {
            self.step_buffered(input, at_end)
        } else {
            self.start = 0;
            self.end = 0;
            self.step_input(input, at_end)
        }
    }

    /// A step on the caller's input, with nothing pending.
    #[inline(always)]
    fn step_input(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        let data: &[u8] = input;
        if data.is_empty() {
            return Step::Idle;
        }
        // (A buffer of no bytes stages nothing: scanned in place, where every candidate is
        // too long.)
        if !SCAN_IN_PLACE && N > 0 {
            self.stage_prefix(input);
            return self.step_buffered(input, at_end);
        }
        let layout = self.layout;
        let layout = layout.layout();
        let offset = self.position;
        let skip = find_candidate(layout.sync, data);
        if skip > 0 {
            let len = self.consume(input, skip).len();
            self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(len as u64);
            return Step::Skipped { offset, len };
        }
        // `find_candidate` has compared the sync bytes.
        let reason = match probe_synced(&self.layout, data, data.len(), self.limit()) {
            Probe::Frame(len) => {
                // `len <= data.len()`: the caller takes the bytes from the input.
                self.position = self.position.wrapping_add(len as u64);
                self.stats.count_frame(len);
                return Step::Input { len, offset };
            }
            Probe::Need(_) => {
                // The candidate runs to the end of the input, which is then shorter than what
                // it needs, itself at most `limit() <= N`: keep it all.
                if self.hold(input) {
                    return self.step_buffered(input, at_end);
                }
                Reject::BadLength
            }
            Probe::Reject(reason) => reason,
        };
        self.consume(input, 1);
        self.stats.count_reject(reason);
        Step::Rejected { offset, reason }
    }

    /// A step on the pending bytes, completing them from the caller's input as needed.
    #[inline(never)]
    fn step_buffered(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        let layout = self.layout;
        let layout = layout.layout();
        let limit = self.limit();
        // A small chunk goes in whole, before anything is probed, and the scan goes on in the
        // buffer: cheaper than probing the pending candidate, completing it with just the
        // bytes it needs and returning to the chunk for a few bytes (PERF.md, lesson 4). The
        // frames do not change: they depend on the bytes, not on where they are held.
        if !input.is_empty() {
            self.stage(input);
        }
        loop {
            let Some(region) = self.buf.get(self.start..self.end) else {
                self.start = 0;
                self.end = 0;
                return Step::Idle;
            };
            let pending = region.len();
            let offset = self.position.wrapping_sub(pending as u64);
            let skip = find_candidate(layout.sync, region);
            if skip > 0 {
                self.start = self.start.wrapping_add(skip);
                self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
                return Step::Skipped { offset, len: skip };
            }
            let readable = self.buf.get(self.start..).unwrap_or_default();
            // `find_candidate` has compared the sync bytes.
            let reason = match probe_synced(&self.layout, readable, pending, limit) {
                Probe::Frame(len) => {
                    let start = self.start;
                    self.start = start.wrapping_add(len);
                    self.stats.count_frame(len);
                    return Step::Buffered {
                        start,
                        end: self.start,
                        offset,
                    };
                }
                Probe::Reject(reason) => reason,
                Probe::Need(_) if input.is_empty() => {
                    if at_end || self.frame_inside(limit) {
                        Reject::Truncated
                    } else {
                        return Step::Idle;
                    }
                }
                Probe::Need(needed) => {
                    if self.fill(input, needed) {
                        continue;
                    }
                    Reject::BadLength
                }
            };
            self.start = self.start.wrapping_add(1);
            self.stats.count_reject(reason);
            return Step::Rejected { offset, reason };
        }
    }

    /// Whether a complete valid frame starts after the first byte of the pending candidate:
    /// then the candidate's claimed length runs over it, and the candidate is taken for a
    /// truncated frame rather than holding the valid one back until more bytes arrive.
    ///
    /// Called each time the input runs out while the candidate waits, so it remembers how many
    /// of the candidate's bytes are known to start no frame (a rejection is final: more bytes
    /// do not change it) and starts after them next time.
    ///
    /// Inlined where the input runs out: most calls end with the block test that finds no
    /// start of the sync bytes among the candidate's bytes, without a call.
    #[inline(always)]
    fn frame_inside(&mut self, limit: usize) -> bool {
        let layout = self.layout;
        let layout = layout.layout();
        let (owner, known, shortest) = self.inside_known();
        // Only a start with room for the shortest frame after it can hold a frame now.
        let Some(last_start) = self.pending().checked_sub(shortest) else {
            return false;
        };
        if known > last_start {
            return false;
        }
        let readable = self
            .buf
            .get(self.start.wrapping_add(known)..)
            .unwrap_or_default();
        let window = last_start.wrapping_sub(known).wrapping_add(1);
        if cfg!(target_pointer_width = "64") && !may_start_sync(layout.sync, readable, window) {
            // None of these bytes starts a frame, now or later; the ones too close to the
            // end may once more bytes arrive.
            self.inner_owner = owner;
            self.inner_dead = last_start.wrapping_add(1);
            return false;
        }
        self.search_inside(limit)
    }

    /// For [`frame_inside`](Self::frame_inside): the pending candidate's stream offset, how
    /// many of its first bytes are known to start no frame (at least its own first byte), and
    /// the shortest frame.
    #[inline(always)]
    fn inside_known(&self) -> (u64, usize, usize) {
        let layout = self.layout;
        let layout = layout.layout();
        let shortest = layout.min_len.max(layout.header_span()).max(1);
        let owner = self.position.wrapping_sub(self.pending() as u64);
        let known = if self.inner_owner == owner {
            self.inner_dead
        } else {
            1
        };
        (owner, known.max(1), shortest)
    }

    /// [`frame_inside`](Self::frame_inside)'s exact search.
    #[inline(never)]
    fn search_inside(&mut self, limit: usize) -> bool {
        let layout = self.layout;
        let layout = layout.layout();
        let (owner, known, shortest) = self.inside_known();
        let readable = self.buf.get(self.start..).unwrap_or_default();
        let region = readable.get(..self.pending()).unwrap_or_default();
        let mut at = known;
        let mut undecided = None;
        let found = loop {
            // Only a start with room for the shortest frame after it can hold a frame.
            let last_start = region.len().saturating_sub(shortest);
            let Some(rest) = region.get(at..).filter(|_| at <= last_start) else {
                break false;
            };
            let window = rest.len().saturating_sub(shortest).saturating_add(1);
            // Read from the buffer, past the pending bytes: whole blocks, masked.
            let readable_rest = readable.get(at..).unwrap_or_default();
            // (The masked block test only where words are 64 bits: on a microcontroller the
            // plain search is smaller and as fast.)
            let skip = if cfg!(not(target_pointer_width = "64"))
                || may_start_sync(layout.sync, readable_rest, window)
            {
                find_first_byte(layout.sync, rest.get(..window).unwrap_or(rest))
            } else {
                window
            };
            if skip >= window {
                // No start left with room for a frame: none of these bytes starts one, now or
                // later, but the ones too close to the end may once more bytes arrive.
                undecided.get_or_insert(at.wrapping_add(window));
                at = region.len();
                break false;
            }
            at = at.wrapping_add(skip);
            let from = readable.get(at..).unwrap_or_default();
            match probe(&self.layout, from, region.len().wrapping_sub(at), limit) {
                Probe::Frame(_) => break true,
                Probe::Need(_) => {
                    undecided.get_or_insert(at);
                }
                Probe::Reject(_) => {}
            }
            at = at.wrapping_add(1);
        };
        self.inner_owner = owner;
        self.inner_dead = undecided.unwrap_or(at);
        found
    }

    /// Appends the whole input behind the pending bytes if it fits the buffer with room for
    /// a checksum window after it (moving the pending bytes to the front first if needed).
    /// Returns `false`, copying nothing, otherwise.
    #[inline(always)]
    fn stage(&mut self, input: &mut &[u8]) -> bool {
        let data: &[u8] = input;
        let room = N.saturating_sub(STAGE_SLACK);
        if self.pending().saturating_add(data.len()) > room {
            return false;
        }
        if self.end.saturating_add(data.len()) > room {
            self.buf.copy_within(self.start..self.end, 0);
            self.end = self.end.wrapping_sub(self.start);
            self.start = 0;
        }
        let end = self.end.wrapping_add(data.len());
        let Some(dst) = self.buf.get_mut(self.end..end) else {
            return false;
        };
        dst.copy_from_slice(data);
        self.end = end;
        self.position = self.position.wrapping_add(data.len() as u64);
        *input = &[];
        true
    }

    /// With nothing pending, copies the start of the input into the buffer: all of it if it
    /// fits with room for a checksum window after it, else as much as fits (at least a byte).
    #[inline(always)]
    fn stage_prefix(&mut self, input: &mut &[u8]) {
        let room = if N > STAGE_SLACK {
            N.wrapping_sub(STAGE_SLACK)
        } else {
            N
        };
        let data: &[u8] = input;
        let (head, rest) = data.split_at_checked(room).unwrap_or((data, &[]));
        if let Some(dst) = self.buf.get_mut(..head.len()) {
            dst.copy_from_slice(head);
            self.start = 0;
            self.end = head.len();
            self.position = self.position.wrapping_add(head.len() as u64);
            *input = rest;
        }
    }

    /// Copies from `input` until the pending bytes number `needed` or the input is exhausted,
    /// moving the pending bytes to the front of the buffer first if they would not fit.
    /// Returns `false`, copying nothing, if `needed` exceeds the buffer.
    fn fill(&mut self, input: &mut &[u8], needed: usize) -> bool {
        if needed > N {
            return false;
        }
        if self.start.saturating_add(needed) > N && self.buf.get(self.start..self.end).is_some() {
            self.buf.copy_within(self.start..self.end, 0);
            self.end = self.end.wrapping_sub(self.start);
            self.start = 0;
        }
        let want = needed.saturating_sub(self.pending()).min(input.len());
        let data: &[u8] = input;
        let Some((src, rest)) = data.split_at_checked(want) else {
            return false;
        };
        let Some(dst) = self
            .end
            .checked_add(want)
            .and_then(|to| self.buf.get_mut(self.end..to))
        else {
            return false;
        };
        dst.copy_from_slice(src);
        *input = rest;
        self.position = self.position.wrapping_add(want as u64);
        self.end = self.end.wrapping_add(want);
        true
    }
}

#[cfg(test)]
mod tests {
    #![allow(
        clippy::indexing_slicing,
        clippy::arithmetic_side_effects,
        clippy::unwrap_used
    )]

    extern crate std;

    use super::{SCAN, may_start_sync};

    /// The definition [`may_start_sync`] filters for: an offset below `n` holding the sync's
    /// first byte, followed by its second (or by the end of `data`).
    fn starts_sync(sync: &[u8], data: &[u8], n: usize) -> bool {
        (0..n.min(data.len())).any(|i| {
            sync.first().is_none_or(|&s| data[i] == s)
                && sync
                    .get(1)
                    .is_none_or(|&s| data.get(i + 1).is_none_or(|&b| b == s))
        })
    }

    #[test]
    fn the_sync_filter_never_misses_a_start() {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut false_true = 0;
        for sync in [
            &[][..],
            &[0xA5],
            &[0xFF, 0xFF],
            &[0xFF, 0xFF, 0xFD],
            &[0x55, 0xAA],
        ] {
            for _ in 0..20_000 {
                let len = (next() % (2 * SCAN as u64 + 20)) as usize;
                // Bytes drawn mostly from the sync's own, so that starts and near misses are
                // common.
                let data: std::vec::Vec<u8> = (0..len)
                    .map(|_| match next() % 4 {
                        0 | 1 => sync.get((next() % 3) as usize).copied().unwrap_or(0),
                        _ => next() as u8,
                    })
                    .collect();
                let n = (next() % (len as u64 + 1)) as usize;
                let exact = starts_sync(sync, &data, n);
                let filtered = may_start_sync(sync, &data, n);
                assert!(filtered || !exact, "{sync:02x?} n={n} {data:02x?}");
                false_true += usize::from(filtered && !exact);
            }
        }
        // A filter that answers `true` to everything would pass the assertion above.
        assert!(false_true < 5 * 20_000 / 10, "{false_true} false starts");
    }
}
