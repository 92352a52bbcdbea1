//! IEEE 754 half precision (binary16) on the cursors: two bytes on the wire, an `f32` in Rust.
//!
//! Every half is exactly an `f32`, so reading is exact ([`f16_to_f32`]). Writing rounds to the
//! nearest half, ties to even ([`f32_to_f16`]), as IEEE 754 conversion and Python's
//! `struct.pack('e', x)` do; a finite value beyond the largest half (65504, after rounding) is
//! [`EncodeError::ValueOutOfRange`], never an infinity, so that what a caller writes is what a
//! peer reads. Infinities stay infinities; a NaN keeps its sign and the top ten bits of its
//! payload (a NaN whose top ten bits are zero becomes the quiet NaN of its sign), so a half
//! read and written again gives its own bits back.
//!
//! The conversion is bit arithmetic on the `f32`'s fields, no float operation, so it is exact
//! on every target and needs no FPU.

use super::{Reader, Writer};
use crate::error::{DecodeError, EncodeError, Place};

/// The `f32` a half's bits stand for (exact: every half is an `f32`).
///
/// ```
/// use protocol_runtime::wire::f16_to_f32;
/// assert_eq!(f16_to_f32(0x3C00), 1.0);
/// assert_eq!(f16_to_f32(0xC000), -2.0);
/// assert_eq!(f16_to_f32(0x7BFF), 65504.0);
/// assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
/// ```
#[must_use]
#[allow(
    clippy::arithmetic_side_effects,
    reason = "shifts and sums of a 5-bit exponent and a 10-bit mantissa in u32: no overflow"
)]
pub fn f16_to_f32(h: u16) -> f32 {
    let sign = u32::from(h & 0x8000) << 16;
    let exp = u32::from(h >> 10) & 0x1F;
    let man = u32::from(h & 0x3FF);
    let bits = match (exp, man) {
        (0, 0) => sign,
        // A subnormal, `man * 2^-24`: normalized so that its top bit is the implicit one.
        (0, _) => {
            let shift = man.leading_zeros() - 21;
            sign | ((113 - shift) << 23) | (((man << shift) & 0x3FF) << 13)
        }
        (0x1F, _) => sign | 0x7F80_0000 | (man << 13),
        _ => sign | ((exp + 112) << 23) | (man << 13),
    };
    f32::from_bits(bits)
}

/// The bits of the half nearest `x`, ties to even; `None` when `x` is finite but rounds beyond
/// the largest half (65504).
///
/// ```
/// use protocol_runtime::wire::f32_to_f16;
/// assert_eq!(f32_to_f16(1.0), Some(0x3C00));
/// assert_eq!(f32_to_f16(0.1), Some(0x2E66));
/// assert_eq!(f32_to_f16(65519.0), Some(0x7BFF));
/// assert_eq!(f32_to_f16(65520.0), None);
/// assert_eq!(f32_to_f16(f32::NEG_INFINITY), Some(0xFC00));
/// ```
#[must_use]
#[allow(
    clippy::arithmetic_side_effects,
    reason = "shifts and sums of an 8-bit exponent and a 24-bit mantissa in u32: no overflow"
)]
pub fn f32_to_f16(x: f32) -> Option<u16> {
    let b = x.to_bits();
    let sign = (b >> 16) & 0x8000;
    let exp = (b >> 23) & 0xFF;
    let man = b & 0x7F_FFFF;
    if exp == 0xFF {
        let payload = man >> 13;
        let nan = match (man, payload) {
            (0, _) => 0,
            (_, 0) => 0x200,
            _ => payload,
        };
        return u16::try_from(sign | 0x7C00 | nan).ok();
    }
    // Below half the smallest subnormal (2^-25, or exactly it: a tie to the even zero).
    if exp < 102 {
        return u16::try_from(sign).ok();
    }
    // A normal half keeps 10 of the 23 mantissa bits; a subnormal one fewer, down to none.
    let (full, drop, base) = if exp >= 113 {
        (man, 13, (exp - 112) << 10)
    } else {
        (man | 0x80_0000, 126 - exp, 0)
    };
    let kept = base | (full >> drop);
    let rest = full & ((1 << drop) - 1);
    let half = 1 << (drop - 1);
    // A carry out of the mantissa raises the exponent, which is the right rounding too.
    let rounded = if rest > half || (rest == half && kept & 1 == 1) {
        kept + 1
    } else {
        kept
    };
    (rounded < 0x7C00)
        .then(|| u16::try_from(sign | rounded).ok())
        .flatten()
}

/// The half bits of `x`, by [`f32_to_f16`].
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `x` is finite but beyond the largest half.
#[inline]
pub fn fit_f16(x: f32) -> Result<u16, EncodeError> {
    f32_to_f16(x).ok_or(EncodeError::ValueOutOfRange { place: Place::NONE })
}

impl Reader<'_> {
    /// Reads a little-endian half (two bytes) as an `f32`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than two bytes remain.
    ///
    /// ```
    /// use protocol_runtime::Reader;
    /// assert_eq!(Reader::new(&[0x00, 0x3C]).f16_le(), Ok(1.0));
    /// ```
    #[inline]
    pub fn f16_le(&mut self) -> Result<f32, DecodeError> {
        self.u16_le().map(f16_to_f32)
    }

    /// Reads a big-endian half (two bytes) as an `f32`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than two bytes remain.
    #[inline]
    pub fn f16_be(&mut self) -> Result<f32, DecodeError> {
        self.u16_be().map(f16_to_f32)
    }
}

impl Writer<'_> {
    /// Writes an `f32` as a little-endian half (two bytes), rounded to the nearest.
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is finite but beyond the largest half (nothing
    /// is written); [`EncodeError::BufferTooSmall`] if too little room remains.
    ///
    /// ```
    /// use protocol_runtime::{EncodeError, Writer};
    /// let mut buf = [0u8; 2];
    /// let mut w = Writer::new(&mut buf);
    /// assert!(w.put_f16_le(1e5).is_err());
    /// w.put_f16_le(-2.0)?;
    /// assert_eq!(buf, [0x00, 0xC0]);
    /// # Ok::<(), EncodeError>(())
    /// ```
    #[inline]
    pub fn put_f16_le(&mut self, v: f32) -> Result<(), EncodeError> {
        self.put_u16_le(fit_f16(v)?)
    }

    /// Writes an `f32` as a big-endian half (two bytes), rounded to the nearest.
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is finite but beyond the largest half (nothing
    /// is written); [`EncodeError::BufferTooSmall`] if too little room remains.
    #[inline]
    pub fn put_f16_be(&mut self, v: f32) -> Result<(), EncodeError> {
        self.put_u16_be(fit_f16(v)?)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::arithmetic_side_effects)]
mod tests {
    use super::*;

    /// Every half, or under Miri (which interprets every step) every 61st: a sample of every
    /// exponent and sign.
    const MIRI_STEP: usize = if cfg!(miri) { 61 } else { 1 };

    #[test]
    fn every_half_reads_and_writes_back_to_its_bits() {
        for h in (0..=u16::MAX).step_by(MIRI_STEP) {
            let x = f16_to_f32(h);
            assert_eq!(f32_to_f16(x), Some(h), "{h:#06x} read as {x}");
        }
    }

    /// Every finite half is its value: checked against the definition, `(-1)^s * 2^(e-15) *
    /// (1 + m/1024)` for normals and `m * 2^-24` for subnormals, computed in `f64`.
    #[test]
    fn every_finite_half_has_its_value() {
        for h in (0..=u16::MAX).step_by(MIRI_STEP) {
            let (s, e, m) = (h >> 15, i32::from((h >> 10) & 0x1F), f64::from(h & 0x3FF));
            if e == 0x1F {
                let x = f16_to_f32(h);
                assert!(if m == 0.0 {
                    x.is_infinite()
                } else {
                    x.is_nan()
                });
                continue;
            }
            let magnitude = if e == 0 {
                m * 2f64.powi(-24)
            } else {
                (1.0 + m / 1024.0) * 2f64.powi(e - 15)
            };
            let want = if s == 1 { -magnitude } else { magnitude };
            assert_eq!(f64::from(f16_to_f32(h)), want, "{h:#06x}");
            assert_eq!(f16_to_f32(h).is_sign_negative(), s == 1);
        }
    }

    /// Rounding to nearest, ties to even, at the values between two neighbouring halves.
    #[test]
    fn values_between_halves_round_to_the_nearest_ties_to_even() {
        for h in (0u16..0x7BFF).step_by(7) {
            let (a, b) = (f16_to_f32(h), f16_to_f32(h + 1));
            let mid = (f64::from(a) + f64::from(b)) / 2.0;
            let even = if h & 1 == 0 { h } else { h + 1 };
            assert_eq!(f32_to_f16(mid as f32), Some(even), "tie at {mid}");
            let below = f32::from_bits((mid as f32).to_bits() - 1);
            let above = f32::from_bits((mid as f32).to_bits() + 1);
            assert_eq!(f32_to_f16(below), Some(h), "below {mid}");
            assert_eq!(f32_to_f16(above), Some(h + 1), "above {mid}");
        }
        assert_eq!(f32_to_f16(2f32.powi(-25)), Some(0));
        assert_eq!(f32_to_f16(-2f32.powi(-25) * 1.5), Some(0x8001));
        assert_eq!(f32_to_f16(f32::MIN_POSITIVE), Some(0));
    }

    #[test]
    fn nans_stay_nans_and_large_values_are_refused() {
        assert_eq!(f32_to_f16(f32::from_bits(0x7F80_0001)), Some(0x7E00));
        assert_eq!(f32_to_f16(f32::from_bits(0xFFC0_0000)), Some(0xFE00));
        assert_eq!(f32_to_f16(65504.0), Some(0x7BFF));
        assert_eq!(f32_to_f16(-65520.0), None);
        assert_eq!(f32_to_f16(f32::MAX), None);
        let mut buf = [0u8; 2];
        assert_eq!(
            Writer::new(&mut buf).put_f16_be(7e4),
            Err(EncodeError::ValueOutOfRange { place: Place::NONE })
        );
    }
}
