//! The `clmul` host feature: reflected CRCs of up to 32 bits folded 16 bytes at a time with
//! carry-less multiplication (`pclmulqdq`), in a build for an x86-64 CPU that has it.
//!
//! This module owns the folding, its constants and which CRCs it computes; when it is used is
//! [`Slicing16`](super::Slicing16)'s business (checks of more than 8 bytes: shorter ones are a
//! few table lookups). It is compiled in when the `clmul` feature is on and the build targets a
//! CPU with `pclmulqdq` (`RUSTFLAGS="-C target-feature=+pclmulqdq"`, or a `target-cpu` that
//! includes it: `native` on any x86-64 CPU since 2010); otherwise [`Folding`] is a type without
//! values and the tables compute every CRC.
//!
//! No run-time CPU detection: the intrinsic is a `#[target_feature]` function, which safe code
//! calls only from a function with the same attribute, and a function without it calls that
//! one only in an `unsafe` block, even when the whole build enables the feature. The
//! `safe_arch` crate (made for exactly this: `core::arch` exposed through `#[cfg]`) wraps the
//! intrinsic in a plain function that exists only in builds that enable the feature, and owns
//! that `unsafe`; this crate stays `#![forbid(unsafe_code)]`. (The crate's switches are
//! listed in one place: [`decoder`](crate::decoder#target-and-build-switches).)
//!
//! # How
//!
//! A reflected CRC is a product in a ring: with the stream's bits numbered in the order they are
//! sent (each byte least significant bit first) and bit `t` the coefficient of `y^t`, data
//! `D(y)` of `L` bits leaves the register `D(y) * y^-L mod Q(y)`, where `Q` is the reciprocal of
//! the CRC polynomial (`Q(y) = y^w P(1/y)`, of degree `w`, the CRC's width, with bit 0 set, so
//! `y` is invertible) and the value is the reflected register; the initial register is xored
//! into the first `w` bits. A little-endian load puts bit `t` of a block at bit `t` of the
//! word, so carry-less products of loaded words are products of these polynomials.
//!
//! The accumulator `A` (the register, not yet reduced) takes the next block `B` as
//! `A' = (A ^ B) * y^-128`, i.e. `lo(A ^ B) * (y^-128 mod Q) ^ hi(A ^ B) * (y^-64 mod Q)`: two
//! products of 64 x `w` bits. At the end, `A` (at most `63 + w` bits) is folded to 64 bits
//! (`hi(A) * (y^64 mod Q) ^ lo(A)`, at most `2w - 2` bits from the product: hence `w <= 32`)
//! and reduced by Barrett's method (two more products, the first set up so that the quotient
//! is its high half: no shift across the vector's halves). The leading `n % 16` bytes are one
//! block with zeros in front, as in the slicing CRC: no byte loop.

#[cfg(all(
    feature = "clmul",
    target_arch = "x86_64",
    target_feature = "pclmulqdq"
))]
pub(super) use folding::Folding;

/// Without the feature, or in a build for a CPU without `pclmulqdq`: no folding, so an
/// `Option<Folding>` is always `None` and takes no space.
#[cfg(not(all(
    feature = "clmul",
    target_arch = "x86_64",
    target_feature = "pclmulqdq"
)))]
#[derive(Clone, Copy, Debug)]
pub(super) enum Folding {}

#[cfg(not(all(
    feature = "clmul",
    target_arch = "x86_64",
    target_feature = "pclmulqdq"
)))]
impl Folding {
    /// No folding in this build.
    pub(super) const fn new(_reflected_poly: u64, _width: u8) -> Option<Self> {
        None
    }

    /// Never called: there is no value to call it on.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub(super) fn register(&self, _data: &[u8], _n: usize, _init: u64) -> u64 {
        match *self {}
    }
}

#[cfg(all(
    feature = "clmul",
    target_arch = "x86_64",
    target_feature = "pclmulqdq"
))]
mod folding {
    use safe_arch::{bitxor_m128i as xor, m128i, mul_i64_carryless_m128i as clmul};

    /// Bytes per folded block.
    const BLOCK: usize = 16;

    /// The constants of one CRC's folding.
    #[derive(Clone, Copy, Debug)]
    pub(in crate::checksum) struct Folding {
        /// `y^-128 mod Q`, `y^-64 mod Q`: the two factors of a fold, one per half of the
        /// accumulator (vector lanes, low first; words, not a `u128`, to keep the tables' own
        /// alignment).
        fold: [u64; 2],
        /// `y^64 mod Q`, Barrett's `floor(y^64 / Q)`.
        reduce: [u64; 2],
        /// `Q`, the reciprocal polynomial, `w + 1` bits.
        q: u64,
        /// The bits of a 64-bit word from bit `w` (the CRC's width, 1 to 32) up.
        above_width: u64,
    }

    impl Folding {
        /// The folding of a reflected CRC of `width` bits whose polynomial, reflected, is
        /// `reflected_poly` (the register's shift: `r >> 1 ^ reflected_poly` when the bit
        /// that leaves is set); `None` for a width outside 1 to 32 or a polynomial without its
        /// constant term (no CRC in use lacks it).
        pub(in crate::checksum) const fn new(reflected_poly: u64, width: u8) -> Option<Self> {
            let w = width as u32;
            if w == 0 || w > 32 || (reflected_poly >> w.wrapping_sub(1)) & 1 == 0 {
                return None;
            }
            let q = (reflected_poly << 1) | 1;
            let fold_lo = y_inverse_pow(q, 128);
            let fold_hi = y_inverse_pow(q, 64);
            Some(Folding {
                fold: [fold_lo, fold_hi],
                reduce: [y_pow(q, w, 64), barrett_mu(q, w)],
                q,
                above_width: u64::MAX << w,
            })
        }

        /// The reflected register after `data[..n]` from `init` (`8 < n <= data.len()`:
        /// shorter checks are the tables'), in its low `w` bits.
        #[cfg_attr(not(protocol_opt0), inline(always))]
        pub(in crate::checksum) fn register(&self, data: &[u8], n: usize, init: u64) -> u64 {
            // (`n <= data.len()`, the caller's bound: said once, so that the compiler drops the
            // fallback of every slice below.)
            let Some(covered) = data.get(..n) else {
                return 0;
            };
            // The leading bytes: 1..=16 of them, so that whole blocks follow. (Written so that
            // the compiler sees both bounds: the shifts below need no test of their range.)
            let lead = (n.wrapping_sub(1) & (BLOCK - 1)).wrapping_add(1);
            let first = match data.first_chunk::<BLOCK>() {
                Some(block) => u128::from_le_bytes(*block),
                None => {
                    // Only when all of `data` is shorter than a block.
                    let mut block = [0u8; BLOCK];
                    if let (Some(dst), Some(src)) = (block.get_mut(..n), data.get(..n)) {
                        dst.copy_from_slice(src);
                    }
                    u128::from_le_bytes(block)
                }
            };
            // The initial register meets the first bytes; both move to the end of the block
            // (zeros in front), and what `first` held past the leading bytes drops out.
            let pad = ((!n.wrapping_sub(1) & (BLOCK - 1)) as u32).wrapping_mul(8);
            let aligned = (first ^ u128::from(init)).checked_shl(pad).unwrap_or(0);
            let k = m128i::from(self.fold);
            let mut acc = times_y_inverse_128(m128i::from(aligned), k);
            // A register wider than the leading bytes still holds its other bits after them.
            let kept = init.checked_shr((lead as u32).wrapping_mul(8)).unwrap_or(0);
            acc = xor(acc, m128i::from(u128::from(kept)));
            let rest = covered.get(lead..).unwrap_or_default();
            for block in rest.chunks_exact(BLOCK) {
                if let Some(block) = block.first_chunk::<BLOCK>() {
                    let block = m128i::from(u128::from_le_bytes(*block));
                    acc = times_y_inverse_128(xor(acc, block), k);
                }
            }
            self.reduce(acc)
        }

        /// The accumulator reduced modulo `Q`.
        #[cfg_attr(not(protocol_opt0), inline(always))]
        fn reduce(&self, acc: m128i) -> u64 {
            let r = m128i::from(self.reduce);
            // At most `63 + w` bits to 64: hi(A) * (y^64 mod Q) ^ lo(A).
            let v = u128::from(xor(acc, clmul::<0x01>(acc, r))) as u64;
            // Barrett: the quotient q = floor(floor(V / y^w) * mu / y^(64 - w)), and
            // V mod Q = V ^ q * Q (of degree below w: the bits above cancel). With V's low `w`
            // bits cleared instead of shifted out, the product is the same one times y^w, at
            // most 128 - w bits, and q is its high half: the next product takes it from there
            // (a shift of the whole vector by 64 - w bits costs eight instructions).
            let high = m128i::from(u128::from(v & self.above_width));
            let times_mu = clmul::<0x10>(high, r);
            let product = clmul::<0x01>(times_mu, m128i::from(u128::from(self.q)));
            v ^ u128::from(product) as u64
        }
    }

    /// `x * y^-128 mod Q`, not reduced: `lo(x) * (y^-128 mod Q) ^ hi(x) * (y^-64 mod Q)`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    fn times_y_inverse_128(x: m128i, k: m128i) -> m128i {
        xor(clmul::<0x00>(x, k), clmul::<0x11>(x, k))
    }

    /// `y^-n mod Q`: `n` steps of the reflected register's shift.
    // Only run in `Folding::new`, a `const` initialiser: the counters are bounded by their
    // loops and the shifts by the width (1 to 32), checked before.
    #[allow(clippy::arithmetic_side_effects)]
    const fn y_inverse_pow(q: u64, n: u32) -> u64 {
        let mut r = 1u64;
        let mut i = 0;
        while i < n {
            r = if r & 1 != 0 { (r ^ q) >> 1 } else { r >> 1 };
            i += 1;
        }
        r
    }

    /// `y^n mod Q`, `Q` of degree `w`.
    // Only run in `Folding::new`, a `const` initialiser: the counters are bounded by their
    // loops and the shifts by the width (1 to 32), checked before.
    #[allow(clippy::arithmetic_side_effects)]
    const fn y_pow(q: u64, w: u32, n: u32) -> u64 {
        let mut r = 1u64;
        let mut i = 0;
        while i < n {
            r <<= 1;
            if (r >> w) & 1 != 0 {
                r ^= q;
            }
            i += 1;
        }
        r
    }

    /// `floor(y^64 / Q)`, Barrett's constant (degree `64 - w`), by long division.
    // Only run in `Folding::new`, a `const` initialiser: the counters are bounded by their
    // loops and the shifts by the width (1 to 32), checked before.
    #[allow(clippy::arithmetic_side_effects)]
    const fn barrett_mu(q: u64, w: u32) -> u64 {
        let mut rem: u128 = 1 << 64;
        let mut quotient = 0u64;
        let mut bit = 64;
        while bit >= w {
            if (rem >> bit) & 1 != 0 {
                rem ^= (q as u128) << (bit - w);
                quotient |= 1 << (bit - w);
            }
            bit -= 1;
        }
        quotient
    }
}
