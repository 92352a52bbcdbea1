//! The scan: the loop that finds every frame of a run of contiguous bytes, wherever they live
//! (the decoder's buffer, where chunks are staged, or the caller's chunk, scanned in place).
//!
//! This module owns the fast path of [`StreamDecoder::feed`](super::StreamDecoder::feed): one
//! search and one decision per candidate, the counters kept in registers and added to the
//! [`Stats`] once. It does not own where the bytes come from nor what happens to a candidate
//! that needs more bytes than there are (the scan stops there, and the decoder's steps buffer
//! it or reject it), and it decides no candidate itself:
//! [`probe_synced`](super::probe_synced) does.

use super::event::{Frame, Stats};
use super::search::find_link;
use super::{Probe, probe_link_synced};
use crate::layout::LayoutRef;

/// Calls `sink` with every frame of `readable[..len]`, counts the rejected candidates and the
/// skipped runs in `stats`, and returns how many bytes are done with: `len`, or up to the start
/// of a candidate that needs more bytes than there are. The frame starting `at` bytes in lies at
/// stream offset `base + at` and borrows `readable`.
///
/// `readable` may run past `len` (the rest of the decoder's buffer): window checksums read whole
/// blocks from there; what lies past `len` decides nothing. Frames longer than `limit` are
/// rejected.
///
/// Per frame, only a count and the offset change: a frame's bytes are what the scan did not
/// skip, added once at the end. Skipped bytes (rare on a good link) go straight to the stats,
/// out of the loop's registers.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn scan<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    len: usize,
    base: u64,
    limit: usize,
    stats: &mut Stats,
    sink: &mut impl FnMut(Frame<'_>),
) -> usize {
    let skipped_before = stats.skipped_bytes;
    let (mut at, mut frames) = (0usize, 0u64);
    // `len <= readable.len()` (the callers' bounds): said here, so that the compiler drops the
    // fallbacks of `readable.get(at..)` from the loop.
    let len = len.min(readable.len());
    // One comparison per step (`at` never passes `len`: every step advances it by at most what
    // is left).
    while at < len {
        let avail = len.wrapping_sub(at);
        // (Never `None`: `at < len <= readable.len()`; a branch the compiler drops, where a
        // fallback value costs a conditional move per candidate.)
        let Some(from) = readable.get(at..) else {
            break;
        };
        let Some(span) = from.get(..avail) else {
            break;
        };
        let skip = find_link(layout, span);
        if skip > 0 {
            stats.skipped_bytes = stats.skipped_bytes.wrapping_add(skip as u64);
            at = at.wrapping_add(skip);
            continue;
        }
        // The search has just compared the sync bytes (as many as there are).
        match probe_link_synced(layout, from, avail, limit) {
            (format, Probe::Frame(len)) => {
                sink(Frame {
                    bytes: from.get(..len).unwrap_or(from),
                    offset: base.wrapping_add(at as u64),
                    format,
                });
                frames = frames.wrapping_add(1);
                at = at.wrapping_add(len);
            }
            (_, Probe::Reject(reason)) => {
                stats.count_reject(reason);
                at = at.wrapping_add(1);
            }
            (_, Probe::Need(_)) => break,
        }
    }
    stats.count_scan(frames, at, skipped_before);
    at
}
