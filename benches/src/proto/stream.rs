//! The prototype engine: the runtime's `StreamDecoder` (`protocol-runtime/src/decoder/stream.rs`)
//! and `FrameLayout::probe_within` (`decoder/mod.rs`), copied with the same rules and changed
//! only where [`super`] says. Event reporting (`next_event`) is left out: the benchmark decodes
//! frames only.

use protocol_runtime::decoder::{Frame, Probe, Reject};
use protocol_runtime::layout::{ByteOrder, LengthRule, WordField};
use protocol_runtime::{FrameLayout, Stats};

use super::LayoutSource;
use crate::ChunkDecoder;

/// Where the first candidate of `data` starts (as the runtime's `find_candidate`).
#[inline(always)]
fn find_candidate(sync: &[u8], data: &[u8]) -> usize {
    let Some((&first, more)) = sync.split_first() else {
        return 0;
    };
    let continues = |at: usize| {
        let after = data.get(at.wrapping_add(1)..).unwrap_or_default();
        after.iter().zip(more).all(|(a, b)| a == b)
    };
    if data.first() == Some(&first) && continues(0) {
        return 0;
    }
    let mut from = 0;
    while let Some(hit) = data
        .get(from..)
        .and_then(|rest| memchr::memchr(first, rest))
    {
        let at = from.wrapping_add(hit);
        if continues(at) {
            return at;
        }
        from = at.wrapping_add(1);
    }
    data.len()
}

/// [`find_candidate`] for the short regions of [`ProtoDecoder::frame_inside`] (a pending
/// candidate, less than a frame): a plain loop, cheaper than a call to memchr on a few bytes.
#[inline(always)]
fn find_candidate_short(sync: &[u8], data: &[u8]) -> usize {
    let Some((&first, more)) = sync.split_first() else {
        return 0;
    };
    for (at, &b) in data.iter().enumerate() {
        if b == first {
            let after = data.get(at + 1..).unwrap_or_default();
            if after.iter().zip(more).all(|(a, b)| a == b) {
                return at;
            }
        }
    }
    data.len()
}

/// `WordField::read`, inlined.
#[inline(always)]
fn read_word(f: &WordField, header: &[u8]) -> Option<u64> {
    let at = f.at.resolve(header.len())?;
    let size = usize::from(f.size);
    let bytes = header.get(at..at.checked_add(size)?)?;
    let mut word = 0u64;
    for i in 0..size.min(8) {
        let b = match f.order {
            ByteOrder::Big => bytes[i],
            ByteOrder::Little => bytes[size - 1 - i],
        };
        word = (word << 8) | u64::from(b);
    }
    let mask = if f.width >= 64 {
        u64::MAX
    } else {
        (1u64 << f.width) - 1
    };
    Some((word >> f.shift) & mask)
}

/// `FrameLayout::frame_len`, inlined.
#[inline(always)]
fn frame_len(layout: &FrameLayout<'_>, header: &[u8]) -> Option<usize> {
    let header = header.get(..layout.header_span())?;
    match layout.length {
        LengthRule::Fixed(len) => Some(len),
        LengthRule::Field { field, adjust } | LengthRule::FieldOrBare { field, adjust, .. } => {
            let value = i64::try_from(read_word(&field, header)?).ok()?;
            usize::try_from(value.checked_add(adjust)?).ok()
        }
    }
}

/// `probe_within` on `readable[..avail]`, with the layout a constant and the checks of the
/// [`LayoutSource`], computed with `readable` (the rest of the input, or of the buffer) in reach:
/// bytes past `avail` are read by window checks, masked out, and never decide anything.
#[inline(always)]
fn probe<L: LayoutSource>(readable: &[u8], avail: usize, limit: usize) -> Probe {
    let layout: &FrameLayout<'static> = L::layout();
    let bytes = readable.get(..avail).unwrap_or_default();
    if !bytes.iter().zip(layout.sync).all(|(a, b)| a == b) {
        return Probe::Reject(Reject::BadHeader);
    }
    let span = layout.header_span();
    if span > limit {
        if bytes.len() < layout.sync.len() {
            return Probe::Need(layout.sync.len());
        }
        return Probe::Reject(Reject::BadLength);
    }
    let Some(header) = bytes.get(..span) else {
        return Probe::Need(span);
    };
    // Plain loops and an inlined word reader: with the layout a constant, `Iterator::all` and
    // `WordField::read` were left out of line by the compiler, and the interpretation stayed.
    for c in layout.constants {
        if read_word(&c.field, header) != Some(c.value) {
            return Probe::Reject(Reject::BadHeader);
        }
    }
    for c in L::header_checks() {
        if !c.verify(readable, span) {
            return Probe::Reject(Reject::BadHeaderCheck);
        }
    }
    let bare = layout.length.bare_len();
    let total = match frame_len(layout, header) {
        Some(t) if Some(t) == bare && t >= span && t > 0 && t <= limit => {
            return Probe::Frame(t);
        }
        Some(t) if t >= span && t > 0 && t >= layout.min_len && t <= limit => t,
        _ => return Probe::Reject(Reject::BadLength),
    };
    let Some(frame) = bytes.get(..total) else {
        return Probe::Need(total);
    };
    for c in L::frame_checks() {
        if !c.verify(readable, total) {
            return Probe::Reject(Reject::BadChecksum);
        }
    }
    if !layout.markers.iter().all(|m| m.matches(frame)) {
        return Probe::Reject(Reject::BadTrailer);
    }
    Probe::Frame(total)
}

enum Step<'i> {
    Input(Frame<'i>),
    Buffered {
        start: usize,
        end: usize,
        offset: u64,
    },
    Rejected,
    Skipped,
    Idle,
}

/// The prototype decoder: frames of at most `N` bytes, a buffer of `B >= N` bytes (the room
/// above `N` takes whole chunks when [`LayoutSource::STAGE`] is on).
pub struct ProtoDecoder<L: LayoutSource, const N: usize, const B: usize> {
    buf: [u8; B],
    start: usize,
    end: usize,
    position: u64,
    stats: Stats,
    inner_owner: u64,
    inner_dead: usize,
    layout: core::marker::PhantomData<L>,
}

impl<L: LayoutSource, const N: usize, const B: usize> Default for ProtoDecoder<L, N, B> {
    fn default() -> Self {
        const { assert!(B >= N) };
        ProtoDecoder {
            buf: [0; B],
            start: 0,
            end: 0,
            position: 0,
            stats: Stats::default(),
            inner_owner: u64::MAX,
            inner_dead: 0,
            layout: core::marker::PhantomData,
        }
    }
}

impl<L: LayoutSource, const N: usize, const B: usize> ProtoDecoder<L, N, B> {
    /// What was counted.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// The next valid frame, consuming from `*input` (as the runtime's `decode`).
    #[inline]
    pub fn decode<'s, 'i: 's>(&'s mut self, input: &mut &'i [u8]) -> Option<Frame<'s>> {
        self.next_frame(input, false)
    }

    /// The next frame among the pending bytes once the input has ended.
    pub fn flush(&mut self) -> Option<Frame<'_>> {
        self.next_frame(&mut &[][..], true)
    }

    #[inline(always)]
    fn next_frame<'s, 'i: 's>(
        &'s mut self,
        input: &mut &'i [u8],
        at_end: bool,
    ) -> Option<Frame<'s>> {
        let (start, end, offset) = loop {
            match self.step(input, at_end) {
                Step::Input(frame) => return Some(frame),
                Step::Buffered { start, end, offset } => break (start, end, offset),
                Step::Rejected | Step::Skipped => {}
                Step::Idle => return None,
            }
        };
        Some(Frame {
            bytes: self.buf.get(start..end).unwrap_or_default(),
            offset,
        })
    }

    #[inline(always)]
    fn limit(&self) -> usize {
        L::layout().max_len.min(N)
    }

    #[inline(always)]
    fn consume<'i>(&mut self, input: &mut &'i [u8], n: usize) -> &'i [u8] {
        let data: &'i [u8] = input;
        let (head, rest) = data.split_at_checked(n).unwrap_or((data, &[]));
        *input = rest;
        self.position = self.position.wrapping_add(head.len() as u64);
        head
    }

    #[inline(always)]
    fn reject(&mut self, reason: Reject) {
        self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(1);
        let counter = match reason {
            Reject::BadHeader => &mut self.stats.bad_header,
            Reject::BadHeaderCheck => &mut self.stats.bad_header_check,
            Reject::BadLength => &mut self.stats.bad_length,
            Reject::BadChecksum => &mut self.stats.bad_checksum,
            Reject::BadTrailer => &mut self.stats.bad_trailer,
            _ => &mut self.stats.truncated,
        };
        *counter = counter.wrapping_add(1);
    }

    #[inline(always)]
    fn count_frame(&mut self, len: usize) {
        self.stats.frames = self.stats.frames.wrapping_add(1);
        self.stats.frame_bytes = self.stats.frame_bytes.wrapping_add(len as u64);
    }

    #[inline(always)]
    fn step<'i>(&mut self, input: &mut &'i [u8], at_end: bool) -> Step<'i> {
        if self.start < self.end {
            self.step_buffered(input, at_end)
        } else {
            self.start = 0;
            self.end = 0;
            self.step_input(input, at_end)
        }
    }

    #[inline(always)]
    fn step_input<'i>(&mut self, input: &mut &'i [u8], at_end: bool) -> Step<'i> {
        let data: &'i [u8] = input;
        if data.is_empty() {
            return Step::Idle;
        }
        let offset = self.position;
        let skip = find_candidate(L::layout().sync, data);
        if skip > 0 {
            let len = self.consume(input, skip).len();
            self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(len as u64);
            return Step::Skipped;
        }
        let reason = match probe::<L>(data, data.len(), self.limit()) {
            Probe::Frame(len) => {
                let bytes = self.consume(input, len);
                self.count_frame(bytes.len());
                return Step::Input(Frame { bytes, offset });
            }
            Probe::Need(_) => {
                if let Some(dst) = self.buf.get_mut(..data.len()) {
                    dst.copy_from_slice(data);
                    self.start = 0;
                    self.end = data.len();
                    self.consume(input, data.len());
                    return self.step_buffered(input, at_end);
                }
                Reject::BadLength
            }
            Probe::Reject(reason) => reason,
        };
        self.consume(input, 1);
        self.reject(reason);
        Step::Rejected
    }

    fn step_buffered<'i>(&mut self, input: &mut &'i [u8], at_end: bool) -> Step<'i> {
        let limit = self.limit();
        loop {
            let Some(region) = self.buf.get(self.start..self.end) else {
                self.start = 0;
                self.end = 0;
                return Step::Idle;
            };
            let pending = region.len();
            let offset = self.position.wrapping_sub(pending as u64);
            let skip = find_candidate(L::layout().sync, region);
            if skip > 0 {
                self.start = self.start.wrapping_add(skip);
                self.stats.skipped_bytes = self.stats.skipped_bytes.wrapping_add(skip as u64);
                return Step::Skipped;
            }
            let readable = self.buf.get(self.start..).unwrap_or_default();
            let reason = match probe::<L>(readable, pending, limit) {
                Probe::Frame(len) => {
                    let start = self.start;
                    self.start = start.wrapping_add(len);
                    self.count_frame(len);
                    return Step::Buffered {
                        start,
                        end: self.start,
                        offset,
                    };
                }
                Probe::Reject(reason) => reason,
                Probe::Need(_) if input.is_empty() => {
                    if at_end || (L::EARLY_TRUNCATION && self.frame_inside(limit)) {
                        Reject::Truncated
                    } else {
                        return Step::Idle;
                    }
                }
                // Change 3: a chunk that fits goes in whole, and the scan goes on in the buffer.
                Probe::Need(_) if L::STAGE && self.stage(input) => continue,
                Probe::Need(needed) => {
                    if self.fill(input, needed) {
                        continue;
                    }
                    Reject::BadLength
                }
            };
            self.start = self.start.wrapping_add(1);
            self.reject(reason);
            return Step::Rejected;
        }
    }

    /// Appends the whole input behind the pending bytes if it fits the buffer (moving the
    /// pending bytes to the front first if needed); false, copying nothing, otherwise.
    #[inline(always)]
    fn stage(&mut self, input: &mut &[u8]) -> bool {
        let data: &[u8] = input;
        // Room for a window check past the last frame start, so that it never falls back to
        // a byte loop.
        let room = B.saturating_sub(super::checks::WINDOW);
        if self.pending() + data.len() > room {
            return false;
        }
        if self.end + data.len() > room {
            self.buf.copy_within(self.start..self.end, 0);
            self.end -= self.start;
            self.start = 0;
        }
        self.buf[self.end..self.end + data.len()].copy_from_slice(data);
        self.end += data.len();
        self.position = self.position.wrapping_add(data.len() as u64);
        *input = &[];
        true
    }

    #[inline(always)]
    fn pending(&self) -> usize {
        self.end.saturating_sub(self.start)
    }

    fn frame_inside(&mut self, limit: usize) -> bool {
        let layout = L::layout();
        let shortest = layout.min_len.max(layout.header_span()).max(1);
        let owner = self.position.wrapping_sub(self.pending() as u64);
        let known = if self.inner_owner == owner {
            self.inner_dead
        } else {
            1
        };
        let region = self.buf.get(self.start..self.end).unwrap_or_default();
        let mut at = known.max(1);
        let mut undecided = None;
        let found = loop {
            let rest = region.get(at..).unwrap_or_default();
            if rest.len() < shortest {
                break false;
            }
            let skip = find_candidate_short(layout.sync, rest);
            let Some(candidate) = rest.get(skip..).filter(|c| !c.is_empty()) else {
                at = region.len();
                break false;
            };
            at = at.wrapping_add(skip);
            let readable = self.buf.get(self.start + at..).unwrap_or_default();
            match probe::<L>(readable, candidate.len(), limit) {
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

    fn fill(&mut self, input: &mut &[u8], needed: usize) -> bool {
        if needed > N {
            return false;
        }
        if self.start.saturating_add(needed) > B && self.buf.get(self.start..self.end).is_some() {
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

impl<L: LayoutSource, const N: usize, const B: usize> ChunkDecoder for ProtoDecoder<L, N, B> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, mut chunk: &[u8], sink: &mut F) {
        while let Some(frame) = self.decode(&mut chunk) {
            sink(frame.bytes);
        }
    }

    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        while let Some(frame) = self.flush() {
            sink(frame.bytes);
        }
    }
}
