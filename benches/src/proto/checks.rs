//! Prototype checks for the runtime: the same algorithms as `protocol_runtime::Checksum`,
//! computed over a window of the input instead of an exact frame slice.
//!
//! Proposed for `protocol-runtime/src/checksum.rs`: a check is computed from the candidate's
//! start with the rest of the input in reach, so that a sum can add a fixed 128-byte window
//! under a mask (no loop whose trip count follows the frame length, which mispredicts once per
//! frame) and a CRC can read whole 16-byte blocks (slicing-by-16 with the leading `n % 16` bytes
//! as one zero-padded block: no byte-wise loop). The `crc` crate's `Table<16>` runs a byte-wise
//! loop over the last `n % 16` bytes, which the issue rules out of hot paths.
//!
//! Only reflected CRCs of 8 and 16 bits are prototyped (what HFLink and the referee need); the
//! MSB-first variant shifts the other way with the same tables-by-linearity construction.

use protocol_runtime::Checksum;
use protocol_runtime::layout::Check;
use protocol_runtime::wire::read_uint;

/// Bytes of the masked sum window: every byte a frame of up to 128 bytes covers.
pub const WINDOW: usize = 128;

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

/// The sum of `data[..n]`: a masked fixed window when `data` holds [`WINDOW`] bytes and
/// `n <= WINDOW`, else a plain loop (the last bytes of an input, or a long frame).
#[inline(always)]
pub fn window_sum(data: &[u8], n: usize) -> u64 {
    match data.first_chunk::<WINDOW>() {
        Some(window) if n <= WINDOW => masked_sum(window, n),
        _ => data.iter().take(n).map(|&b| u64::from(b)).sum(),
    }
}

/// The sum of `window[..n]` (`n <= WINDOW`) without a branch on `n`.
///
/// SWAR on pairs of `u64` words, shaped for the compiler's SLP vectorizer (one SSE2 register
/// per pair, wherever the function is inlined): each word's bytes are added pairwise into four
/// 16-bit lanes (at most 8 pairs x 2 x 255 = 4080 per lane), the lanes added at the end by one
/// multiplication. A plain byte loop widens every byte to 32 bits, or compares 64-bit indices:
/// 2-4x slower.
#[inline(always)]
pub fn masked_sum(window: &[u8; WINDOW], n: usize) -> u64 {
    const LOW_BYTES: u64 = 0x00FF_00FF_00FF_00FF;
    let mask = MASK[WINDOW - n.min(WINDOW)..]
        .first_chunk::<WINDOW>()
        .unwrap_or(&[0; WINDOW]);
    let word = |b: &[u8], at: usize| {
        b.get(at..at + 8)
            .and_then(|w| <[u8; 8]>::try_from(w).ok())
            .map_or(0, u64::from_le_bytes)
    };
    let mut acc = [0u64; 2];
    for k in 0..WINDOW / 16 {
        for (j, lane) in acc.iter_mut().enumerate() {
            let at = 16 * k + 8 * j;
            let x = word(window, at) & word(mask, at);
            *lane += (x & LOW_BYTES) + ((x >> 8) & LOW_BYTES);
        }
    }
    (acc[0] + acc[1]).wrapping_mul(0x0001_0001_0001_0001) >> 48
}

/// Slicing-by-16 tables of a reflected CRC of up to 16 bits, and its initial and final values.
pub struct Slices {
    tables: [[u16; 256]; 16],
    init: u16,
    xorout: u16,
    width: u32,
}

impl Slices {
    /// The tables of a reflected CRC (`refin` and `refout`) of 8 or 16 bits.
    ///
    /// # Panics
    ///
    /// At compile time, for another kind of CRC.
    pub const fn new(
        width: u32,
        poly: u16,
        init: u16,
        refin: bool,
        refout: bool,
        xorout: u16,
    ) -> Self {
        assert!(refin && refout && (width == 8 || width == 16));
        // The reflected polynomial and register: the register shifts right.
        let mut rpoly = 0u16;
        let mut rinit = 0u16;
        let mut bit = 0;
        while bit < width {
            if poly & (1 << bit) != 0 {
                rpoly |= 1 << (width - 1 - bit);
            }
            if init & (1 << bit) != 0 {
                rinit |= 1 << (width - 1 - bit);
            }
            bit += 1;
        }
        let mut tables = [[0u16; 256]; 16];
        let mut x = 0;
        while x < 256 {
            let mut r = x as u16;
            let mut b = 0;
            while b < 8 {
                r = if r & 1 != 0 { (r >> 1) ^ rpoly } else { r >> 1 };
                b += 1;
            }
            tables[0][x] = r;
            x += 1;
        }
        let mut k = 1;
        while k < 16 {
            let mut x = 0;
            while x < 256 {
                let prev = tables[k - 1][x];
                tables[k][x] = (prev >> 8) ^ tables[0][(prev & 0xFF) as usize];
                x += 1;
            }
            k += 1;
        }
        Slices {
            tables,
            init: rinit,
            xorout,
            width,
        }
    }

    #[inline(always)]
    fn block(&self, r: u16, b: [u8; 16]) -> u16 {
        let [r0, r1] = r.to_le_bytes();
        let t = &self.tables;
        let mut acc = t[15][usize::from(b[0] ^ r0)] ^ t[14][usize::from(b[1] ^ r1)];
        let mut k = 2;
        while k < 16 {
            acc ^= t[15 - k][usize::from(b[k])];
            k += 1;
        }
        acc
    }

    /// The CRC of `data[..n]` (`data` may run past `n`: the first block is read whole).
    #[inline(always)]
    pub fn checksum(&self, data: &[u8], n: usize) -> u16 {
        let Some(covered) = data.get(..n).filter(|c| !c.is_empty()) else {
            return self.init ^ self.xorout;
        };
        let lead = (n - 1) % 16 + 1;
        let first = match data.first_chunk::<16>() {
            Some(block) => u128::from_le_bytes(*block),
            None => {
                let mut block = [0u8; 16];
                block[..covered.len()].copy_from_slice(covered);
                u128::from_le_bytes(block)
            }
        };
        // The leading bytes moved to the end of a zero block, the initial register folded into
        // the first of them; what of the register does not fit the leading bytes is what the
        // register still holds after them.
        let pad = 8 * (16 - lead as u32);
        let init = u128::from(self.init) << pad;
        let mut r = self.block(0, ((first << pad) ^ init).to_le_bytes());
        r ^= (u32::from(self.init) >> (8 * (lead as u32).min(self.width / 8))) as u16;
        for block in covered[lead..].chunks_exact(16) {
            if let Ok(block) = <[u8; 16]>::try_from(block) {
                r = self.block(r, block);
            }
        }
        r ^ self.xorout
    }
}

/// How a prototype check computes its value.
#[derive(Clone, Copy)]
pub enum Fast {
    /// The runtime's `Checksum::compute` over the exact covered slice (as today).
    Runtime,
    /// A masked window sum, reduced modulo 255 (`true`) or 256.
    Sum {
        /// Modulo 255 rather than 256.
        mod255: bool,
    },
    /// A reflected CRC by slicing-by-16.
    Crc(&'static Slices),
}

/// A check of the layout with the way the prototype computes it.
#[derive(Clone, Copy)]
pub struct FastCheck {
    /// The layout's check: positions, stored order, and the algorithm for [`Fast::Runtime`].
    pub check: Check<'static>,
    /// How to compute it.
    pub fast: Fast,
}

impl FastCheck {
    /// The check value of a candidate of `len` bytes at the start of `bytes` (which may run
    /// past the candidate), or `None` if its range falls outside. Positions resolve against
    /// `len`, as the runtime's do.
    #[inline(always)]
    pub fn compute(&self, bytes: &[u8], len: usize) -> Option<u64> {
        let c = &self.check;
        let (from, to) = (c.from.resolve(len)?, c.to.resolve(len)?);
        let n = to.checked_sub(from)?;
        let rest = bytes.get(from..).filter(|r| r.len() >= n && to <= len)?;
        Some(match self.fast {
            Fast::Runtime => c.checksum.compute(rest.get(..n)?),
            Fast::Sum { mod255: true } => window_sum(rest, n) % 255,
            Fast::Sum { mod255: false } => window_sum(rest, n) & 0xFF,
            Fast::Crc(slices) => u64::from(slices.checksum(rest, n)),
        })
    }

    /// The check value of the `len`-byte frame at the start of `bytes`, for encoding: a sum is
    /// added over the exact covered bytes. Freshly written bytes read back by the wide loads of
    /// a window sum stall on store forwarding; with the frame length a constant (a fixed-size
    /// payload), the exact sum is straight-line code instead.
    #[inline(always)]
    pub fn compute_exact(&self, bytes: &[u8], len: usize) -> Option<u64> {
        let c = &self.check;
        let (from, to) = (c.from.resolve(len)?, c.to.resolve(len)?);
        let covered = bytes.get(from..to).filter(|_| to <= len)?;
        let sum = || covered.iter().map(|&b| u64::from(b)).sum::<u64>();
        Some(match self.fast {
            Fast::Sum { mod255: true } => sum() % 255,
            Fast::Sum { mod255: false } => sum() & 0xFF,
            _ => return self.compute(bytes, len),
        })
    }

    /// Whether the check holds for a candidate of `len` bytes at the start of `bytes`.
    #[inline(always)]
    pub fn verify(&self, bytes: &[u8], len: usize) -> bool {
        let c = &self.check;
        let (Some(value), Some(at), Some(frame)) = (
            self.compute(bytes, len),
            c.at.resolve(len),
            bytes.get(..len),
        ) else {
            return false;
        };
        read_uint(frame, at, c.checksum.width() as u8, c.order) == Some(value)
    }
}

/// The prototype of a runtime check: [`Fast::Sum`] for the sums, [`Fast::Runtime`] otherwise
/// (a CRC needs its slicing tables, which a layout source names).
pub const fn sum_or_runtime(check: Check<'static>) -> FastCheck {
    let fast = match check.checksum {
        Checksum::SumMod255 => Fast::Sum { mod255: true },
        Checksum::Sum8 => Fast::Sum { mod255: false },
        _ => Fast::Runtime,
    };
    FastCheck { check, fast }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workload::{Rng, referee_crc8, referee_crc16};

    #[test]
    fn window_sum_is_the_sum_for_every_length_and_overrun() {
        let mut rng = Rng::new(5);
        let buf: Vec<u8> = (0..400).map(|_| rng.byte()).collect();
        let ones = [0xFFu8; 300];
        for n in 0..=200 {
            for data in [&buf[..], &ones[..]] {
                let want: u64 = data[..n].iter().map(|&b| u64::from(b)).sum();
                assert_eq!(window_sum(data, n), want, "n {n}");
                assert_eq!(window_sum(&data[..n], n), want, "n {n}, no overrun");
            }
        }
    }

    #[test]
    fn slicing_crcs_match_the_crc_crate() {
        static CRC8: Slices = Slices::new(8, 0x31, 0xFF, true, true, 0);
        static CRC16: Slices = Slices::new(16, 0x1021, 0xFFFF, true, true, 0);
        assert_eq!(CRC16.checksum(b"123456789", 9), 0x6F91);
        assert_eq!(CRC8.checksum(b"123456789", 9), 0x0B);
        let mut rng = Rng::new(6);
        let buf: Vec<u8> = (0..300).map(|_| rng.byte()).collect();
        for n in 1..200 {
            for extra in [0, 1, 16, 40] {
                let data = &buf[..n + extra];
                assert_eq!(CRC16.checksum(data, n), referee_crc16(&buf[..n]), "n {n}");
                assert_eq!(
                    u64::from(CRC8.checksum(data, n)),
                    u64::from(referee_crc8(&buf[..n])),
                    "n {n}"
                );
            }
        }
    }
}
