//! 40-, 48- and 56-bit integers on the cursors: five, six or seven bytes on the wire, a `u64`
//! or `i64` in Rust.
//!
//! Reading a signed value extends its sign bit. Writing a value that does not fit its width is
//! [`EncodeError::ValueOutOfRange`], never a silent truncation, so that what a caller writes is
//! what a peer reads.

use super::{Reader, Writer};
use crate::error::{DecodeError, EncodeError, Place};

/// `v` if it fits `bits` unsigned bits (1 to 64): the rule of every wide unsigned write, for
/// callers that hold the value before writing it (the run-time codec fitting a scaled value).
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `v` is `2^bits` or more.
///
/// ```
/// use protocol_runtime::wire::fit_unsigned;
/// assert_eq!(fit_unsigned(0xFF_FFFF_FFFF, 40), Ok(0xFF_FFFF_FFFF));
/// assert!(fit_unsigned(0x100_0000_0000, 40).is_err());
/// ```
#[inline]
pub fn fit_unsigned(v: u64, bits: u32) -> Result<u64, EncodeError> {
    match v.checked_shr(bits) {
        Some(0) | None => Ok(v),
        Some(_) => Err(EncodeError::ValueOutOfRange { place: Place::NONE }),
    }
}

/// `v` if it fits a `bits`-bit two's complement integer (1 to 64): the rule of every wide
/// signed write.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `v` is outside `-2^(bits-1)..2^(bits-1)`.
///
/// ```
/// use protocol_runtime::wire::fit_signed;
/// assert_eq!(fit_signed(-0x80_0000_0000, 40), Ok(-0x80_0000_0000));
/// assert!(fit_signed(0x80_0000_0000, 40).is_err());
/// ```
#[inline]
pub fn fit_signed(v: i64, bits: u32) -> Result<i64, EncodeError> {
    // The bits above the sign bit are all copies of it exactly when the value fits.
    match v.checked_shr(bits.saturating_sub(1)) {
        Some(0 | -1) | None => Ok(v),
        Some(_) => Err(EncodeError::ValueOutOfRange { place: Place::NONE }),
    }
}

macro_rules! wide_ints {
    ($($n:literal bytes, $bits:literal bits: $ule:ident $ube:ident $ile:ident $ibe:ident,
       $pule:ident $pube:ident $pile:ident $pibe:ident;)*) => {
        impl Reader<'_> {$(
            #[doc = concat!("Reads a little-endian ", $bits, "-bit unsigned integer (", $n,
                " bytes) as a `u64`.")]
            ///
            /// # Errors
            ///
            /// [`DecodeError::Truncated`] if too few bytes remain.
            #[inline]
            pub fn $ule(&mut self) -> Result<u64, DecodeError> {
                let b: [u8; $n] = self.bytes()?;
                let mut x = [0u8; 8];
                x.iter_mut().zip(b).for_each(|(x, b)| *x = b);
                Ok(u64::from_le_bytes(x))
            }

            #[doc = concat!("Reads a big-endian ", $bits, "-bit unsigned integer (", $n,
                " bytes) as a `u64`.")]
            ///
            /// # Errors
            ///
            /// [`DecodeError::Truncated`] if too few bytes remain.
            #[inline]
            pub fn $ube(&mut self) -> Result<u64, DecodeError> {
                let b: [u8; $n] = self.bytes()?;
                let mut x = [0u8; 8];
                x.iter_mut().rev().zip(b.iter().rev()).for_each(|(x, b)| *x = *b);
                Ok(u64::from_be_bytes(x))
            }

            #[doc = concat!("Reads a little-endian ", $bits, "-bit two's complement integer (",
                $n, " bytes) as an `i64`, its sign bit extended.")]
            ///
            /// # Errors
            ///
            /// [`DecodeError::Truncated`] if too few bytes remain.
            #[inline]
            pub fn $ile(&mut self) -> Result<i64, DecodeError> {
                // The bytes in the top of an `i64`; the arithmetic shift brings the sign down.
                self.$ule().map(|v| ((v << (64 - $bits)) as i64) >> (64 - $bits))
            }

            #[doc = concat!("Reads a big-endian ", $bits, "-bit two's complement integer (",
                $n, " bytes) as an `i64`, its sign bit extended.")]
            ///
            /// # Errors
            ///
            /// [`DecodeError::Truncated`] if too few bytes remain.
            #[inline]
            pub fn $ibe(&mut self) -> Result<i64, DecodeError> {
                self.$ube().map(|v| ((v << (64 - $bits)) as i64) >> (64 - $bits))
            }
        )*}

        impl Writer<'_> {$(
            #[doc = concat!("Writes a `u64` as a little-endian ", $bits,
                "-bit unsigned integer (", $n, " bytes).")]
            ///
            /// # Errors
            ///
            /// [`EncodeError::ValueOutOfRange`] if `v` does not fit (nothing is written);
            /// [`EncodeError::BufferTooSmall`] if too little room remains.
            #[inline]
            pub fn $pule(&mut self, v: u64) -> Result<(), EncodeError> {
                let x = fit_unsigned(v, $bits)?.to_le_bytes();
                let mut b = [0u8; $n];
                b.iter_mut().zip(x).for_each(|(b, x)| *b = x);
                self.put_array(b)
            }

            #[doc = concat!("Writes a `u64` as a big-endian ", $bits,
                "-bit unsigned integer (", $n, " bytes).")]
            ///
            /// # Errors
            ///
            /// [`EncodeError::ValueOutOfRange`] if `v` does not fit (nothing is written);
            /// [`EncodeError::BufferTooSmall`] if too little room remains.
            #[inline]
            pub fn $pube(&mut self, v: u64) -> Result<(), EncodeError> {
                let x = fit_unsigned(v, $bits)?.to_be_bytes();
                let mut b = [0u8; $n];
                b.iter_mut().rev().zip(x.iter().rev()).for_each(|(b, x)| *b = *x);
                self.put_array(b)
            }

            #[doc = concat!("Writes an `i64` as a little-endian ", $bits,
                "-bit two's complement integer (", $n, " bytes).")]
            ///
            /// # Errors
            ///
            /// [`EncodeError::ValueOutOfRange`] if `v` does not fit (nothing is written);
            /// [`EncodeError::BufferTooSmall`] if too little room remains.
            #[inline]
            pub fn $pile(&mut self, v: i64) -> Result<(), EncodeError> {
                // The low bytes of a fitting value are its wire bytes, of either sign.
                self.$pule((fit_signed(v, $bits)? as u64) & (u64::MAX >> (64 - $bits)))
            }

            #[doc = concat!("Writes an `i64` as a big-endian ", $bits,
                "-bit two's complement integer (", $n, " bytes).")]
            ///
            /// # Errors
            ///
            /// [`EncodeError::ValueOutOfRange`] if `v` does not fit (nothing is written);
            /// [`EncodeError::BufferTooSmall`] if too little room remains.
            #[inline]
            pub fn $pibe(&mut self, v: i64) -> Result<(), EncodeError> {
                self.$pube((fit_signed(v, $bits)? as u64) & (u64::MAX >> (64 - $bits)))
            }
        )*}
    };
}

wide_ints! {
    5 bytes, 40 bits: u40_le u40_be i40_le i40_be, put_u40_le put_u40_be put_i40_le put_i40_be;
    6 bytes, 48 bits: u48_le u48_be i48_le i48_be, put_u48_le put_u48_be put_i48_le put_i48_be;
    7 bytes, 56 bits: u56_le u56_be i56_le i56_be, put_u56_le put_u56_be put_i56_le put_i56_be;
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing)]
mod tests {
    use super::*;

    #[test]
    fn forty_bits_in_both_orders() {
        let mut buf = [0u8; 10];
        let mut w = Writer::new(&mut buf);
        w.put_u40_le(0x12_3456_789A).unwrap();
        w.put_u40_be(0x12_3456_789A).unwrap();
        assert_eq!(
            buf,
            [0x9A, 0x78, 0x56, 0x34, 0x12, 0x12, 0x34, 0x56, 0x78, 0x9A]
        );
        let mut r = Reader::new(&buf);
        assert_eq!(r.u40_le(), Ok(0x12_3456_789A));
        assert_eq!(r.u40_be(), Ok(0x12_3456_789A));
        r.finish().unwrap();
    }

    #[test]
    fn signed_values_extend_their_sign_at_every_width() {
        let mut buf = [0u8; 7];
        for (bits, v) in [
            (40, -2i64),
            (48, -0x8000_0000_0000),
            (56, 0x7F_FFFF_FFFF_FFFF),
        ] {
            let n = bits / 8;
            let put: fn(&mut Writer<'_>, i64) -> Result<(), EncodeError> = match bits {
                40 => |w, v| w.put_i40_be(v),
                48 => |w, v| w.put_i48_be(v),
                _ => |w, v| w.put_i56_be(v),
            };
            put(&mut Writer::new(&mut buf[..n]), v).unwrap();
            let mut r = Reader::new(&buf[..n]);
            let got = match bits {
                40 => r.i40_be(),
                48 => r.i48_be(),
                _ => r.i56_be(),
            };
            assert_eq!(got, Ok(v), "{bits} bits");
        }
        assert_eq!(
            Reader::new(&[0xFE, 0xFF, 0xFF, 0xFF, 0xFF]).i40_le(),
            Ok(-2)
        );
        assert_eq!(
            Reader::new(&[0, 0, 0, 0, 0, 0x80]).i48_le(),
            Ok(-0x8000_0000_0000)
        );
    }

    #[test]
    fn values_beyond_the_width_are_refused_not_truncated() {
        let mut buf = [0u8; 7];
        let out = Err(EncodeError::ValueOutOfRange { place: Place::NONE });
        let mut w = Writer::new(&mut buf);
        assert_eq!(w.put_u40_le(1 << 40), out);
        assert_eq!(w.put_u48_be(u64::MAX), out);
        assert_eq!(w.put_i56_le(0x80_0000_0000_0000), out);
        assert_eq!(w.put_i40_be(-0x80_0000_0001), out);
        assert_eq!(w.position(), 0);
        assert_eq!(fit_unsigned(u64::MAX, 64), Ok(u64::MAX));
        assert_eq!(fit_signed(i64::MIN, 64), Ok(i64::MIN));
    }

    #[test]
    fn a_short_input_is_truncated() {
        assert!(matches!(
            Reader::new(&[1, 2, 3, 4, 5]).u48_le(),
            Err(DecodeError::Truncated { .. })
        ));
    }
}
