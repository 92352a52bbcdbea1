//! [`Appending`]: the chunked feed of the fastest hand-written decoder known, built from its
//! description: a 2 KiB staging buffer in which a small chunk is appended right behind the
//! still-undecided bytes and the whole contiguous run is scanned; the buffer is compacted only
//! when it is full, so a frame cut by a chunk boundary costs one append, never a move per
//! chunk. A large chunk is scanned in place, after staging just enough of it to decide the
//! pending bytes. No early-truncation search: a candidate waits for its declared length.

use super::Scan;

/// Bytes of the staging buffer.
pub const STAGE: usize = 2048;
/// Chunks shorter than this are appended; longer ones are scanned in place.
const SMALL: usize = 256;
/// Bytes kept free behind the staged run: a checksum window read from a candidate near the end
/// stays inside the buffer.
const SLACK: usize = 128;

/// A [`Scan`] fed in chunks through a 2 KiB buffer compacted only when full.
pub struct Appending<S: Scan> {
    buf: [u8; STAGE],
    /// The undecided bytes are `buf[start..end]`.
    start: usize,
    end: usize,
    scan: core::marker::PhantomData<S>,
}

impl<S: Scan> Default for Appending<S> {
    fn default() -> Self {
        Appending {
            buf: [0; STAGE],
            start: 0,
            end: 0,
            scan: core::marker::PhantomData,
        }
    }
}

impl<S: Scan> Appending<S> {
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
}

impl<S: Scan> crate::ChunkDecoder for Appending<S> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, mut chunk: &[u8], sink: &mut F) {
        if chunk.len() < SMALL {
            self.append(chunk);
            self.scan_staged(false, sink);
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
    }

    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        self.scan_staged(true, sink);
        self.start = 0;
        self.end = 0;
    }
}
