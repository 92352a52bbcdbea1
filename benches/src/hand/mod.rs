//! Hand-written, optimized codecs, written for the benchmark as a skilled engineer would write
//! them for one protocol: the baseline the generated code is measured against.
//!
//! Decoding is a slice scan ([`Scan`]): find the sync with memchr, reject an impossible length
//! at once, verify the check over the frame in place, hand the frame to the sink without copying
//! it, resume one byte after a rejected start. Chunked input goes through [`Staged`], which
//! copies small chunks behind the pending bytes and scans contiguously (cheaper than completing
//! a partial frame aside: see [`crate::floor`]); [`appending`] is the faster feed of the best
//! baseline known (a 2 KiB buffer compacted only when full), also with the framework's
//! early-truncation rule ([`appending::Early`]). [`hflink`] and [`referee`] hold
//! the protocol-specific parts and the encoders; [`crc`] the table-driven CRCs, [`clmul`] the
//! CRC-16 folded with carry-less multiplication.

pub mod appending;
#[cfg(target_arch = "x86_64")]
pub mod clmul;
pub mod crc;
pub mod hflink;
pub mod referee;

use crate::ChunkDecoder;

/// A protocol's frame scan over contiguous bytes.
pub trait Scan {
    /// The longest frame: a candidate with this many bytes after its start is always decided.
    const MAX_FRAME: usize;

    /// The shortest frame: a complete frame inside a waiting candidate starts at least this
    /// many bytes before the candidate's last byte ([`appending::Early`]).
    const SHORTEST: usize;

    /// What the first bytes of every frame hold ([`appending::Early`]'s test).
    const LEAD: Lead;

    /// Calls `sink` with every frame of `data[..len]` and returns how many bytes are done with:
    /// all of them, or up to the start of a candidate that needs more bytes to be decided. With
    /// `at_end`, no more bytes will come: such a candidate is rejected instead.
    ///
    /// `data` may run past `len` (the rest of a staging buffer): checks read whole windows from
    /// there instead of falling back to byte loops near the end of the input; what lies past
    /// `len` never decides anything.
    fn scan<F: FnMut(&[u8])>(data: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize;
}

/// What the first bytes of every frame of a protocol hold: `first`, and `reach` bytes on a byte
/// whose bits under `mask` are `value`. A cheap filter for where a frame may start.
#[derive(Clone, Copy)]
pub struct Lead {
    /// The first byte.
    pub first: u8,
    /// How far after the first byte the second byte tested lies.
    pub reach: usize,
    /// The bits of that byte that are known.
    pub mask: u8,
    /// Their value.
    pub value: u8,
}

/// Bytes the staging buffer holds: pending bytes (less than a frame) and one chunk appended
/// behind them, or the first `S::MAX_FRAME + 1` bytes of a larger chunk.
const STAGE: usize = 512;

/// A [`Scan`] fed in chunks of any size.
///
/// With nothing pending, a chunk is scanned in place (zero copy) and its undecided tail (less
/// than a frame) is kept. With bytes pending, a small chunk is appended to them and the whole
/// is scanned; of a large chunk only enough bytes are appended to decide every pending
/// candidate, then the scan goes on in the chunk itself.
pub struct Staged<S: Scan> {
    buf: [u8; STAGE],
    len: usize,
    scan: core::marker::PhantomData<S>,
}

impl<S: Scan> Default for Staged<S> {
    fn default() -> Self {
        Staged {
            buf: [0; STAGE],
            len: 0,
            scan: core::marker::PhantomData,
        }
    }
}

impl<S: Scan> Staged<S> {
    /// Keeps `tail` (shorter than a frame) as the pending bytes.
    #[inline]
    fn keep(&mut self, tail: &[u8]) {
        self.buf[..tail.len()].copy_from_slice(tail);
        self.len = tail.len();
    }
}

impl<S: Scan> ChunkDecoder for Staged<S> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, mut chunk: &[u8], sink: &mut F) {
        while self.len > 0 {
            let old = self.len;
            let room = STAGE - old;
            // A small chunk goes in whole; of a large one, `MAX_FRAME + 1` bytes decide every
            // pending candidate (the pending bytes are shorter than a frame).
            let whole = chunk.len() <= room;
            let take = if whole {
                chunk.len()
            } else {
                room.min(S::MAX_FRAME + 1)
            };
            self.buf[old..old + take].copy_from_slice(&chunk[..take]);
            self.len = old + take;
            let done = S::scan(&self.buf, self.len, false, sink);
            if !whole && done >= old {
                // Every pending byte is decided: go on in the chunk, where the scan stopped.
                chunk = &chunk[done - old..];
                self.len = 0;
                break;
            }
            self.buf.copy_within(done..self.len, 0);
            self.len -= done;
            chunk = &chunk[take..];
            if chunk.is_empty() {
                return;
            }
        }
        let done = S::scan(chunk, chunk.len(), false, sink);
        self.keep(&chunk[done..]);
    }

    fn finish<F: FnMut(&[u8])>(&mut self, sink: &mut F) {
        let done = S::scan(&self.buf, self.len, true, sink);
        debug_assert_eq!(done, self.len);
        self.len = 0;
    }
}
