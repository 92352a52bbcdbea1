//! The decoder's buffer: the bytes of a candidate cut by the end of a chunk, the chunks staged
//! behind them, and the bytes taken off the caller's input.
//!
//! This module owns how bytes enter and leave `buf[start..end]` of a [`StreamDecoder`]: copying
//! (whole chunks, with the block test's filler behind them on hosts; a candidate's missing
//! bytes), compaction (the pending bytes move to the front when what comes would not fit behind
//! them), and the count of bytes taken from the input ([`StreamDecoder::position`]). It does
//! not decide what is pending: the scan and the steps do, by moving `start`.

use super::Stats;
use super::StreamDecoder;
use super::search::{FILL, filler};
use super::target::{EARLY_TRUNCATION, HOST};
use crate::layout::{FrameLayout, LayoutRef, LengthRule};

/// Takes the first `len` bytes off `input` (all of it if shorter).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn take<'i>(input: &mut &'i [u8], len: usize) -> &'i [u8] {
    let data: &'i [u8] = input;
    let (head, rest) = data.split_at_checked(len).unwrap_or((data, &[]));
    *input = rest;
    head
}

/// Bytes kept free behind staged input on hosts: a window checksum reads a fixed-size block
/// from a candidate's start (up to 128 bytes), which then stays inside the buffer instead of
/// falling back to an exact loop; the first [`FILL`] of them take the filler of the block test.
/// None elsewhere: no window checksums there, nor a block test.
const STAGE_SLACK: usize = if HOST { 128 } else { 0 };

// The filler behind staged input fits in the room kept free there.
const _: () = assert!(!HOST || STAGE_SLACK >= FILL);

/// The smallest buffer of a generated decoder on a host (a target with 64-bit pointers), in
/// bytes: chunks are appended behind the pending bytes until it is full, and only then do those
/// move to its front.
pub const HOST_BUFFER_LEN: usize = 2048;

/// Bytes of the buffer of a decoder of frames of at most `max_frame` bytes, as generated code
/// sizes it (`DECODER_BUFFER_LEN`): the decoder's RAM but for its state
/// ([`decoder_state_len`]); [`decoder_buffer_len_for`] on the target this is built for.
pub const fn decoder_buffer_len(max_frame: usize) -> usize {
    decoder_buffer_len_for(max_frame, HOST)
}

/// Bytes of the buffer of a decoder of frames of at most `max_frame` bytes on a host (a target
/// with 64-bit pointers, `host`) or elsewhere: what [`decoder_buffer_len`] gives on either, so
/// that a tool on a host can state what a microcontroller's decoder takes. `usize::MAX` when
/// the size does not fit a `usize`.
///
/// On targets without 64-bit pointers (microcontrollers), what the engine needs and no more:
/// the frame, as much again (at least 64 bytes) for a chunk staged behind a pending frame (the
/// engine stages a chunk only if it fits, and otherwise completes the frame from the input),
/// and 128 bytes for a checksum window, rounded up to a multiple of 64: 384 bytes for frames of
/// up to 127 bytes. On hosts at least [`HOST_BUFFER_LEN`]: in a small buffer, small chunks
/// fill the room behind a pending frame within a few chunks, and moving the pending bytes to
/// the front (a copy of varying length, at irregular intervals) costs mispredicted branches
/// that a larger buffer pays once every few dozen chunks (`BENCHMARKS.md` measures both).
///
/// ```
/// use protocol_runtime::decoder::decoder_buffer_len_for;
///
/// assert_eq!(decoder_buffer_len_for(127, false), 384);
/// assert_eq!(decoder_buffer_len_for(127, true), 2048);
/// assert_eq!(decoder_buffer_len_for(usize::MAX / 2, false), usize::MAX);
/// ```
pub const fn decoder_buffer_len_for(max_frame: usize, host: bool) -> usize {
    let frame_and_chunk = if max_frame > 64 {
        max_frame.saturating_mul(2)
    } else {
        max_frame.saturating_add(64)
    };
    let small = match frame_and_chunk
        .saturating_add(128)
        .checked_next_multiple_of(64)
    {
        Some(rounded) => rounded,
        None => usize::MAX,
    };
    if host && small < HOST_BUFFER_LEN {
        HOST_BUFFER_LEN
    } else {
        small
    }
}

/// The RAM of a generated decoder, in bytes: its buffer and the rest of it (positions,
/// counters, padding), the two summing to its `size_of`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecoderRam {
    /// The buffer: [`decoder_buffer_len`] on that target.
    pub buffer: usize,
    /// Everything else: the decoder's state.
    pub state: usize,
}

/// The RAM a generated decoder of frames of at most `max_frame` bytes takes on a target whose
/// pointers have `pointer_bytes` bytes (4 on a microcontroller such as thumbv7em, 8 on a
/// 64-bit host) and whose `u64` is 8-aligned (both of those): the [`StreamDecoder`] with a
/// generated layout type (zero-sized), laid out as its `repr(C)` declares, so that generated
/// docs can state a microcontroller's figure from a build on a host.
///
/// ```
/// use protocol_runtime::decoder::{StreamDecoder, decoder_buffer_len, decoder_ram};
/// use protocol_runtime::layout::LengthRule;
/// use protocol_runtime::{FrameLayout, LayoutRef};
///
/// static FIXED: FrameLayout<'static> = FrameLayout {
///     sync: &[0xAA], sync_set: &[], header_len: 1, min_len: 4, max_len: 4, length: LengthRule::Fixed(4),
///     constants: &[], header_checks: &[], frame_checks: &[], markers: &[], escape: None,
/// };
/// // A generated layout type: zero-sized.
/// #[derive(Clone, Copy)]
/// struct Fixed;
/// impl LayoutRef for Fixed {
///     fn layout(&self) -> &FrameLayout<'_> {
///         &FIXED
///     }
/// }
/// for max_frame in [4, 127, 1024] {
///     assert_eq!(decoder_ram(max_frame, size_of::<usize>()).buffer, decoder_buffer_len(max_frame));
/// }
/// const N: usize = decoder_buffer_len(127);
/// let ram = decoder_ram(127, size_of::<usize>());
/// assert_eq!(ram.buffer + ram.state, size_of::<StreamDecoder<Fixed, N>>());
/// const M: usize = decoder_buffer_len(1024);
/// let ram = decoder_ram(1024, size_of::<usize>());
/// assert_eq!(ram.buffer + ram.state, size_of::<StreamDecoder<Fixed, M>>());
/// ```
pub const fn decoder_ram(max_frame: usize, pointer_bytes: usize) -> DecoderRam {
    DecoderRam {
        buffer: decoder_buffer_len_for(max_frame, pointer_bytes >= 8),
        state: decoder_state_len(pointer_bytes),
    }
}

/// Bytes of a [`StreamDecoder`] besides its buffer, with a generated layout type (which takes
/// none), on a target with `pointer_bytes`-byte pointers: three indices into the buffer, the
/// stream position, the start of the last candidate a frame was found inside, and the counts
/// of [`Stats`], padded to a `u64`'s alignment. 112 bytes on x86-64 and AArch64 (8-byte
/// pointers), 104 on Arm Cortex-M (4-byte pointers, 8-byte-aligned `u64`).
///
/// ```
/// use protocol_runtime::decoder::decoder_state_len;
///
/// assert_eq!(decoder_state_len(8), 112);
/// assert_eq!(decoder_state_len(4), 104);
/// ```
pub const fn decoder_state_len(pointer_bytes: usize) -> usize {
    let fields = pointer_bytes
        .saturating_mul(3)
        .saturating_add(size_of::<u64>().saturating_mul(2))
        .saturating_add(size_of::<Stats>());
    fields.next_multiple_of(align_of::<u64>())
}

/// A layout type of no bytes, as generated code's, so that the size of a decoder of it is the
/// size of its state.
#[derive(Clone, Copy)]
struct NoBytes;

static NO_LAYOUT: FrameLayout<'static> = FrameLayout {
    sync: &[],
    sync_set: &[],
    header_len: 0,
    min_len: 0,
    max_len: 0,
    length: LengthRule::Fixed(0),
    constants: &[],
    header_checks: &[],
    frame_checks: &[],
    markers: &[],
    escape: None,
};

impl LayoutRef for NoBytes {
    fn layout(&self) -> &FrameLayout<'_> {
        &NO_LAYOUT
    }
}

// What `decoder_state_len` states is what a decoder takes, on every target this is built for.
const _: () =
    assert!(decoder_state_len(size_of::<usize>()) == size_of::<StreamDecoder<NoBytes, 0>>());

/// `dst.copy_from_slice(src)` (`dst` and `src` of one length), inline for the chunks of a
/// serial link on hosts: 16 to 64 bytes as two fixed-size moves that overlap in the middle
/// (a few vector loads and stores), where `copy_from_slice` calls the C library's `memcpy`,
/// whose call and length dispatch cost more than the copy. Other lengths, and every length
/// on targets without 64-bit pointers (where the moves cost flash), as `copy_from_slice`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn copy_chunk(dst: &mut [u8], src: &[u8]) {
    if HOST && dst.len() == src.len() {
        if (32..=64).contains(&src.len()) && overlapping::<32>(dst, src) {
            return;
        }
        if (16..32).contains(&src.len()) && overlapping::<16>(dst, src) {
            return;
        }
    }
    dst.copy_from_slice(src);
}

/// Copies the first and the last `K` bytes of `src` to `dst`: all of it if `K <= len <= 2K`.
/// `false`, copying nothing, if either holds fewer than `K` bytes.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn overlapping<const K: usize>(dst: &mut [u8], src: &[u8]) -> bool {
    let (Some(head), Some(tail)) = (src.first_chunk::<K>(), src.last_chunk::<K>()) else {
        return false;
    };
    let Some(to) = dst.first_chunk_mut::<K>() else {
        return false;
    };
    *to = *head;
    let Some(to) = dst.last_chunk_mut::<K>() else {
        return false;
    };
    *to = *tail;
    true
}

impl<L: LayoutRef, const N: usize> StreamDecoder<L, N> {
    /// Keeps the whole input, with nothing pending, as the pending bytes (the start of a
    /// candidate that needs more). Returns `false`, copying nothing, if it does not fit.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn hold(&mut self, input: &mut &[u8]) -> bool {
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

    /// Advances `input` by `n` bytes (at most its length) and returns the bytes skipped.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn consume<'i>(&mut self, input: &mut &'i [u8], n: usize) -> &'i [u8] {
        let data: &'i [u8] = input;
        let (head, rest) = data.split_at_checked(n).unwrap_or((data, &[]));
        *input = rest;
        self.position = self.position.wrapping_add(head.len() as u64);
        head
    }

    /// Appends the whole input behind the pending bytes if it fits the buffer with room for
    /// a checksum window after it (moving the pending bytes to the front first if needed).
    /// Returns `false`, copying nothing, otherwise. On hosts, writes [`FILL`] bytes of
    /// [`filler`] behind it, inside that room: the block test that follows reads whole blocks
    /// there, unmasked.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn stage(&mut self, input: &mut &[u8]) -> bool {
        let data: &[u8] = input;
        let room = N.saturating_sub(STAGE_SLACK);
        // Behind the pending bytes where they are (two comparisons, the common case), else
        // behind them moved to the front, if they leave room.
        if self.end > room || data.len() > room.wrapping_sub(self.end) {
            if self.buffered().saturating_add(data.len()) > room {
                return false;
            }
            self.buf.copy_within(self.start..self.end, 0);
            self.end = self.end.wrapping_sub(self.start);
            self.start = 0;
        }
        let end = self.end.wrapping_add(data.len());
        let Some(dst) = self.buf.get_mut(self.end..end) else {
            return false;
        };
        copy_chunk(dst, data);
        // (Part of the early-truncation rule: not written where the rule is ablated.)
        if HOST && EARLY_TRUNCATION {
            let byte = filler(&self.layout, self.limit());
            // Inside the room kept free: `STAGE_SLACK >= FILL`.
            if let Some(behind) = self
                .buf
                .get_mut(end..)
                .and_then(<[u8]>::first_chunk_mut::<FILL>)
            {
                *behind = [byte; FILL];
            }
        }
        self.end = end;
        self.position = self.position.wrapping_add(data.len() as u64);
        *input = &[];
        true
    }

    /// With nothing pending, copies the start of the input into the buffer: all of it if it
    /// fits with room for a checksum window after it, else as much as fits (at least a byte).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn stage_prefix(&mut self, input: &mut &[u8]) {
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
    pub(super) fn fill(&mut self, input: &mut &[u8], needed: usize) -> bool {
        if needed > N {
            return false;
        }
        if self.start.saturating_add(needed) > N && self.buf.get(self.start..self.end).is_some() {
            self.buf.copy_within(self.start..self.end, 0);
            self.end = self.end.wrapping_sub(self.start);
            self.start = 0;
        }
        let want = needed.saturating_sub(self.buffered()).min(input.len());
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
    #![allow(clippy::indexing_slicing, clippy::cast_possible_truncation)]

    use super::copy_chunk;

    /// Every length, at every offset of a larger buffer: the bytes copied are the source's, and
    /// not one byte around them changes.
    #[test]
    fn copy_chunk_copies_exactly_its_bytes() {
        let src: [u8; 96] = core::array::from_fn(|i| (i as u8).wrapping_mul(37).wrapping_add(1));
        for len in 0..=src.len() {
            for at in 0..8 {
                let mut dst = [0xEEu8; 112];
                copy_chunk(&mut dst[at..at + len], &src[..len]);
                assert_eq!(&dst[at..at + len], &src[..len], "len {len} at {at}");
                assert!(dst[..at].iter().all(|&b| b == 0xEE), "len {len} at {at}");
                assert!(
                    dst[at + len..].iter().all(|&b| b == 0xEE),
                    "len {len} at {at}"
                );
            }
        }
    }
}
