//! [`StreamDecoder`]: finds frames in input that arrives in chunks, and accounts for every
//! byte ([`Stats`]) and every decision ([`Event`]).
//!
//! This module owns the decoder's state and the order of its work: the public calls, the
//! choice between scanning the caller's chunk in place and staging it, and the steps that hand
//! out one event at a time, with the rule that a rejection costs one byte. It leans on its
//! siblings for the rest: the searches (`search`), the scan loop (`scan`), the buffer's copies
//! (`buffer`) and the event types (`event`); whether a candidate is a frame is decided by
//! [`FrameLayout::probe`]'s rules, in the parent module.

use core::fmt;

use super::buffer::take;
use super::event::{Event, Frame, Reject, Stats};
use super::search::{find_link, frame_inside, frame_may_be_inside};
use super::target::{EARLY_TRUNCATION, HOST, SCAN_IN_PLACE};
use super::{Probe, link_max_len, probe_link_synced, scan};
use crate::layout::{FrameLayout, LayoutRef};

/// One step of the engine: the data of an [`Event`], with frames as numbers: a buffered frame
/// as a range, so that the engine's buffer is borrowed only once the step is over, and a frame
/// of the input as its length, taken from the input by the caller. (A step holding a slice was
/// returned through memory and read back with one wide load from two narrow stores: a store
/// forwarding stall once per frame.)
pub(super) enum Step {
    /// The next `len` bytes of the input are a frame (consumed by the caller).
    Input {
        len: usize,
        offset: u64,
        format: usize,
    },
    Buffered {
        start: usize,
        end: usize,
        offset: u64,
        format: usize,
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
/// is staged in the buffer first, which takes less code (the module docs list the
/// [target and build switches](crate::decoder#target-and-build-switches)). Frames longer than
/// `min(max_len, N)` are rejected as [`Reject::BadLength`].
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
///     sync_set: &[],
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
///     escape: None,
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
// In declaration order (`repr(C)`): the words every step reads and writes first, ahead of the
// buffer, which makes the HFLink firmware (thumbv7em) smaller than with the buffer first
// (`benches/footprint.sh` measures it).
#[repr(C)]
pub struct StreamDecoder<L: LayoutRef, const N: usize> {
    /// What [`Self::frame_inside`] learnt about the pending candidate starting at stream offset
    /// `inner_owner`: its first `inner_dead` bytes start no frame, now or later (at least its
    /// first byte, the candidate's own start). For an escaped format, the escaped path's state
    /// instead (`escaped.rs`).
    pub(super) inner_dead: usize,
    /// The pending bytes are `buf[start..end]`; `start < end` or both are 0.
    pub(super) start: usize,
    pub(super) end: usize,
    pub(super) buf: [u8; N],
    pub(super) layout: L,
    /// Bytes consumed from all inputs.
    pub(super) position: u64,
    pub(super) stats: Stats,
    pub(super) inner_owner: u64,
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

    /// The layout value the decoder was made with (a generated `Layout` type, or a run-time
    /// codec's format), for what it knows besides the frame format (its packets' decoding).
    #[inline]
    pub fn layout_ref(&self) -> &L {
        &self.layout
    }

    /// What was counted since the decoder was created or reset.
    #[inline]
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// Bytes held in the buffer: the start of a candidate the input has not completed yet.
    /// For an escaped format, the candidate's bytes on the wire not counted yet (its buffer
    /// holds them unescaped: [`pending_bytes`](Self::pending_bytes)), so that the bytes fed
    /// are always the frame bytes, the skipped bytes and these.
    #[inline]
    pub fn pending(&self) -> usize {
        if L::ESCAPED && self.layout.layout().escape.is_some() {
            return self.escaped_pending();
        }
        self.buffered()
    }

    /// The bytes in the buffer.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn buffered(&self) -> usize {
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
        // An escaped format has a path of its own (`escaped.rs`); for a generated layout this
        // test is a constant.
        if L::ESCAPED && self.layout.layout().escape.is_some() {
            while let Some(frame) = self.next_frame(&mut chunk, false) {
                sink(frame);
            }
            return;
        }
        // Input cut into small chunks: a candidate waits for the rest of its bytes, the chunk
        // goes whole behind them and the scan goes on in the buffer; the chunk is used up,
        // and unless a frame is complete inside the candidate still waiting, so is this call.
        // The rest is out of line. (Where every chunk is staged, the rest does this too: one
        // copy of the scan in firmware.)
        if SCAN_IN_PLACE && self.start < self.end && self.stage(&mut chunk) {
            self.scan_buffered(&mut sink);
            // (`stage` has written its filler behind the chunk.)
            if self.start >= self.end || !self.frame_inside(self.limit(), true) {
                return;
            }
        }
        self.feed_rest(chunk, &mut sink);
    }

    /// [`feed`](Self::feed) but for its first step: a chunk scanned in place, a chunk too
    /// large to stage, a candidate that a frame inside it cuts short.
    #[inline(never)]
    fn feed_rest(&mut self, mut chunk: &[u8], sink: &mut impl FnMut(Frame<'_>)) {
        loop {
            if self.start >= self.end && SCAN_IN_PLACE {
                self.scan_input(&mut chunk, sink);
                if chunk.is_empty() {
                    return;
                }
                // A candidate runs to the end of the chunk and needs more: keep it and, unless
                // a frame is complete inside it, wait (what `step_input` and `step_buffered`
                // would decide, without probing the candidate twice more).
                if self.hold(&mut chunk) && !self.frame_inside(self.limit(), false) {
                    return;
                }
            } else {
                if !chunk.is_empty() {
                    self.stage(&mut chunk);
                }
                self.scan_buffered(sink);
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
                } else if chunk.is_empty() && !self.frame_inside(self.limit(), false) {
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

    /// The [scan](scan::scan) of the pending bytes, for [`feed`](Self::feed), once the chunk
    /// is staged: frames, rejected candidates and skipped runs, until a candidate needs more
    /// bytes than are pending (left to the general engine).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn scan_buffered(&mut self, sink: &mut impl FnMut(Frame<'_>)) {
        let limit = self.limit();
        // (Never `None`: `start <= end <= N`. Branches the processor predicts, where fallback
        // values cost conditional moves on every chunk.)
        let (Some(pending), Some(readable)) =
            (self.end.checked_sub(self.start), self.buf.get(self.start..))
        else {
            return;
        };
        let base = self.position.wrapping_sub(pending as u64);
        let done = scan::scan(
            &self.layout,
            readable,
            pending,
            base,
            limit,
            &mut self.stats,
            sink,
        );
        self.start = self.start.wrapping_add(done.min(pending));
        if self.start >= self.end {
            self.start = 0;
            self.end = 0;
        }
    }

    /// The [scan](scan::scan) of `input` in place, for [`feed`](Self::feed), with nothing
    /// pending: frames, rejected candidates and skipped runs, until a candidate needs more
    /// bytes than `input` holds (left to the general engine, which buffers it) or `input` is
    /// used up.
    ///
    /// Out of line: the loop gets registers of its own (inlined into `feed`, whose other paths
    /// keep their state live around it, the loop reloads the input's pointer from the stack
    /// every frame).
    #[inline(never)]
    fn scan_input(&mut self, input: &mut &[u8], sink: &mut impl FnMut(Frame<'_>)) {
        let data: &[u8] = input;
        let limit = self.limit();
        let base = self.position;
        let done = scan::scan(
            &self.layout,
            data,
            data.len(),
            base,
            limit,
            &mut self.stats,
            sink,
        );
        self.position = self.position.wrapping_add(done as u64);
        *input = data.get(done..).unwrap_or_default();
    }

    // Inlined into the caller's loop: the common step (a frame found in the input) is a few
    // dozen instructions, which a call and a return per frame would add to; the buffered
    // steps stay out of line.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn next_frame<'s, 'i: 's>(
        &'s mut self,
        input: &mut &'i [u8],
        at_end: bool,
    ) -> Option<Frame<'s>> {
        // The two kinds of step are matched apart, not through `step`: a step result that
        // comes from either an inlined or a called function is passed through memory, and
        // reading a frame back from there stalled on store forwarding, once per frame.
        let (start, end, offset, format) = loop {
            if L::ESCAPED && self.layout.layout().escape.is_some() {
                match self.escaped_step(input, at_end) {
                    Step::Buffered {
                        start,
                        end,
                        offset,
                        format,
                    } => break (start, end, offset, format),
                    Step::Idle => return None,
                    _ => continue,
                }
            }
            if self.start < self.end {
                match self.step_buffered(input, at_end) {
                    Step::Input {
                        len,
                        offset,
                        format,
                    } => {
                        let bytes = take(input, len);
                        return Some(Frame {
                            bytes,
                            offset,
                            format,
                        });
                    }
                    Step::Buffered {
                        start,
                        end,
                        offset,
                        format,
                    } => break (start, end, offset, format),
                    Step::Rejected { .. } | Step::Skipped { .. } => {}
                    Step::Idle => return None,
                }
            } else {
                self.start = 0;
                self.end = 0;
                match self.step_input(input, at_end) {
                    Step::Input {
                        len,
                        offset,
                        format,
                    } => {
                        let bytes = take(input, len);
                        return Some(Frame {
                            bytes,
                            offset,
                            format,
                        });
                    }
                    Step::Buffered {
                        start,
                        end,
                        offset,
                        format,
                    } => break (start, end, offset, format),
                    Step::Rejected { .. } | Step::Skipped { .. } => {}
                    Step::Idle => return None,
                }
            }
        };
        Some(Frame {
            bytes: self.buf.get(start..end).unwrap_or_default(),
            offset,
            format,
        })
    }

    fn event<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8], at_end: bool) -> Option<Event<'s>> {
        Some(match self.step(input, at_end) {
            Step::Input {
                len,
                offset,
                format,
            } => Event::Frame(Frame {
                bytes: take(input, len),
                offset,
                format,
            }),
            Step::Buffered {
                start,
                end,
                offset,
                format,
            } => Event::Frame(Frame {
                bytes: self.buf.get(start..end).unwrap_or_default(),
                offset,
                format,
            }),
            Step::Rejected { offset, reason } => Event::Rejected { offset, reason },
            Step::Skipped { offset, len } => Event::Skipped { offset, len },
            Step::Idle => return None,
        })
    }

    /// Frames longer than this are rejected (and longer than their own format's `max_len`).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn limit(&self) -> usize {
        link_max_len(&self.layout).min(N)
    }

    /// One event's worth of work.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn step(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        if L::ESCAPED && self.layout.layout().escape.is_some() {
            return self.escaped_step(input, at_end);
        }
        if self.start < self.end {
            self.step_buffered(input, at_end)
        } else {
            self.start = 0;
            self.end = 0;
            self.step_input(input, at_end)
        }
    }

    /// A step on the caller's input, with nothing pending.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn step_input(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        // (A buffer of no bytes stages nothing: scanned in place, where every candidate is
        // too long.)
        if !SCAN_IN_PLACE && N > 0 && !input.is_empty() {
            self.stage_prefix(input);
            return self.step_buffered(input, at_end);
        }
        self.step_in::<InInput>(input, at_end)
    }

    /// A step on the pending bytes, completing them from the caller's input as needed.
    #[inline(never)]
    fn step_buffered(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        // A small chunk goes in whole, before anything is probed, and the scan goes on in the
        // buffer: cheaper than probing the pending candidate, completing it with just the
        // bytes it needs and returning to the chunk for a few bytes, which costs a second
        // search and a second probe per chunk. The frames do not change: they depend on the
        // bytes, not on where they are held.
        if !input.is_empty() {
            self.stage(input);
        }
        self.step_in::<InBuffer>(input, at_end)
    }

    /// One step on the bytes at `P`: a skipped run, a frame, a rejected candidate (which
    /// costs one byte), or what `P` does with a candidate that needs more bytes.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn step_in<P: Place>(&mut self, input: &mut &[u8], at_end: bool) -> Step {
        let limit = self.limit();
        loop {
            let Some((region, offset)) = P::bytes(self, input) else {
                return P::idle(self);
            };
            let skip = find_link(&self.layout, region);
            if skip > 0 {
                P::advance(self, input, skip);
                self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
                return Step::Skipped { offset, len: skip };
            }
            let pending = region.len();
            let readable = P::readable(self, input);
            // `find_candidate` has compared the sync bytes.
            let reason = match probe_link_synced(&self.layout, readable, pending, limit) {
                (format, Probe::Frame(len)) => {
                    self.stats.count_frame(len);
                    return P::frame(self, len, offset, format);
                }
                (_, Probe::Reject(reason)) => reason,
                (_, Probe::Need(needed)) => match P::need(self, input, needed, limit, at_end) {
                    Need::Again => continue,
                    Need::Step(step) => return step,
                    Need::Reject(reason) => reason,
                },
            };
            P::advance(self, input, 1);
            self.stats.count_reject(reason);
            return Step::Rejected { offset, reason };
        }
    }

    /// Whether a complete valid frame starts after the first byte of the pending candidate
    /// ([`search::frame_inside`](super::search::frame_inside)), with what earlier calls learnt
    /// about this candidate: how many of its first bytes start no frame.
    ///
    /// Inlined on hosts, where the block test usually answers; out of line elsewhere, where it
    /// has no block test and is called from two places (the
    /// [host switch](crate::decoder#target-and-build-switches)). `filled`:
    /// [`stage`](Self::stage) has just written its filler behind the pending bytes, and the
    /// block test reads whole blocks unmasked
    /// ([`search::frame_may_be_inside`](super::search::frame_may_be_inside)).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn frame_inside(&mut self, limit: usize, filled: bool) -> bool {
        if !EARLY_TRUNCATION {
            return false;
        }
        if HOST {
            self.frame_inside_here(limit, filled)
        } else {
            self.frame_inside_apart(limit)
        }
    }

    /// [`frame_inside`](Self::frame_inside), out of line.
    #[inline(never)]
    fn frame_inside_apart(&mut self, limit: usize) -> bool {
        self.frame_inside_here(limit, false)
    }

    /// [`frame_inside`](Self::frame_inside)'s body.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn frame_inside_here(&mut self, limit: usize, filled: bool) -> bool {
        let pending = self.buffered();
        // (The block test on hosts only: on a microcontroller the exact search is smaller and
        // as fast.)
        if HOST {
            let Some(readable) = self.buf.get(self.start..) else {
                return false;
            };
            if !frame_may_be_inside(&self.layout, readable, pending, limit, filled) {
                return false;
            }
        }
        let owner = self.position.wrapping_sub(pending as u64);
        if self.inner_owner != owner {
            self.inner_owner = owner;
            self.inner_dead = 1;
        }
        let Some(readable) = self.buf.get(self.start..) else {
            return false;
        };
        frame_inside(&self.layout, readable, pending, &mut self.inner_dead, limit)
    }
}

/// What a [`Place`] does with a candidate that needs more bytes than it holds.
enum Need {
    /// More bytes are there: probe the candidate again.
    Again,
    /// The step is this.
    Step(Step),
    /// The candidate is rejected.
    Reject(Reject),
}

/// Where the bytes of a step live ([`StreamDecoder::step_in`]): the caller's input
/// ([`InInput`]) or the decoder's buffer ([`InBuffer`]). Each is a type of its own, so that
/// the step is compiled once for each, with these functions inlined.
trait Place {
    /// The bytes to search and the stream offset of the first; `None` if there are none.
    fn bytes<'a, L: LayoutRef, const N: usize>(
        decoder: &'a StreamDecoder<L, N>,
        input: &'a [u8],
    ) -> Option<(&'a [u8], u64)>;

    /// The bytes readable from the same start: a window checksum may read past the searched
    /// ones. (Apart from [`bytes`](Self::bytes), taken after the search: the firmware's
    /// buffered step is smaller so; `benches/footprint.sh` measures it.)
    fn readable<'a, L: LayoutRef, const N: usize>(
        decoder: &'a StreamDecoder<L, N>,
        input: &'a [u8],
    ) -> &'a [u8];

    /// The step when [`bytes`](Self::bytes) finds none.
    fn idle<L: LayoutRef, const N: usize>(decoder: &mut StreamDecoder<L, N>) -> Step;

    /// Moves past the first `n` bytes searched.
    fn advance<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        input: &mut &[u8],
        n: usize,
    );

    /// The step for a frame of the first `len` bytes, moving past it.
    fn frame<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        len: usize,
        offset: u64,
        format: usize,
    ) -> Step;

    /// A candidate at the start needs `needed` bytes, more than there are.
    fn need<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        input: &mut &[u8],
        needed: usize,
        limit: usize,
        at_end: bool,
    ) -> Need;
}

/// The caller's input, with nothing pending: frames are taken from it by the caller.
struct InInput;

impl Place for InInput {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn bytes<'a, L: LayoutRef, const N: usize>(
        decoder: &'a StreamDecoder<L, N>,
        input: &'a [u8],
    ) -> Option<(&'a [u8], u64)> {
        if input.is_empty() {
            return None;
        }
        Some((input, decoder.position))
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn readable<'a, L: LayoutRef, const N: usize>(
        _decoder: &'a StreamDecoder<L, N>,
        input: &'a [u8],
    ) -> &'a [u8] {
        input
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn idle<L: LayoutRef, const N: usize>(_decoder: &mut StreamDecoder<L, N>) -> Step {
        Step::Idle
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn advance<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        input: &mut &[u8],
        n: usize,
    ) {
        decoder.consume(input, n);
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn frame<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        len: usize,
        offset: u64,
        format: usize,
    ) -> Step {
        // `len <= input.len()`: the caller takes the bytes from the input.
        decoder.position = decoder.position.wrapping_add(len as u64);
        Step::Input {
            len,
            offset,
            format,
        }
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn need<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        input: &mut &[u8],
        _needed: usize,
        _limit: usize,
        at_end: bool,
    ) -> Need {
        // The candidate runs to the end of the input, which is then shorter than what it
        // needs, itself at most `limit() <= N`: keep it all.
        if decoder.hold(input) {
            Need::Step(decoder.step_buffered(input, at_end))
        } else {
            Need::Reject(Reject::BadLength)
        }
    }
}

/// The pending bytes, completed from the caller's input as needed.
struct InBuffer;

impl Place for InBuffer {
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn bytes<'a, L: LayoutRef, const N: usize>(
        decoder: &'a StreamDecoder<L, N>,
        _input: &'a [u8],
    ) -> Option<(&'a [u8], u64)> {
        let region = decoder.buf.get(decoder.start..decoder.end)?;
        let offset = decoder.position.wrapping_sub(region.len() as u64);
        Some((region, offset))
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn readable<'a, L: LayoutRef, const N: usize>(
        decoder: &'a StreamDecoder<L, N>,
        _input: &'a [u8],
    ) -> &'a [u8] {
        decoder.buf.get(decoder.start..).unwrap_or_default()
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn idle<L: LayoutRef, const N: usize>(decoder: &mut StreamDecoder<L, N>) -> Step {
        decoder.start = 0;
        decoder.end = 0;
        Step::Idle
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn advance<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        _input: &mut &[u8],
        n: usize,
    ) {
        decoder.start = decoder.start.wrapping_add(n);
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn frame<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        len: usize,
        offset: u64,
        format: usize,
    ) -> Step {
        let start = decoder.start;
        decoder.start = start.wrapping_add(len);
        Step::Buffered {
            start,
            end: decoder.start,
            offset,
            format,
        }
    }

    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn need<L: LayoutRef, const N: usize>(
        decoder: &mut StreamDecoder<L, N>,
        input: &mut &[u8],
        needed: usize,
        limit: usize,
        at_end: bool,
    ) -> Need {
        if !input.is_empty() {
            if decoder.fill(input, needed) {
                Need::Again
            } else {
                Need::Reject(Reject::BadLength)
            }
        } else if at_end || decoder.frame_inside(limit, false) {
            Need::Reject(Reject::Truncated)
        } else {
            Need::Step(Step::Idle)
        }
    }
}
