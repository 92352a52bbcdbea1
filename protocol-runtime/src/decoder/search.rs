//! The searches of the engine: where the next candidate starts ([`find_candidate`]), and
//! whether a complete valid frame starts inside a pending candidate ([`frame_inside`]: the
//! search that rejects a candidate as truncated early, behind the block test of hosts,
//! [`frame_may_be_inside`]), with the byte filters they are built from.
//!
//! This module owns how bytes are searched (memchr on hosts, byte loops on microcontrollers,
//! masked word compares in between) and nothing else: whether a candidate is a frame is
//! decided by the parent module's rules, what a search's answer costs (skipped bytes, a
//! rejection) by the scan and the steps of [`StreamDecoder`](super::StreamDecoder), and which
//! of a candidate's bytes are already known to start no frame is remembered there.

use super::target::HOST;
use super::{Probe, bytes_agree, probe_link};
use crate::layout::{ByteOrder, FrameLayout, LayoutRef, LengthRule, Pos};

/// [`find_candidate`] for a link of one or several formats: the first offset where `data`
/// holds any format's sync, or a prefix of it that runs to the end of `data`.
///
/// With several formats, a byte loop that asks every format at each offset (a few formats,
/// each deciding on its first byte nearly always): the search stops at the first start, so a
/// stream costs each byte once whatever the formats' syncs.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn find_link<L: LayoutRef>(link: &L, data: &[u8]) -> usize {
    let others = link.others();
    if !L::SEVERAL_FORMATS || others.is_empty() {
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
#[cfg_attr(not(protocol_opt0), inline(always))]
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
    if HOST {
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

/// The first offset of `byte` in `data`: `memchr` (vector compares) on hosts; elsewhere
/// (microcontrollers) a plain loop, where `memchr`'s word-at-a-time code costs more flash than
/// it saves time on a UART's chunks.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn find_byte(byte: u8, data: &[u8]) -> Option<usize> {
    if HOST {
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
#[cfg_attr(not(protocol_opt0), inline(always))]
const fn zero_byte_flags(x: u64) -> u64 {
    x.wrapping_sub(LOW) & !x & HIGH
}

/// Bytes [`block_may_start`] compares at once.
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

/// What the block test asks of an offset: that it holds the sync's first byte, and that the
/// byte `reach` bytes on has the bits `mask` equal to `value`: the sync's second byte (`reach`
/// 1, every bit), or else bits of the length field that no frame short enough to be accepted
/// sets (the referee's `A5` is followed by a 16-bit length of at most 118: its high byte, two
/// bytes on, is 0). Both hold at the start of every frame the probe can accept, so a `false`
/// is never wrong; the second makes a `true` rare (a random byte is `A5` once in 256, a pair
/// once in 65,536), so the branch on it predicts well and the exact search is seldom run.
///
/// Derived from the layout where it is used: for a layout known at compile time a constant,
/// which the compiler folds into the compares.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Lead {
    first: u8,
    reach: usize,
    mask: u8,
    value: u8,
}

impl Lead {
    /// The test for `layout`'s frames of at most `limit` bytes; `None` if its sync is empty
    /// (every offset may start a frame).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn of(layout: &FrameLayout<'_>, limit: usize) -> Option<Self> {
        let (&first, more) = layout.sync.split_first()?;
        let (reach, mask, value) = match *more {
            [second, ..] => (1, 0xFF, second),
            [] => length_zero_bits(layout, limit).map_or((0, 0, 0), |(at, mask)| (at, mask, 0)),
        };
        Some(Self {
            first,
            reach,
            mask,
            value,
        })
    }

    /// A byte that is not `first` and, unless every byte does, fails the second byte's test:
    /// behind the staged input, the offsets of [`frame_may_be_inside`]'s unmasked blocks past
    /// the pending bytes fail on it, and so do those whose second byte is in it.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn filler(self) -> u8 {
        // `!first` is not `first`; if it passes the second byte's test, flipping the lowest
        // bit that test reads fails it, and leaves a byte that is still not `first` (which
        // differs from `!first` in all eight bits, not one).
        let byte = !self.first;
        if byte & self.mask == self.value {
            byte ^ (self.mask & self.mask.wrapping_neg())
        } else {
            byte
        }
    }

    /// Whether offset `i` of `data` passes: a byte `reach` on that `data` does not hold passes.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn passes(self, data: &[u8], i: usize) -> bool {
        data.get(i) == Some(&self.first)
            && data
                .get(i.wrapping_add(self.reach))
                .is_none_or(|&b| b & self.mask == self.value)
    }
}

/// The header byte holding the most bits of the length field that are 0 in every frame of at
/// most `limit` bytes, as its offset and those bits; `None` if there is none (no length field
/// at a fixed offset, or every value of it fits). A length rule with parts that header values
/// decide (a marker value announcing a wider length) is left alone.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn length_zero_bits(layout: &FrameLayout<'_>, limit: usize) -> Option<(usize, u8)> {
    let (LengthRule::Field { field, adjust } | LengthRule::FieldOrBare { field, adjust, .. }) =
        layout.length
    else {
        return None;
    };
    let Pos::Start(at) = field.at else {
        return None;
    };
    // The field is read from the header: a byte of it is at most `shortest_frame - 1` bytes on
    // from the start, so the test never reads past the pending bytes (nor changes its answer
    // when more arrive).
    if !field.is_valid() || at.saturating_add(usize::from(field.size)) > layout.header_span() {
        return None;
    }
    // The largest value of the field whose frame fits: total = value + adjust <= limit.
    let largest = i64::try_from(limit).ok()?.checked_sub(adjust)?;
    let largest = u64::try_from(largest).ok()?;
    // The value's bits above the highest one `largest` sets, then as bits of the word.
    let fits = u64::MAX.checked_shr(largest.leading_zeros()).unwrap_or(0);
    let zero = (field.max_value() & !fits).checked_shl(u32::from(field.shift))?;
    // The bits form one run, up to the word's highest forced bit: the byte holding that bit
    // or the one below it (whole, when the run spans it) holds the most of them. No loop: the
    // run-time codec's layout, read through a reference, computes this once per chunk.
    let top = 63u32.checked_sub(zero.leading_zeros())?;
    let byte = |significance: u32| {
        let bits = zero.checked_shr(significance.wrapping_mul(8)).unwrap_or(0) & 0xFF;
        u8::try_from(bits).unwrap_or(0)
    };
    let high = top / 8;
    let below = high.saturating_sub(1);
    let significance = if byte(below).count_ones() > byte(high).count_ones() {
        below
    } else {
        high
    };
    // Where that byte is on the wire.
    let last = u32::from(field.size).wrapping_sub(1);
    let k = match field.order {
        ByteOrder::Little => significance,
        ByteOrder::Big => last.wrapping_sub(significance),
    };
    Some((at.wrapping_add(k as usize), byte(significance)))
}

/// Whether some offset of `data[..n]` may start a frame: passes `lead` (any offset, without
/// one). The question asked of a pending candidate every time the input runs out, whose answer
/// is nearly always no. A `true` may be wrong (the caller searches exactly then), a `false`
/// never is.
///
/// Whole 64-byte blocks are compared byte by byte under a mask, with no branch per byte: the
/// compiler turns each block into a few vector compares and one test; a search that stops at
/// the first match mispredicts its exit once per call, at a length that changes every time.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn may_start_lead(lead: Option<Lead>, data: &[u8], n: usize) -> bool {
    let Some(lead) = lead else {
        return n > 0;
    };
    let mut from = 0usize;
    while from < n {
        let rest = data.get(from..).unwrap_or_default();
        let left = n.wrapping_sub(from);
        if let Some(hit) = block_may_start(lead, rest, left) {
            if hit {
                return true;
            }
        } else {
            // The end of the buffer: fewer bytes left to read than a block and its reach.
            return may_start_exact(lead.first, lead.reach, lead.mask, lead.value, rest, left);
        }
        from = from.wrapping_add(SCAN);
    }
    false
}

/// [`may_start_lead`] byte by byte, where fewer than a block's bytes can be read. (The lead's
/// parts as arguments: in registers, where a struct would be stored for the call every time.)
#[inline(never)]
fn may_start_exact(first: u8, reach: usize, mask: u8, value: u8, rest: &[u8], left: usize) -> bool {
    let lead = Lead {
        first,
        reach,
        mask,
        value,
    };
    (0..left).any(|i| lead.passes(rest, i))
}

/// [`may_start_lead`] on one block: whether one of the first `min(left, SCAN)` offsets of
/// `data` passes `lead`; `None` if `data` holds fewer than a block and its reach.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn block_may_start(lead: Lead, data: &[u8], left: usize) -> Option<bool> {
    // One bounds check: with the lead's reach a constant, the two chunks of the block are known
    // to fit.
    let block = data.get(..SCAN.wrapping_add(lead.reach))?;
    let (here, next) = (block.first_chunk::<SCAN>()?, block.last_chunk::<SCAN>()?);
    let keep = SCAN_MASK
        .get(SCAN.saturating_sub(left)..)
        .and_then(<[u8]>::first_chunk::<SCAN>)
        .unwrap_or(&[0; SCAN]);
    // `&` on the comparisons, not `&&`: no branch, so that the loop vectorises. A loop over
    // indices, not an iterator adapter's `fold`: in a large caller (the benchmark binary) the
    // compiler calls `fold` out of line, where the lead's bytes are no longer constants, and
    // the call, once per chunk, costs more than the test itself.
    let mut hits = 0u8;
    for i in 0..SCAN {
        let (Some(&b), Some(&c), Some(&k)) = (here.get(i), next.get(i), keep.get(i)) else {
            break;
        };
        let pair = (b == lead.first) & (c & lead.mask == lead.value);
        hits |= u8::from(pair) & k;
    }
    Some(hits != 0)
}

/// The first offset of `data` holding `sync`'s first byte, or `data.len()`: the search inside
/// a pending candidate, a few dozen bytes. Eight bytes per step (a zero-byte test on a word
/// xored with the byte repeated); a call to `memchr` costs more on so few bytes.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn find_first_byte(sync: &[u8], data: &[u8]) -> usize {
    let Some(&first) = sync.first() else {
        return 0;
    };
    if !HOST {
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

/// [`may_start_lead`] for `link`'s frames of at most `limit` bytes: with a sync set or several
/// formats, always `true` (the exact search then decides).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn may_start<L: LayoutRef>(link: &L, data: &[u8], n: usize, limit: usize) -> bool {
    let layout = link.layout();
    if layout.sync_set.is_empty() && link.others().is_empty() {
        may_start_lead(Lead::of(layout, limit), data, n)
    } else {
        n > 0
    }
}

/// [`may_start`] on the first block of `data`, `n <= SCAN`; `None` if `data` holds fewer than a
/// block and its reach.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn may_start_block<L: LayoutRef>(link: &L, data: &[u8], n: usize, limit: usize) -> Option<bool> {
    let layout = link.layout();
    if layout.sync_set.is_empty() && link.others().is_empty() {
        match Lead::of(layout, limit) {
            Some(lead) => block_may_start(lead, data, n),
            None => Some(n > 0),
        }
    } else {
        Some(n > 0)
    }
}

/// The first offset of `data` holding the first byte of `link`'s sync (any byte of its sync
/// set; of any format's), or `data.len()`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn find_lead<L: LayoutRef>(link: &L, data: &[u8]) -> usize {
    let layout = link.layout();
    let others = link.others();
    if L::SEVERAL_FORMATS && !others.is_empty() {
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
#[cfg_attr(not(protocol_opt0), inline(always))]
fn shortest_frame<L: LayoutRef>(link: &L) -> usize {
    let shortest = |f: &FrameLayout<'_>| f.min_len.max(f.header_span()).max(1);
    let first = shortest(link.layout());
    link.others().iter().fold(first, |m, f| m.min(shortest(f)))
}

/// Whether a frame may start at one of the offsets of the pending candidate
/// `readable[..pending]` that could hold a complete one now: after its first byte, with room
/// for the shortest frame. The block test of hosts, asked every time the input runs out while a
/// candidate waits: nearly always `false`, and a `false` is never wrong ([`frame_inside`] then
/// finds nothing); a `true` may be (the exact search decides).
///
/// From the candidate's second byte every time, with nothing remembered between calls: one
/// block for up to 64 offsets (a candidate cut by a small chunk), a block per 64 more; keeping
/// what earlier calls learnt costs a branch on whether the candidate is the one of the last
/// call, which follows the frame lengths and is mispredicted often.
///
/// `filled`: the [`FILL`] bytes behind the pending ones hold [`filler`] (the input was just
/// staged). Then up to two whole blocks are compared with no mask of the offsets that may start
/// a complete frame: the offsets past those are tested too, which can only add a `true` (an
/// offset among the last pending bytes that passes; those past the pending bytes hold the
/// filler, which fails), and the mask's four loads and four ands (of about 40 instructions)
/// are saved.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn frame_may_be_inside<L: LayoutRef>(
    layout: &L,
    readable: &[u8],
    pending: usize,
    limit: usize,
    filled: bool,
) -> bool {
    // Offsets `1..=last_start`.
    let Some(last_start) = pending.checked_sub(shortest_frame(layout)) else {
        return false;
    };
    if last_start == 0 {
        return false;
    }
    // (Never `None`: `1 <= last_start < pending <= readable.len()`; a branch, where a fallback
    // value costs conditional moves on every chunk.)
    let Some(rest) = readable.get(1..) else {
        return false;
    };
    if filled {
        // Whole blocks, read less than `FILL` bytes past the pending ones (see `FILL`).
        let first = may_start_block(layout, rest, SCAN, limit);
        if last_start <= SCAN {
            // Nearly always: a candidate cut by a small chunk.
            if let Some(hit) = first {
                return hit;
            }
        } else if last_start <= 2 * SCAN {
            let second = rest
                .get(SCAN..)
                .and_then(|rest| may_start_block(layout, rest, SCAN, limit));
            if let (Some(first), Some(second)) = (first, second) {
                return first | second;
            }
        }
    } else if let Some(hit) = may_start_block(layout, rest, last_start, limit) {
        // Nearly always: the bytes to test fit one block.
        if last_start <= SCAN {
            return hit;
        }
    }
    may_start(layout, rest, last_start, limit)
}

/// Bytes of [`filler`] written behind staged input on hosts, so that the block test of
/// [`frame_may_be_inside`] reads whole blocks unmasked. Enough: its `k`-th block, read when
/// more than `(k - 1) * SCAN` offsets are to be tested, ends `k * SCAN + reach + 1` bytes from
/// the candidate's start, where more than `(k - 1) * SCAN + shortest` bytes are pending; the
/// lead's reach lies inside the shortest frame, so the block ends less than `SCAN` bytes past
/// them.
pub(super) const FILL: usize = SCAN;

/// A byte that starts no frame of `link`'s single format: its lead's [`Lead::filler`]. (With a
/// sync set or several formats there is no block test, and the byte is never read.)
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn filler<L: LayoutRef>(link: &L, limit: usize) -> u8 {
    Lead::of(link.layout(), limit).map_or(0, Lead::filler)
}

/// Whether a complete valid frame starts after the first byte of the pending candidate
/// `readable[..pending]` (`readable` may run past it: whole blocks are read from there): then
/// the candidate's claimed length runs over it, and the candidate is taken for a truncated
/// frame rather than holding the valid one back until more bytes arrive.
///
/// `dead` is how many of the candidate's first bytes are known to start no frame (its own first
/// byte counts as known); the search starts after them and leaves there how many it now knows
/// (a rejection is final: more bytes do not change it), since it is asked again each time the
/// input runs out while the candidate waits. On hosts, asked only where
/// [`frame_may_be_inside`] says yes.
#[cfg_attr(not(protocol_opt0), inline(always))]
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
        // (The masked block test on hosts only: on a microcontroller the plain search is
        // smaller and as fast.)
        let skip = if !HOST || may_start(layout, readable_rest, window, limit) {
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
        clippy::unwrap_used,
        clippy::cast_possible_truncation
    )]

    extern crate std;

    use std::vec::Vec;

    use super::{FILL, Lead, SCAN, frame_may_be_inside, may_start_lead, shortest_frame};
    use crate::layout::{ByteOrder, FrameLayout, LengthRule, Pos, WordField};

    /// A small xorshift generator: the tests are reproducible.
    fn rng() -> impl FnMut() -> u64 {
        let mut state = 0x9E37_79B9_7F4A_7C15u64;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    /// The definition [`may_start_lead`] filters for: an offset below `n` holding the lead's
    /// first byte, with the bits under its mask of the byte `reach` on equal to its value (or
    /// that byte past the end of `data`).
    fn starts(lead: Option<Lead>, data: &[u8], n: usize) -> bool {
        let Some(lead) = lead else {
            return n.min(data.len()) > 0;
        };
        (0..n.min(data.len())).any(|i| {
            data[i] == lead.first
                && data
                    .get(i + lead.reach)
                    .is_none_or(|&b| b & lead.mask == lead.value)
        })
    }

    #[test]
    fn the_block_test_answers_as_its_definition() {
        let mut next = rng();
        let leads = [
            None,
            Some(Lead {
                first: 0xA5,
                reach: 0,
                mask: 0,
                value: 0,
            }),
            Some(Lead {
                first: 0xFF,
                reach: 1,
                mask: 0xFF,
                value: 0xFF,
            }),
            Some(Lead {
                first: 0x55,
                reach: 1,
                mask: 0xFF,
                value: 0xAA,
            }),
            Some(Lead {
                first: 0xA5,
                reach: 2,
                mask: 0xFF,
                value: 0,
            }),
            Some(Lead {
                first: 0xFE,
                reach: 5,
                mask: 0x0C,
                value: 0,
            }),
        ];
        // (Under Miri, which interprets every step, fewer draws.)
        let rounds = if cfg!(miri) { 200 } else { 20_000 };
        for lead in leads {
            let own = lead.map_or([0; 2], |l| [l.first, l.value]);
            for _ in 0..rounds {
                let len = (next() % (2 * SCAN as u64 + 20)) as usize;
                // Bytes drawn mostly from the lead's own, so that starts and near misses are
                // common.
                let data: Vec<u8> = (0..len)
                    .map(|_| match next() % 4 {
                        0 | 1 => own[(next() % 2) as usize] ^ (next() % 3 == 0) as u8,
                        _ => next() as u8,
                    })
                    .collect();
                let n = (next() % (len as u64 + 1)) as usize;
                let exact = starts(lead, &data, n);
                let filtered = may_start_lead(lead, &data, n);
                assert_eq!(filtered, exact, "{lead:?} n={n} {data:02x?}");
            }
        }
    }

    #[test]
    fn the_filler_fails_every_lead() {
        // (Under Miri, which interprets every step, every 17th first byte and mask.)
        let step = if cfg!(miri) { 17 } else { 1 };
        for first in (0..=255u8).step_by(step) {
            for mask in (0..=255u8).step_by(step) {
                for value in [0, mask, mask & first, mask & !first, mask & 0x5A] {
                    let lead = Lead {
                        first,
                        reach: 1,
                        mask,
                        value,
                    };
                    let filler = lead.filler();
                    assert_ne!(filler, first, "{lead:?}");
                    if mask != 0 {
                        assert_ne!(filler & mask, value, "{lead:?}");
                    }
                    assert!(!lead.passes(&[filler, filler], 0), "{lead:?}");
                }
            }
        }
    }

    /// With the filler behind the pending bytes, the unmasked block test says yes wherever the
    /// masked one does, and besides only where an offset of its blocks among the last pending
    /// bytes, too near their end to start a complete frame, passes the lead: never on the
    /// filler.
    #[test]
    fn the_filled_block_test_adds_only_the_last_pending_offsets() {
        let mut next = rng();
        let hflink = FrameLayout {
            sync: &[0xFF, 0xFF],
            ..layout(WordField::be(4, 2), 7, 6)
        };
        let referee = layout(WordField::le(1, 2), 9, 5);
        let mut extra = 0;
        // (Under Miri, which interprets every step, fewer draws, which may not reach the case.)
        let (rounds, least) = if cfg!(miri) { (500, 0) } else { (50_000, 100) };
        for layout in [&hflink, &referee] {
            let limit = 127;
            let lead = Lead::of(layout, limit).unwrap();
            let shortest = shortest_frame(&layout);
            let own = [lead.first, lead.value];
            for _ in 0..rounds {
                let pending = (next() % 140) as usize;
                let mut buf: Vec<u8> = (0..pending + FILL + 8)
                    .map(|_| match next() % 4 {
                        0 | 1 => own[(next() % 2) as usize],
                        _ => next() as u8,
                    })
                    .collect();
                buf[pending..pending + FILL].fill(super::filler(&layout, limit));
                let masked = frame_may_be_inside(&layout, &buf, pending, limit, false);
                let filled = frame_may_be_inside(&layout, &buf, pending, limit, true);
                let last_start = pending.saturating_sub(shortest);
                // The offsets of the whole blocks read (one or two; more are masked); none
                // when no offset has room for a frame.
                let covered = if last_start <= 2 * SCAN {
                    last_start.div_ceil(SCAN) * SCAN
                } else {
                    last_start
                };
                let near_end =
                    (last_start + 1..pending.min(covered + 1)).any(|i| lead.passes(&buf, i));
                assert!(!masked || filled, "{pending} {buf:02x?}");
                assert_eq!(filled, masked || near_end, "{pending} {buf:02x?}");
                extra += usize::from(filled && !masked);
            }
        }
        // The draw reaches the case it is about.
        assert!(extra >= least, "{extra}");
    }

    fn layout(field: WordField, adjust: i64, header_len: usize) -> FrameLayout<'static> {
        FrameLayout {
            sync: &[0xA5],
            sync_set: &[],
            header_len,
            min_len: header_len,
            max_len: 4096,
            length: LengthRule::Field { field, adjust },
            constants: &[],
            header_checks: &[],
            frame_checks: &[],
            markers: &[],
            escape: None,
        }
    }

    #[test]
    fn the_lead_is_the_second_sync_byte_or_the_length_bits_no_frame_sets() {
        let hflink = FrameLayout {
            sync: &[0xFF, 0xFF],
            ..layout(WordField::be(4, 2), 7, 6)
        };
        assert_eq!(
            Lead::of(&hflink, 127),
            Some(Lead {
                first: 0xFF,
                reach: 1,
                mask: 0xFF,
                value: 0xFF
            })
        );
        // The referee: `A5`, a u16le count of data bytes (frames of 9 + count bytes).
        let referee = layout(WordField::le(1, 2), 9, 5);
        assert_eq!(
            Lead::of(&referee, 127),
            Some(Lead {
                first: 0xA5,
                reach: 2,
                mask: 0xFF,
                value: 0
            })
        );
        // Frames of up to 300 bytes: counts up to 291, nine bits; the high byte's upper seven.
        assert_eq!(
            Lead::of(&referee, 300),
            Some(Lead {
                first: 0xA5,
                reach: 2,
                mask: 0xFE,
                value: 0
            })
        );
        // Every count fits: no second test.
        assert_eq!(
            Lead::of(&referee, 70_000),
            Some(Lead {
                first: 0xA5,
                reach: 0,
                mask: 0,
                value: 0
            })
        );
        // A 10-bit length under a 6-bit version in a big-endian u16 (the length is the low
        // bits, in the second byte and the first's low two): frames of up to 64 + 4 bytes.
        let packed = layout(WordField::be(1, 2).bits(0, 10), 4, 3);
        assert_eq!(
            Lead::of(&packed, 68),
            Some(Lead {
                first: 0xA5,
                reach: 1,
                mask: 0x03,
                value: 0
            })
        );
    }

    /// Whatever the field's size, order, bits and the limit, the start of every frame the
    /// probe can accept passes its layout's lead: every header whose length by the layout's own
    /// rule ([`FrameLayout::frame_len`]) is at most the limit.
    #[test]
    fn every_acceptable_header_passes_its_lead() {
        let mut next = rng();
        let mut accepted = 0;
        // (Under Miri, which interprets every step, fewer draws.)
        let rounds = if cfg!(miri) { 400 } else { 20_000 };
        for _ in 0..rounds {
            let size = [1u8, 2, 4, 8][(next() % 4) as usize];
            let width = 1 + (next() % u64::from(size * 8)) as u8;
            let shift = (next() % u64::from(size * 8 - width + 1)) as u8;
            let order = if next() % 2 == 0 {
                ByteOrder::Little
            } else {
                ByteOrder::Big
            };
            let at = 1 + (next() % 3) as usize;
            let field = WordField {
                at: Pos::Start(at),
                size,
                order,
                shift,
                width,
            };
            let header_len = at + usize::from(size);
            let adjust = (next() % 20) as i64 - 5;
            let layout = layout(field, adjust, header_len);
            let limit = (next() % 5000) as usize;
            let lead = Lead::of(&layout, limit).unwrap();
            for _ in 0..8 {
                let mut header: Vec<u8> = (0..header_len).map(|_| next() as u8).collect();
                header[0] = 0xA5;
                // Random bytes, or a value drawn near the limit's: accepted lengths are rare
                // among random wide fields.
                if next() % 2 == 0 {
                    let near = (limit as u64).wrapping_sub(next() % 64) & field.max_value();
                    field.write(&mut header, near).unwrap();
                }
                if layout.frame_len(&header).is_some_and(|t| t <= limit) {
                    accepted += 1;
                    assert!(
                        lead.passes(&header, 0),
                        "{field:?} {adjust} {limit} {header:02x?}"
                    );
                }
            }
        }
        // The assertion above ran often enough to mean something.
        assert!(accepted > rounds, "{accepted} headers accepted");
    }
}
