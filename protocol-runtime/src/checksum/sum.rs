//! Byte sums and xor: exact over a slice, and masked over a fixed window.
//!
//! This module owns how the byte checks are computed; which one a check uses is the parent
//! module's business. Two shapes:
//!
//! - exact: whole 16-byte steps then the last bytes as one masked step, for any length;
//! - window: when the input holds [`WINDOW`] bytes and the check covers at most that many, the
//!   whole window under a mask, with no loop or branch on the covered length: a loop whose trip
//!   count follows the frame length mispredicts its exit about once per frame, since the length
//!   changes from one frame to the next (see BENCHMARKS.md).
//!
//! Nothing here divides a 64-bit number: on 32-bit targets that links a division routine
//! (`__aeabi_uldivmod`, 864 bytes on thumbv7em).

/// Bytes of the masked window: every byte a check of up to 128 bytes covers.
pub(super) const WINDOW: usize = 128;

/// `WINDOW_MASK.as_flattened()[WINDOW - n..][..WINDOW]` keeps the first `n` bytes of a window.
static WINDOW_MASK: [[u8; WINDOW]; 2] = [[0xFF; WINDOW], [0; WINDOW]];

/// The mask keeping the first `n` (`<= WINDOW`) bytes of a window.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn window_mask(n: usize) -> &'static [u8; WINDOW] {
    WINDOW_MASK
        .as_flattened()
        .get(WINDOW.wrapping_sub(n)..)
        .and_then(<[u8]>::first_chunk::<WINDOW>)
        .unwrap_or(&[0; WINDOW])
}

/// The little-endian `u64` at `at` of a window (0 past its end, which no caller reads).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn word(bytes: &[u8; WINDOW], at: usize) -> u64 {
    bytes
        .get(at..)
        .and_then(<[u8]>::first_chunk::<8>)
        .map_or(0, |b| u64::from_le_bytes(*b))
}

/// Applies `step` to `(lane, masked word)` for the sixteen words of `window[..n]` (bytes
/// past `n` read as zero), two lanes of one `u64` each: the shape of one SSE2 or NEON register,
/// which the SLP vectoriser fills. Offsets are loop counters rather than `chunks_exact`
/// iterators, whose length division stays in the code at `opt-level = "s"`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn masked_words(window: &[u8; WINDOW], n: usize, mut step: impl FnMut(&mut u64, u64)) -> [u64; 2] {
    let mask = window_mask(n);
    let mut lanes = [0u64; 2];
    for pair in 0..WINDOW / 16 {
        for (j, lane) in lanes.iter_mut().enumerate() {
            let at = pair.wrapping_mul(16).wrapping_add(j.wrapping_mul(8));
            step(lane, word(window, at) & word(mask, at));
        }
    }
    lanes
}

/// The sum of `window[..n]` (`n <= WINDOW`, at most 128 × 255 = 32640), without a branch on
/// `n`: SWAR, each word's bytes added pairwise into four 16-bit lanes (at most 8 words × 2 ×
/// 255 = 4080 per lane and `u64`), the lanes added at the end by one multiplication.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn window_sum(window: &[u8; WINDOW], n: usize) -> u32 {
    const LOW_BYTES: u64 = 0x00FF_00FF_00FF_00FF;
    let [a, b] = masked_words(window, n, |lane, x| {
        let pairs = (x & LOW_BYTES).wrapping_add((x >> 8) & LOW_BYTES);
        *lane = lane.wrapping_add(pairs);
    });
    // Each 16-bit lane of `a + b` is at most 8160; the top lane of the product is the sum of
    // the four (at most 32640), no carry crossing lanes.
    (a.wrapping_add(b).wrapping_mul(0x0001_0001_0001_0001) >> 48) as u32
}

/// The xor of `window[..n]` (`n <= WINDOW`), without a branch on `n`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn window_xor(window: &[u8; WINDOW], n: usize) -> u8 {
    let [a, b] = masked_words(window, n, |lane, x| *lane ^= x);
    fold_xor(a ^ b)
}

/// The xor of the eight bytes of `x`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn fold_xor(x: u64) -> u8 {
    let x = x ^ (x >> 32);
    let x = x ^ (x >> 16);
    (x ^ (x >> 8)) as u8
}

/// `x % 255` without a 64-bit division: `2^32 ≡ 1 (mod 255)`, so the two halves of `x` add up
/// to a congruent number, and once more to one that fits a `u32`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn mod255(x: u64) -> u8 {
    let halves = |x: u64| (x >> 32).wrapping_add(x & 0xFFFF_FFFF);
    // At most 2^33 - 2, then at most 2^32 - 1.
    let folded = halves(halves(x)) as u32;
    rem255_u32(folded)
}

/// `x % 255` as a quotient and an add, without the remainder's multiply-back: with
/// `x = 255q + r` (`r < 255`), `x + q = 256q + r`, whose low byte is `r`. (The add may wrap:
/// `2^32` is a multiple of 256.) A division by a constant is a multiplication; the remainder
/// costs three more instructions on top of it on x86-64 (`q * 255` as a shift and a
/// subtraction, then `x - q * 255`), on every frame a decoder checks.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn rem255_u32(x: u32) -> u8 {
    x.wrapping_add(x.wrapping_div(255)) as u8
}

/// [`rem255_u32`] of a [`ShortSum`] (`2^64` is a multiple of 256 too).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn rem255_short(x: ShortSum) -> u8 {
    x.wrapping_add(x.wrapping_div(255)) as u8
}

/// Whether the window shapes are used: on hosts, where words are 64 bits and vector registers
/// back the compiler's vectoriser. On a 32-bit microcontroller a plain loop is about as fast and
/// much smaller (the unrolled window and its mask cost flash). The decoder's host switch
/// ([`decoder`](crate::decoder#target-and-build-switches) lists what else it changes).
const WINDOWS: bool = cfg!(target_pointer_width = "64");

/// The sum of `data[..n]` (`n <= data.len()`): the window when it applies, else exact.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn prefix_sum(data: &[u8], n: usize) -> u64 {
    match data.first_chunk::<WINDOW>() {
        Some(window) if WINDOWS && n <= WINDOW => u64::from(window_sum(window, n)),
        _ => byte_sum(data.get(..n).unwrap_or(data)),
    }
}

/// The sum modulo 256 of `data`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn sum8(data: &[u8]) -> u8 {
    if WINDOWS && data.len() <= SHORT {
        return unrolled_sum(data) as u8;
    }
    byte_sum(data) as u8
}

/// The sum modulo 255 of `data`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn sum_mod255(data: &[u8]) -> u8 {
    if WINDOWS && data.len() <= SHORT {
        return rem255_short(unrolled_sum(data));
    }
    exact_sum_mod255(data)
}

/// [`sum_mod255`] without the unrolled short case (decoders' fallback from the window).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn exact_sum_mod255(data: &[u8]) -> u8 {
    if fits_u32_sum(data) {
        // One remainder in the target's word, without folding a `u64` first (sealing a frame
        // waits for it).
        return rem255_short(short_sum(data));
    }
    mod255(byte_sum(data))
}

/// The sum modulo 256 of `data[..n]` (`n <= data.len()`).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn sum8_prefix(data: &[u8], n: usize) -> u8 {
    prefix_sum(data, n) as u8
}

/// The sum modulo 255 of `data[..n]` (`n <= data.len()`).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn sum_mod255_prefix(data: &[u8], n: usize) -> u8 {
    match data.first_chunk::<WINDOW>() {
        // At most 32640: a `u32` remainder.
        Some(window) if WINDOWS && n <= WINDOW => rem255_u32(window_sum(window, n)),
        _ => exact_sum_mod255(data.get(..n).unwrap_or(data)),
    }
}

/// The xor of `data[..n]` (`n <= data.len()`).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn xor8_prefix(data: &[u8], n: usize) -> u8 {
    match data.first_chunk::<WINDOW>() {
        Some(window) if WINDOWS && n <= WINDOW => window_xor(window, n),
        _ => xor8(data.get(..n).unwrap_or(data)),
    }
}

/// Bytes summed or xored per step of the exact functions: one SSE2 register, which the
/// compiler fills for a loop over fixed-size arrays (`psadbw` for the sum).
const STEP: usize = 16;

/// `MASK[r..r + STEP]` keeps the last `r` bytes of a `STEP`-byte window.
static MASK: [[u8; STEP]; 2] = [[0; STEP], [0xFF; STEP]];

/// The last `STEP` bytes of `data` (at least `STEP` long), masked to keep the last `rest`
/// (`< STEP`) of them: the bytes a whole-step loop from the start left over, read without a
/// byte loop.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn masked_tail(data: &[u8], rest: usize) -> [u8; STEP] {
    let mut tail = data.last_chunk::<STEP>().copied().unwrap_or([0; STEP]);
    let mask = MASK
        .as_flattened()
        .get(rest..)
        .and_then(<[u8]>::first_chunk::<STEP>)
        .unwrap_or(&[0; STEP]);
    for (b, m) in tail.iter_mut().zip(mask) {
        *b &= m;
    }
    tail
}

/// `data` (shorter than `STEP`), zero-extended.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn padded(data: &[u8]) -> [u8; STEP] {
    let mut block = [0u8; STEP];
    for (dst, src) in block.iter_mut().zip(data) {
        *dst = *src;
    }
    block
}

/// Splits `data` into whole steps and what is left, as one zero-filled step.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn steps(data: &[u8]) -> (core::slice::ChunksExact<'_, u8>, [u8; STEP]) {
    let whole = data.chunks_exact(STEP);
    let rest = whole.remainder().len();
    let last = if data.len() < STEP {
        padded(data)
    } else {
        masked_tail(data, rest)
    };
    (whole, last)
}

#[cfg_attr(not(protocol_opt0), inline(always))]
fn sum_step(block: &[u8; STEP]) -> u64 {
    block
        .iter()
        .map(|&b| u64::from(b))
        .fold(0, u64::wrapping_add)
}

/// Inputs up to this long are summed byte by byte by [`byte_sum`].
const SHORT: usize = 32;

/// The exact sum of all bytes.
///
/// A short input is summed byte by byte: an encoder seals a frame it has just written, and
/// once inlined with a constant length the compiler takes each byte from the stores that wrote
/// it, while a wide load over freshly stored bytes stalls on store forwarding (measured: 3x on
/// a 28-byte HFLink frame).
#[cfg_attr(not(protocol_opt0), inline(always))]
// `ShortSum` is a `u64` on this target only.
#[allow(clippy::useless_conversion)]
pub(super) fn byte_sum(data: &[u8]) -> u64 {
    if fits_u32_sum(data) {
        return u64::from(short_sum(data));
    }
    if !WINDOWS {
        return data
            .iter()
            .fold(0u64, |sum, &b| sum.wrapping_add(u64::from(b)));
    }
    long_sum(data)
}

/// Inputs up to this long have a byte sum that fits a `u32` (`255 * 2^24 < 2^32`).
const U32_SUM_MAX: usize = 1 << 24;

/// Whether [`byte_sum`] adds `data` byte by byte in a `u32`: short inputs, and on 32-bit
/// targets every input a `u32` holds the sum of (a `u64` accumulator there takes two
/// registers and an add with carry per byte; frames never come near the limit).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn fits_u32_sum(data: &[u8]) -> bool {
    data.len() <= SHORT || (!WINDOWS && data.len() <= U32_SUM_MAX)
}

/// The sum of `data`, which [`fits_u32_sum`], as a `u32` on 32-bit targets and a `u64` on
/// 64-bit ones.
///
/// On 64-bit targets the bytes are added in a `u64`: with a `u32` accumulator (or a `u64`
/// narrowed afterwards) the compiler vectorizes the loop with 4-byte loads, which over the
/// bytes an encoder has just stored one field at a time stall on store forwarding (measured:
/// 3x on a 28-byte HFLink frame), while it keeps `u64` adds of bytes scalar.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn short_sum(data: &[u8]) -> ShortSum {
    data.iter()
        .fold(0, |sum: ShortSum, &b| sum.wrapping_add(ShortSum::from(b)))
}

/// [`short_sum`] of at most [`SHORT`] bytes as a loop of constant trip count, for the checks
/// encoders compute ([`sum8`], [`sum_mod255`]): the compiler unrolls it before it forwards
/// stores to loads, so an encoder sealing the frame it has just written adds the values it
/// stored instead of reading the bytes back (a loop over `data.len()` bytes was unrolled too
/// late for that, and kept a loop over its last bytes: 0.90x - 0.91x the hand-written HFLink
/// encoder before, 0.94x - 0.96x after, in full benchmark runs). Not for decoders: inlined in a scan loop, its 32 steps cost more than they save.
///
/// Written out term by term (a loop of 32 was unrolled or not depending on where it was
/// inlined: kept as a loop, it cost the HFLink encoder 2.8x).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn unrolled_sum(data: &[u8]) -> ShortSum {
    macro_rules! terms {
        ($($i:literal)*) => {
            (0 as ShortSum) $(.wrapping_add(data.get($i).map_or(0, |&b| ShortSum::from(b))))*
        };
    }
    const _: () = assert!(SHORT == 32);
    terms!(0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20 21 22 23 24 25 26 27 28 29 30 31)
}

/// [`short_sum`]'s accumulator: the target's word (the host switch, as [`WINDOWS`]).
#[cfg(target_pointer_width = "64")]
type ShortSum = u64;
#[cfg(not(target_pointer_width = "64"))]
type ShortSum = u32;

/// [`byte_sum`] of a long input.
#[inline]
fn long_sum(data: &[u8]) -> u64 {
    let (whole, last) = steps(data);
    let mut total = sum_step(&last);
    for block in whole {
        if let Some(block) = block.first_chunk::<STEP>() {
            total = total.wrapping_add(sum_step(block));
        }
    }
    total
}

/// The xor of all bytes.
#[inline]
pub(super) fn xor8(data: &[u8]) -> u8 {
    let (whole, last) = steps(data);
    let mut acc = u128::from_le_bytes(last);
    for block in whole {
        if let Some(block) = block.first_chunk::<STEP>() {
            acc ^= u128::from_le_bytes(*block);
        }
    }
    fold_xor((acc as u64) ^ ((acc >> 64) as u64))
}

/// The sum of `init` and `data` modulo 2^(8 × `width`) (`width` 1, else 2), xored with
/// `xorout`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub(super) fn sum_xorout(data: &[u8], width: u8, init: u16, xorout: u16) -> u64 {
    let mask: u64 = if width == 1 { 0xFF } else { 0xFFFF };
    (byte_sum(data).wrapping_add(u64::from(init)) ^ u64::from(xorout)) & mask
}
