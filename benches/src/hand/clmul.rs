//! CRC-16/MCRF4XX folded with carry-less multiplication (`pclmulqdq`), the fastest CRC-16 the
//! baseline knows of on x86-64 hosts; [`crc16`](super::crc::crc16) (slicing-by-16) elsewhere.
//!
//! A reflected CRC is a product in a ring: with the stream's bits numbered in the order they are
//! sent (each byte least significant bit first) and bit `t` the coefficient of `y^t`, the data
//! `D(y)` of `L` bits leaves the register `D(y) * y^-L mod Q(y)`, where `Q` is the reciprocal of
//! the CRC polynomial (`Q(y) = y^16 P(1/y)`, bit 0 set, so `y` is invertible) and the register
//! value is the CRC's reflected register; the initial register is xored into the first two
//! bytes. A little-endian load puts bit `t` of a block at bit `t` of the word, so carry-less
//! products of loaded words are products of these polynomials.
//!
//! Sixteen bytes at a time: the accumulator `A` (the register, not yet reduced) takes the next
//! block `B` as `A' = (A ^ B) * y^-128`, i.e. `lo(A ^ B) * (y^-128 mod Q) ^ hi(A ^ B) * (y^-64
//! mod Q)`, two products of 64 x 16 bits. At the end, `A` (79 bits) is folded to 64 bits
//! (`hi(A) * (y^64 mod Q)`) and reduced by Barrett's method (two more products). The leading
//! `n % 16` bytes are one block padded with zeros in front, as in the slicing CRC: no byte loop.

use core::arch::x86_64::{
    __m128i, _mm_clmulepi64_si128, _mm_cvtsi128_si64, _mm_set_epi64x, _mm_srli_si128, _mm_xor_si128,
};

/// `Q(y)`, the reciprocal of CRC-16/MCRF4XX's polynomial `0x1021`: `1 + y^4 + y^11 + y^16`.
const Q: u64 = 0x1_0811;
/// The initial register.
const INIT: u16 = 0xFFFF;

/// `y^-n mod Q`: `n` steps of the reflected register's shift.
const fn y_inverse_pow(n: u32) -> u64 {
    let mut r = 1u64;
    let mut i = 0;
    while i < n {
        r = if r & 1 != 0 { (r ^ Q) >> 1 } else { r >> 1 };
        i += 1;
    }
    r
}

/// `y^n mod Q`.
const fn y_pow(n: u32) -> u64 {
    let mut r = 1u64;
    let mut i = 0;
    while i < n {
        r <<= 1;
        if r & (1 << 16) != 0 {
            r ^= Q;
        }
        i += 1;
    }
    r
}

/// `floor(y^64 / Q)`, Barrett's constant (degree 48).
const fn barrett_mu() -> u64 {
    let mut rem: u128 = 1 << 64;
    let mut quotient = 0u64;
    let mut bit = 64;
    while bit >= 16 {
        if rem & (1 << bit) != 0 {
            rem ^= (Q as u128) << (bit - 16);
            quotient |= 1 << (bit - 16);
        }
        bit -= 1;
    }
    quotient
}

const FOLD_LO: u64 = y_inverse_pow(128);
const FOLD_HI: u64 = y_inverse_pow(64);
const Y64: u64 = y_pow(64);
const MU: u64 = barrett_mu();

/// Whether this CPU multiplies without carries.
pub fn available() -> bool {
    std::arch::is_x86_feature_detected!("pclmulqdq")
}

/// `value` as a vector, low half first.
#[inline]
#[target_feature(enable = "pclmulqdq")]
fn vector(value: u128) -> __m128i {
    _mm_set_epi64x((value >> 64) as i64, value as i64)
}

/// `(a ^ b) * y^-128 mod Q`, unreduced (79 bits).
#[inline]
#[target_feature(enable = "pclmulqdq")]
fn fold(a: __m128i, b: __m128i, k: __m128i) -> __m128i {
    let x = _mm_xor_si128(a, b);
    _mm_xor_si128(
        _mm_clmulepi64_si128::<0x00>(x, k),
        _mm_clmulepi64_si128::<0x11>(x, k),
    )
}

/// CRC-16/MCRF4XX of `data[..n]` (`1 <= n <= data.len()`); `data` may run past the covered bytes
/// (a whole first block is read from there), which decide nothing.
///
/// # Safety
///
/// Called from code not compiled for `pclmulqdq`, only after [`available`] has returned `true`.
#[inline]
#[target_feature(enable = "pclmulqdq")]
pub fn crc16(data: &[u8], n: usize) -> u16 {
    let Some(covered) = data.get(..n).filter(|c| !c.is_empty()) else {
        return INIT;
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
    let pad = 8 * (16 - lead as u32);
    let k = vector((u128::from(FOLD_HI) << 64) | u128::from(FOLD_LO));
    let zero = vector(0);
    // The first `lead` bytes at the end of a zero block, the initial register folded into the
    // first two; with `lead == 1` the register's high byte is still in the register after the
    // block (it would be xored into the next byte).
    let mut acc = fold(zero, vector((first << pad) ^ (u128::from(INIT) << pad)), k);
    let rest = u32::from(INIT) >> (8 * lead.min(2) as u32);
    acc = _mm_xor_si128(acc, vector(u128::from(rest)));
    for block in covered[lead..].chunks_exact(16) {
        if let Ok(block) = <[u8; 16]>::try_from(block) {
            acc = fold(acc, vector(u128::from_le_bytes(block)), k);
        }
    }
    // 79 bits to 64: hi(A) * (y^64 mod Q) ^ lo(A).
    let r = vector((u128::from(MU) << 64) | u128::from(Y64));
    let v = _mm_xor_si128(acc, _mm_clmulepi64_si128::<0x01>(acc, r));
    let v = _mm_cvtsi128_si64(v) as u64;
    // Barrett: q = floor(floor(V / y^16) * mu / y^48); V mod Q = low 16 bits of V ^ q * Q.
    let t = vector(u128::from(v >> 16));
    let q = _mm_srli_si128::<6>(_mm_clmulepi64_si128::<0x10>(t, r));
    let qp = _mm_clmulepi64_si128::<0x00>(q, vector(u128::from(Q)));
    (v ^ _mm_cvtsi128_si64(qp) as u64) as u16
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workload::{Rng, referee_crc16};

    /// Runs `crc16` where the CPU has it (the test passes vacuously on one without: the
    /// benchmark then times the slicing CRC, and says so).
    #[allow(unsafe_code)]
    fn crc(data: &[u8], n: usize) -> Option<u16> {
        // SAFETY: `available` has checked that the CPU has `pclmulqdq`.
        available().then(|| unsafe { crc16(data, n) })
    }

    #[test]
    fn check_value() {
        if let Some(c) = crc(b"123456789", 9) {
            assert_eq!(c, 0x6F91);
        }
    }

    #[test]
    fn matches_the_crc_crate_for_every_length_and_overrun() {
        let mut rng = Rng::new(9);
        let buf: Vec<u8> = (0..400).map(|_| rng.byte()).collect();
        for n in 1..260 {
            for extra in [0, 1, 15, 16, 40] {
                if let Some(c) = crc(&buf[..n + extra], n) {
                    assert_eq!(c, referee_crc16(&buf[..n]), "n {n} +{extra}");
                }
            }
        }
    }
}
