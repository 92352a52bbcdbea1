//! Lower bounds, not decoders: frames found by walking the length fields alone, with no sync or
//! length test and no resynchronisation, so they are only correct on clean streams (frames back
//! to back from the first byte). [`LengthWalk`] checks nothing: what any decoder pays to find
//! the frames and hand each one over as one slice. [`CheckedWalk`] also verifies each frame's
//! checks with the runtime's code for them (the generated layout's `Check`s, the code the
//! engine runs): what any decoder that checks the frames with it pays at the least.
//!
//! Fed in chunks, it appends each chunk behind the bytes of the frame the previous chunk cut,
//! walks the whole, and moves the new cut frame to the front: the cheapest staging for small
//! chunks (keeping the cut frame aside and completing it from the next chunk makes the walk
//! 1.6x slower on 64-byte chunks). The move is a fixed-size copy (the bytes after the cut frame
//! go along, unused): a `copy_within` of the cut frame's own length, a call to `memmove`, makes
//! the chunked walk 1.3x slower. Its chunked time over its whole-stream time is what cutting the
//! input into chunks costs at the least.

use core::marker::PhantomData;

use protocol_kit::FrameLayout;
use protocol_kit::layout::LayoutRef;

use crate::ChunkDecoder;
use crate::generated::{hflink, referee};

/// What the walk knows of a protocol's frames: where the length is (the one field it reads) and
/// how to check a frame.
///
/// The lengths are read by hand, not through the generated layout's rule
/// (`FrameLayout::frame_len`, what the engine reads): a bound should be the cheapest walk, and
/// through the layout's general rule the walk that checks nothing measured 5-17% slower on whole
/// streams and 0-9% on 64-byte chunks (quick runs, HFLink and referee), the checked walk within
/// 5%. The checks are the layout's own.
pub trait Format {
    /// Bytes up to and including the length field.
    const HEADER: usize;
    /// The whole frame's length, from its first `HEADER` bytes.
    fn frame_len(header: &[u8]) -> usize;
    /// Whether the `len`-byte frame at the start of `readable` (which may run past it) passes
    /// the generated layout's header and frame checks.
    fn verify(readable: &[u8], len: usize) -> bool;
}

/// Every check of `layout` over the `len`-byte frame at the start of `readable`.
#[inline(always)]
fn checks_hold(layout: &FrameLayout<'_>, readable: &[u8], len: usize) -> bool {
    let span = layout.header_span();
    // Loops, not `all` with a closure: as in the engine.
    for check in layout.header_checks {
        if !check.verify_prefix(readable, span) {
            return false;
        }
    }
    for check in layout.frame_checks {
        if !check.verify_prefix(readable, len) {
            return false;
        }
    }
    true
}

/// HFLink: `FF FF sender receiver length(u16 BE)`, then `length` bytes and the sum.
pub struct HfLinkFormat;

impl Format for HfLinkFormat {
    const HEADER: usize = 6;
    #[inline(always)]
    fn frame_len(header: &[u8]) -> usize {
        7 + usize::from(u16::from_be_bytes([header[4], header[5]]))
    }
    #[inline(always)]
    fn verify(readable: &[u8], len: usize) -> bool {
        checks_hold(hflink::Layout.layout(), readable, len)
    }
}

/// Referee: `A5 length(u16 LE)`, then sequence, CRC-8, command, `length` bytes and CRC-16.
pub struct RefereeFormat;

impl Format for RefereeFormat {
    const HEADER: usize = 3;
    #[inline(always)]
    fn frame_len(header: &[u8]) -> usize {
        9 + usize::from(u16::from_le_bytes([header[1], header[2]]))
    }
    #[inline(always)]
    fn verify(readable: &[u8], len: usize) -> bool {
        checks_hold(referee::Layout.layout(), readable, len)
    }
}

/// Bytes moved at once to the front: more than a frame of the benchmark's clean streams.
const MOVE: usize = 128;

/// Calls `sink` with every whole frame of `data[..avail]` (that passes its checks, with
/// `CHECKS`) and returns the bytes they cover. Checks may read past `avail` (window checksums,
/// as in the engine), which decides nothing.
#[inline(always)]
fn walk<L: Format, const CHECKS: bool, F: FnMut(&[u8])>(
    data: &[u8],
    avail: usize,
    sink: &mut F,
) -> usize {
    let bytes = &data[..avail];
    let mut at = 0;
    while let Some(header) = bytes.get(at..at + L::HEADER) {
        let len = L::frame_len(header);
        let Some(frame) = bytes.get(at..at + len) else {
            break;
        };
        if !CHECKS || L::verify(&data[at..], len) {
            sink(frame);
        }
        at += len;
    }
    at
}

/// The walk, checking nothing.
pub type LengthWalk<L> = Walk<L, false>;
/// The walk, verifying every frame's checks.
pub type CheckedWalk<L> = Walk<L, true>;

/// The walk, fed in chunks.
pub struct Walk<L: Format, const CHECKS: bool> {
    /// The cut frame's bytes are `buf[..len]`.
    buf: Vec<u8>,
    len: usize,
    format: PhantomData<L>,
}

impl<L: Format, const CHECKS: bool> Default for Walk<L, CHECKS> {
    fn default() -> Self {
        Walk {
            buf: vec![0; 4096],
            len: 0,
            format: PhantomData,
        }
    }
}

impl<L: Format, const CHECKS: bool> ChunkDecoder for Walk<L, CHECKS> {
    #[inline]
    fn feed<F: FnMut(&[u8])>(&mut self, chunk: &[u8], sink: &mut F) {
        if self.len == 0 {
            let done = walk::<L, CHECKS, F>(chunk, chunk.len(), sink);
            let tail = &chunk[done..];
            if self.buf.len() < tail.len() + MOVE {
                self.buf.resize(tail.len() + MOVE, 0);
            }
            self.buf[..tail.len()].copy_from_slice(tail);
            self.len = tail.len();
            return;
        }
        let end = self.len + chunk.len();
        if self.buf.len() < end + MOVE {
            self.buf.resize(end + MOVE, 0);
        }
        self.buf[self.len..end].copy_from_slice(chunk);
        // The stale bytes after `end` are in reach of window checksums and decide nothing.
        let done = walk::<L, CHECKS, F>(&self.buf, end, sink);
        let left = end - done;
        if left <= MOVE {
            self.buf.copy_within(done..done + MOVE, 0);
        } else {
            self.buf.copy_within(done..end, 0);
        }
        self.len = left;
    }

    fn finish<F: FnMut(&[u8])>(&mut self, _: &mut F) {
        self.len = 0;
    }
}
