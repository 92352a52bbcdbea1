//! [`Appending`]: the chunked feed of the fastest hand-written decoder known, built from its
//! description: a 2 KiB staging buffer in which a small chunk is appended right behind the
//! still-undecided bytes and the whole contiguous run is scanned; the buffer is compacted only
//! when it is full, so a frame cut by a chunk boundary costs one append, never a move per
//! chunk. A large chunk is scanned in place, after staging just enough of it to decide the
//! pending bytes. No early-truncation search: a candidate waits for its declared length.
//!
//! [`Early`] is the same feed with the framework's early-truncation rule added as one masked
//! block test per chunk that ends inside a candidate: what the rule costs a decoder that does
//! nothing else the best baseline does not. (The runtime's test reads whole blocks unmasked
//! behind a filler it writes when it stages a chunk, which costs less.)

use super::{Lead, Scan};

/// Bytes of the staging buffer.
pub const STAGE: usize = 2048;
/// Chunks shorter than this are appended; longer ones are scanned in place.
const SMALL: usize = 256;
/// Bytes kept free behind the staged run: a checksum window read from a candidate near the end
/// stays inside the buffer.
const SLACK: usize = 128;

/// A [`Scan`] fed in chunks through a 2 KiB buffer compacted only when full; with `EARLY`, the
/// early-truncation rule after every chunk ([`Early`]).
pub struct Appending<S: Scan, const EARLY: bool = false> {
    buf: [u8; STAGE],
    /// The undecided bytes are `buf[start..end]`.
    start: usize,
    end: usize,
    scan: core::marker::PhantomData<S>,
}

/// [`Appending`] with the framework's early-truncation rule: when a chunk ends inside a candidate
/// and a complete valid frame starts after the candidate's first byte, the candidate is
/// rejected at once (the search resumes one byte on) instead of waiting for its declared
/// length. The test is a 64-byte block of the staged bytes compared under a mask of the
/// offsets that may hold such a frame, no state kept between chunks; the exact search runs only
/// where the block holds a possible start.
pub type Early<S> = Appending<S, true>;

impl<S: Scan, const EARLY: bool> Default for Appending<S, EARLY> {
    fn default() -> Self {
        Appending {
            buf: [0; STAGE],
            start: 0,
            end: 0,
            scan: core::marker::PhantomData,
        }
    }
}

impl<S: Scan, const EARLY: bool> Appending<S, EARLY> {
    /// Appends `bytes` behind the undecided ones, moving those to the front first if the buffer
    /// is full.
    #[inline(always)]
    fn append(&mut self, bytes: &[u8]) {
        if self.end + bytes.len() > STAGE - SLACK {
            self.buf.copy_within(self.start..self.end, 0);
            self.end -= self.start;
            self.start = 0;
        }
        self.buf[self.end..self.end + bytes.len()].copy_from_slice(bytes);
        self.end += bytes.len();
    }

    /// Scans the undecided bytes; `start` moves to the first byte still undecided.
    #[inline(always)]
    fn scan_staged<F: FnMut(&[u8])>(&mut self, at_end: bool, sink: &mut F) {
        let done = S::scan(&self.buf[self.start..], self.end - self.start, at_end, sink);
        self.start += done;
        if self.start == self.end {
            self.start = 0;
            self.end = 0;
        }
    }

    /// The early-truncation rule on the undecided bytes, once the chunk is scanned: while a
    /// complete valid frame starts after the first byte of the waiting candidate, the candidate
    /// is rejected and the scan goes on one byte on.
    #[inline(always)]
    fn cut_short<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        while self.end - self.start > S::SHORTEST && self.frame_inside() {
            self.start += 1;
            self.scan_staged(false, sink);
        }
    }

    /// Whether a complete valid frame starts after the first byte of the undecided bytes (more
    /// than `S::SHORTEST` of them).
    #[inline(always)]
    fn frame_inside(&self) -> bool {
        let pending = self.end - self.start;
        // Offsets 1..=last may start a frame complete now.
        let last = pending - S::SHORTEST;
        let mut from = 1;
        while from <= last {
            // In bounds: `SLACK` bytes lie behind the undecided ones.
            let block = self.buf[self.start + from..].first_chunk::<{ BLOCK + MAX_REACH }>();
            let hit = match block {
                Some(block) => may_start(S::LEAD, block, last + 1 - from),
                None => true,
            };
            if hit {
                let mut found = false;
                let rest = &self.buf[self.start + 1..];
                S::scan(rest, pending - 1, true, &mut |_: &[u8]| found = true);
                return found;
            }
            from += BLOCK;
        }
        false
    }
}

/// Offsets one block test covers.
const BLOCK: usize = 64;
/// The largest [`Lead::reach`] of the protocols here.
const MAX_REACH: usize = 2;

/// `KEEP[BLOCK - n..][..BLOCK]` keeps the first `n` offsets of a block.
static KEEP: [u8; 2 * BLOCK] = {
    let mut m = [0u8; 2 * BLOCK];
    let mut i = 0;
    while i < BLOCK {
        m[i] = 0xFF;
        i += 1;
    }
    m
};

/// Whether one of the first `min(n, BLOCK)` offsets of `block` holds `lead`: compared byte by
/// byte under a mask of the offsets kept, with no branch per byte (the compiler makes it a few
/// vector compares and one test).
#[inline(always)]
fn may_start(lead: Lead, block: &[u8; BLOCK + MAX_REACH], n: usize) -> bool {
    let keep = &KEEP[BLOCK - n.min(BLOCK)..][..BLOCK];
    let mut hits = 0u8;
    for i in 0..BLOCK {
        let pair = (block[i] == lead.first) & (block[i + lead.reach] & lead.mask == lead.value);
        hits |= u8::from(pair) & keep[i];
    }
    hits != 0
}

impl<S: Scan, const EARLY: bool> crate::ChunkDecoder for Appending<S, EARLY> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, mut chunk: &[u8], sink: &mut F) {
        if chunk.len() < SMALL {
            self.append(chunk);
            self.scan_staged(false, sink);
            if EARLY {
                self.cut_short(sink);
            }
            return;
        }
        if self.end > self.start {
            // The undecided bytes are shorter than a frame: `MAX_FRAME` more decide every
            // candidate that starts among them.
            let old = self.end - self.start;
            let take = S::MAX_FRAME;
            self.append(&chunk[..take]);
            self.scan_staged(false, sink);
            let pending = self.end - self.start;
            // The scan stopped at a candidate that starts in the chunk (or ran through).
            let resume = old + take - pending;
            chunk = &chunk[resume - old..];
            self.start = 0;
            self.end = 0;
        }
        let done = S::scan(chunk, chunk.len(), false, sink);
        let tail = &chunk[done..];
        self.buf[..tail.len()].copy_from_slice(tail);
        self.start = 0;
        self.end = tail.len();
        if EARLY {
            self.cut_short(sink);
        }
    }

    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        self.scan_staged(true, sink);
        self.start = 0;
        self.end = 0;
    }
}
