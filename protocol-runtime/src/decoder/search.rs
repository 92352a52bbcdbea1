//! The searches of the engine: where the next candidate starts ([`find_candidate`]), and
//! whether a complete valid frame starts inside a pending candidate ([`frame_inside`]: the
//! search that rejects a candidate as truncated early), with the byte filters they are built
//! from.
//!
//! This module owns how bytes are searched (memchr on hosts, byte loops on microcontrollers,
//! masked word compares in between) and nothing else: whether a candidate is a frame is
//! decided by the parent module's rules, what a search's answer costs (skipped bytes, a
//! rejection) by the scan and the steps of [`StreamDecoder`](super::StreamDecoder), and which
//! of a candidate's bytes are already known to start no frame is remembered there.

use super::{Probe, bytes_agree, probe_link};
use crate::layout::{FrameLayout, LayoutRef};

/// [`find_candidate`] for a link of one or several formats: the first offset where `data`
/// holds any format's sync, or a prefix of it that runs to the end of `data`.
///
/// With several formats, a byte loop that asks every format at each offset (a few formats,
/// each deciding on its first byte nearly always): the search stops at the first start, so a
/// stream costs each byte once whatever the formats' syncs.
#[inline(always)]
pub(super) fn find_link<L: LayoutRef>(link: &L, data: &[u8]) -> usize {
    let others = link.others();
    if others.is_empty() {
        return find_candidate(link.layout(), data);
    }
    find_any(link.layout(), others, data)
}

/// [`find_link`]'s search with several formats.
#[inline(never)]
fn find_any(first: &FrameLayout<'_>, others: &[FrameLayout<'_>], data: &[u8]) -> usize {
    (0..data.len())
        .find(|&at| {
            let rest = data.get(at..).unwrap_or_default();
            first.sync_matches(rest) || others.iter().any(|f| f.sync_matches(rest))
        })
        .unwrap_or(data.len())
}

/// Where the first candidate of `data` for `layout` starts: the first offset where `data` holds
/// the sync, or a prefix of it that runs to the end of `data`; `data.len()` if there is none.
///
/// A layout known at compile time has a constant [`FrameLayout::sync_set`]: the branch on it
/// folds away, and a single sync costs what it did before sync sets existed.
#[inline(always)]
pub(super) fn find_candidate(layout: &FrameLayout<'_>, data: &[u8]) -> usize {
    if layout.sync_set.is_empty() {
        find_sync(layout.sync, data)
    } else {
        find_sync_set(layout.sync_set, layout.sync, data)
    }
}

/// The first offset where `data` holds one of the bytes of `set` followed by `more` (or by a
/// prefix of it that runs to the end of `data`); `data.len()` if there is none.
///
/// A byte loop that tests each byte against the set: sets are a few bytes (CRSF's five device
/// addresses), and on a clean stream the next frame starts at the first byte.
#[inline(never)]
fn find_sync_set(set: &[u8], more: &[u8], data: &[u8]) -> usize {
    let mut from = 0;
    while let Some(hit) = data
        .get(from..)
        .and_then(|rest| rest.iter().position(|b| set.contains(b)))
    {
        let at = from.wrapping_add(hit);
        let after = data.get(at.wrapping_add(1)..).unwrap_or_default();
        if bytes_agree(after, more) {
            return at;
        }
        from = at.wrapping_add(1);
    }
    data.len()
}

/// [`find_candidate`] for a layout whose frames start with the bytes `sync`.
#[inline]
fn find_sync(sync: &[u8], data: &[u8]) -> usize {
    let Some((&first, more)) = sync.split_first() else {
        return 0;
    };
    let continues = |at: usize| {
        let after = data.get(at.wrapping_add(1)..).unwrap_or_default();
        bytes_agree(after, more)
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
/// Whole 64-byte blocks are compared byte by byte under a mask, with no branch per byte: the
/// compiler turns each block into a few vector compares and one test; a search that stops at
/// the first match mispredicts its exit once per call, at a length that changes every time.
/// Testing pairs rather than the first byte alone makes a `true` rare for two-byte syncs
/// (`FF FF`: a random payload byte is `FF` once in 256, a pair once in 65,536), so the branch
/// on it predicts well.
#[inline(always)]
fn may_start_sync(sync: &[u8], data: &[u8], n: usize) -> bool {
    let mut from = 0usize;
    while from < n {
        let rest = data.get(from..).unwrap_or_default();
        let left = n.wrapping_sub(from);
        // The block and, for the second byte, the byte after it.
        let Some(block) = rest.first_chunk::<{ SCAN + 1 }>() else {
            // The end of the buffer: fewer bytes left to read than a block.
            return may_start_sync_exact(sync, rest, left);
        };
        if block_may_start_sync(sync, block, left) {
            return true;
        }
        from = from.wrapping_add(SCAN);
    }
    false
}

/// [`may_start_sync`] byte by byte, where fewer than a block's bytes can be read.
#[inline(never)]
fn may_start_sync_exact(sync: &[u8], rest: &[u8], left: usize) -> bool {
    let (first, second) = match *sync {
        [] => return left > 0,
        [first] => (first, None),
        [first, second, ..] => (first, Some(second)),
    };
    (0..left).any(|i| {
        rest.get(i) == Some(&first)
            && second.is_none_or(|s| rest.get(i.wrapping_add(1)).is_none_or(|&b| b == s))
    })
}

/// [`may_start_sync`] on one block: whether one of its first `min(left, SCAN)` offsets holds
/// the sync's first byte followed by its second (the block's last byte is only read as the
/// byte after its 64th offset).
#[inline(always)]
fn block_may_start_sync(sync: &[u8], block: &[u8; SCAN + 1], left: usize) -> bool {
    let (first, second) = match *sync {
        [] => return left > 0,
        [first] => (first, None),
        [first, second, ..] => (first, Some(second)),
    };
    let (Some(here), Some(next)) = (block.first_chunk::<SCAN>(), block.last_chunk::<SCAN>()) else {
        return true;
    };
    let keep = SCAN_MASK
        .get(SCAN.saturating_sub(left)..)
        .and_then(<[u8]>::first_chunk::<SCAN>)
        .unwrap_or(&[0; SCAN]);
    // `&` on the comparisons, not `&&`: no branch, so that the loop vectorises. A loop over
    // indices, not an iterator adapter's `fold`: in a large caller (the benchmark binary) the
    // compiler calls `fold` out of line, where the sync bytes are no longer constants, and the
    // call, once per chunk, costs more than the test itself.
    let mut hits = 0u8;
    for i in 0..SCAN {
        let (Some(&b), Some(&c), Some(&k)) = (here.get(i), next.get(i), keep.get(i)) else {
            break;
        };
        let pair = (b == first) & second.is_none_or(|s| c == s);
        hits |= u8::from(pair) & k;
    }
    hits != 0
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

/// [`may_start_sync`] for `link`: with a sync set or several formats, always `true` (the exact
/// search then decides).
#[inline(always)]
fn may_start<L: LayoutRef>(link: &L, data: &[u8], n: usize) -> bool {
    let layout = link.layout();
    if layout.sync_set.is_empty() && link.others().is_empty() {
        may_start_sync(layout.sync, data, n)
    } else {
        n > 0
    }
}

/// [`may_start`] on one block of `data`, `n <= SCAN`.
#[inline(always)]
fn may_start_block<L: LayoutRef>(link: &L, block: &[u8; SCAN + 1], n: usize) -> bool {
    let layout = link.layout();
    if layout.sync_set.is_empty() && link.others().is_empty() {
        block_may_start_sync(layout.sync, block, n)
    } else {
        n > 0
    }
}

/// The first offset of `data` holding the first byte of `link`'s sync (any byte of its sync
/// set; of any format's), or `data.len()`.
#[inline(always)]
fn find_lead<L: LayoutRef>(link: &L, data: &[u8]) -> usize {
    let layout = link.layout();
    let others = link.others();
    if !others.is_empty() {
        return find_any(layout, others, data);
    }
    if layout.sync_set.is_empty() {
        find_first_byte(layout.sync, data)
    } else {
        data.iter()
            .position(|b| layout.sync_set.contains(b))
            .unwrap_or(data.len())
    }
}

/// The shortest frame of `link`: no candidate with fewer bytes after its start is decided.
#[inline(always)]
fn shortest_frame<L: LayoutRef>(link: &L) -> usize {
    let shortest = |f: &FrameLayout<'_>| f.min_len.max(f.header_span()).max(1);
    let first = shortest(link.layout());
    link.others().iter().fold(first, |m, f| m.min(shortest(f)))
}

/// Whether a complete valid frame starts after the first byte of the pending candidate
/// `readable[..pending]` (`readable` may run past it: whole blocks are read from there): then
/// the candidate's claimed length runs over it, and the candidate is taken for a truncated
/// frame rather than holding the valid one back until more bytes arrive.
///
/// `dead` is how many of the candidate's first bytes are known to start no frame (at least its
/// own first byte); the search starts after them and leaves there how many it now knows (a
/// rejection is final: more bytes do not change it), since it is asked again each time the
/// input runs out while the candidate waits.
///
/// Inlined where the input runs out: most calls end with the block test that finds no start of
/// the sync bytes among the candidate's bytes, without a call.
#[inline(always)]
pub(super) fn frame_inside<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    pending: usize,
    dead: &mut usize,
    limit: usize,
) -> bool {
    let known = (*dead).max(1);
    // Only a start with room for the shortest frame after it can hold a frame now.
    let Some(last_start) = pending.checked_sub(shortest_frame(layout)) else {
        return false;
    };
    if known > last_start {
        return false;
    }
    let window = last_start.wrapping_sub(known).wrapping_add(1);
    if cfg!(target_pointer_width = "64")
        && !match readable
            .get(known..known.wrapping_add(SCAN + 1))
            .and_then(<[u8]>::first_chunk::<{ SCAN + 1 }>)
        {
            // Nearly always: the bytes to test fit one block.
            Some(block) if window <= SCAN => may_start_block(layout, block, window),
            _ => may_start(layout, readable.get(known..).unwrap_or_default(), window),
        }
    {
        // None of these bytes starts a frame, now or later; the ones too close to the end may
        // once more bytes arrive.
        *dead = last_start.wrapping_add(1);
        return false;
    }
    search_inside(layout, readable, pending, dead, limit)
}

/// [`frame_inside`]'s exact search.
#[inline(never)]
fn search_inside<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    pending: usize,
    dead: &mut usize,
    limit: usize,
) -> bool {
    let shortest = shortest_frame(layout);
    let region = readable.get(..pending).unwrap_or_default();
    let mut at = (*dead).max(1);
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
        // (The masked block test only where words are 64 bits: on a microcontroller the plain
        // search is smaller and as fast.)
        let skip =
            if cfg!(not(target_pointer_width = "64")) || may_start(layout, readable_rest, window) {
                find_lead(layout, rest.get(..window).unwrap_or(rest))
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
        match probe_link(layout, from, region.len().wrapping_sub(at), limit).1 {
            Probe::Frame(_) => break true,
            Probe::Need(_) => {
                undecided.get_or_insert(at);
            }
            Probe::Reject(_) => {}
        }
        at = at.wrapping_add(1);
    };
    *dead = undecided.unwrap_or(at);
    found
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
