//! HFLink by hand: the frame scan and an encoder.
//!
//! `FF FF sender receiver length(u16 BE) command payload sum`, `length` in `1..=120` (command and
//! payload), `sum` the sum of every byte before it modulo 255.

use super::{Lead, Scan};

/// HFLink frames.
pub struct HfLink;

/// Largest frame.
const MAX_FRAME: usize = 127;
/// Bytes summed by the fixed-window sum: every byte a frame's check covers.
const WINDOW: usize = 128;

/// Where the next candidate starts at or after `at`: `FF FF`, or a lone `FF` as the last byte.
#[inline(always)]
fn find_sync(data: &[u8], mut at: usize) -> Option<usize> {
    // On a clean stream the next frame starts right here.
    if let Some([0xFF, 0xFF]) = data.get(at..at + 2).and_then(|s| s.first_chunk::<2>()) {
        return Some(at);
    }
    loop {
        let q = at + memchr::memchr(0xFF, data.get(at..)?)?;
        match data.get(q + 1) {
            None | Some(0xFF) => return Some(q),
            // Neither `q` nor `q + 1` starts a frame.
            Some(_) => at = q + 2,
        }
    }
}

/// `MASK[WINDOW - n..][..WINDOW]` keeps the first `n` bytes of a window.
static MASK: [u8; 2 * WINDOW] = {
    let mut m = [0u8; 2 * WINDOW];
    let mut i = 0;
    while i < WINDOW {
        m[i] = 0xFF;
        i += 1;
    }
    m
};

/// Sum of `window[..n]` (`n <= WINDOW`), with no branch on `n`: a loop whose trip count follows
/// the frame length mispredicts once per frame; summing a fixed window under a mask does not.
///
/// The sum is SWAR on `u64` words, which the compiler turns into SSE2: each word's bytes are
/// added pairwise into four 16-bit lanes (at most 16 words x 2 x 255 = 8160 per lane), and the
/// lanes are added at the end with one multiplication. (Written as a plain byte loop, the
/// compiler widens every byte to 32 bits or compares 64-bit indices: 2-4x slower.)
#[inline(always)]
fn masked_sum(window: &[u8; WINDOW], n: usize) -> u32 {
    const LOW_BYTES: u64 = 0x00FF_00FF_00FF_00FF;
    let mask = MASK[WINDOW - n.min(WINDOW)..]
        .first_chunk::<WINDOW>()
        .unwrap_or(&[0; WINDOW]);
    let mut lanes = 0u64;
    for (w, m) in window.chunks_exact(8).zip(mask.chunks_exact(8)) {
        let (Ok(w), Ok(m)) = (<[u8; 8]>::try_from(w), <[u8; 8]>::try_from(m)) else {
            continue;
        };
        let x = u64::from_le_bytes(w) & u64::from_le_bytes(m);
        lanes += (x & LOW_BYTES) + ((x >> 8) & LOW_BYTES);
    }
    // The four lanes add up to at most 32640: the top 16 bits of the product hold their sum.
    (lanes.wrapping_mul(0x0001_0001_0001_0001) >> 48) as u32
}

/// Whether the `total`-byte frame at the start of `rest` carries the right sum (`rest` holds
/// the frame and may run past it).
#[inline(always)]
fn sum_ok(rest: &[u8], total: usize) -> bool {
    let covered = total - 1;
    let sum = match rest.first_chunk::<WINDOW>() {
        Some(window) => masked_sum(window, covered),
        // The last bytes of the input: a plain loop.
        None => rest[..covered].iter().map(|&b| u32::from(b)).sum(),
    };
    (sum % 255) as u8 == rest[covered]
}

impl Scan for HfLink {
    const MAX_FRAME: usize = MAX_FRAME;
    const SHORTEST: usize = 8;
    // `FF FF`.
    const LEAD: Lead = Lead {
        first: 0xFF,
        reach: 1,
        mask: 0xFF,
        value: 0xFF,
    };

    #[inline(always)]
    fn scan<F: FnMut(&[u8])>(buf: &[u8], len: usize, at_end: bool, sink: &mut F) -> usize {
        let data = &buf[..len];
        let mut at = 0;
        while let Some(p) = find_sync(data, at) {
            let rest = &data[p..];
            let Some(header) = rest.first_chunk::<6>() else {
                if at_end {
                    at = p + 1;
                    continue;
                }
                return p;
            };
            let length = usize::from(u16::from_be_bytes([header[4], header[5]]));
            // `length` in 1..=120, in one comparison.
            if length.wrapping_sub(1) >= 120 {
                at = p + 1;
                continue;
            }
            let total = length + 7;
            if rest.len() < total {
                if at_end {
                    at = p + 1;
                    continue;
                }
                return p;
            }
            if sum_ok(&buf[p..], total) {
                sink(&rest[..total]);
                at = p + total;
            } else {
                at = p + 1;
            }
        }
        data.len()
    }
}

/// Bytes of a `READ_SYSTEM_INFO` response: header, command, 20 payload bytes, sum.
pub const SYSTEM_INFO_FRAME: usize = 28;

/// Writes a `READ_SYSTEM_INFO` response carrying the five `f32` of `SystemInfo` at the start of
/// `buf`; returns its length, or `None` if `buf` is too short.
#[inline]
pub fn encode_system_info(
    buf: &mut [u8],
    sender: u8,
    receiver: u8,
    info: [f32; 5],
) -> Option<usize> {
    let frame = buf.first_chunk_mut::<SYSTEM_INFO_FRAME>()?;
    frame[..7].copy_from_slice(&[0xFF, 0xFF, sender, receiver, 0, 21, 1]);
    for (dst, v) in frame[7..27].chunks_exact_mut(4).zip(info) {
        dst.copy_from_slice(&v.to_le_bytes());
    }
    let sum: u32 = frame[..27].iter().map(|&b| u32::from(b)).sum();
    frame[27] = (sum % 255) as u8;
    Some(SYSTEM_INFO_FRAME)
}
