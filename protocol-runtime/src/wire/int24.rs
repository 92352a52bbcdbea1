//! 24-bit integers on the cursors: three bytes on the wire, a `u32` or `i32` in Rust.
//!
//! Reading a signed value extends its sign bit (bit 23). Writing a value that does not fit 24
//! bits is [`EncodeError::ValueOutOfRange`], never a silent truncation, so that what a caller
//! writes is what a peer reads.

use super::{Reader, Writer};
use crate::error::{DecodeError, EncodeError};

/// The largest 24-bit unsigned value.
const U24_MAX: u32 = 0xFF_FFFF;

/// The 24-bit signed range.
const I24_RANGE: core::ops::RangeInclusive<i32> = -0x80_0000..=0x7F_FFFF;

/// `v` if it fits 24 unsigned bits: the rule of every 24-bit write, for callers that hold the
/// value before writing it (the run-time codec fitting a scaled value).
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `v` is above `0xFF_FFFF`.
#[inline]
pub fn fit_u24(v: u32) -> Result<u32, EncodeError> {
    if v <= U24_MAX {
        Ok(v)
    } else {
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
    }
}

/// `v` if it fits a 24-bit two's complement integer: the rule of every signed 24-bit write.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `v` is outside `-0x80_0000..=0x7F_FFFF`.
#[inline]
pub fn fit_i24(v: i32) -> Result<i32, EncodeError> {
    if I24_RANGE.contains(&v) {
        Ok(v)
    } else {
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
    }
}

impl Reader<'_> {
    /// Reads a little-endian 24-bit unsigned integer (three bytes) as a `u32`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than three bytes remain.
    ///
    /// ```
    /// use protocol_runtime::Reader;
    ///
    /// assert_eq!(Reader::new(&[0x56, 0x34, 0x12]).u24_le(), Ok(0x12_3456));
    /// ```
    #[inline]
    pub fn u24_le(&mut self) -> Result<u32, DecodeError> {
        self.bytes()
            .map(|[a, b, c]| u32::from_le_bytes([a, b, c, 0]))
    }

    /// Reads a big-endian 24-bit unsigned integer (three bytes) as a `u32`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than three bytes remain.
    #[inline]
    pub fn u24_be(&mut self) -> Result<u32, DecodeError> {
        self.bytes()
            .map(|[a, b, c]| u32::from_be_bytes([0, a, b, c]))
    }

    /// Reads a little-endian 24-bit two's complement integer (three bytes) as an `i32`, its
    /// sign bit (bit 23) extended.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than three bytes remain.
    ///
    /// ```
    /// use protocol_runtime::Reader;
    ///
    /// assert_eq!(Reader::new(&[0xFE, 0xFF, 0xFF]).i24_le(), Ok(-2));
    /// ```
    #[inline]
    pub fn i24_le(&mut self) -> Result<i32, DecodeError> {
        // The three bytes in the top of an `i32`; the arithmetic shift brings the sign down.
        self.bytes()
            .map(|[a, b, c]| i32::from_le_bytes([0, a, b, c]) >> 8)
    }

    /// Reads a big-endian 24-bit two's complement integer (three bytes) as an `i32`, its sign
    /// bit (bit 23) extended.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than three bytes remain.
    #[inline]
    pub fn i24_be(&mut self) -> Result<i32, DecodeError> {
        self.bytes()
            .map(|[a, b, c]| i32::from_be_bytes([a, b, c, 0]) >> 8)
    }
}

impl Writer<'_> {
    /// Writes a `u32` as a little-endian 24-bit unsigned integer (three bytes).
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is above `0xFF_FFFF` (nothing is written);
    /// [`EncodeError::BufferTooSmall`] if too little room remains.
    ///
    /// ```
    /// use protocol_runtime::{EncodeError, Writer};
    ///
    /// let mut buf = [0u8; 3];
    /// let mut w = Writer::new(&mut buf);
    /// assert_eq!(w.put_u24_le(0x100_0000), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
    /// w.put_u24_le(0x12_3456)?;
    /// assert_eq!(buf, [0x56, 0x34, 0x12]);
    /// # Ok::<(), EncodeError>(())
    /// ```
    #[inline]
    pub fn put_u24_le(&mut self, v: u32) -> Result<(), EncodeError> {
        let [a, b, c, _] = fit_u24(v)?.to_le_bytes();
        self.put_array([a, b, c])
    }

    /// Writes a `u32` as a big-endian 24-bit unsigned integer (three bytes).
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is above `0xFF_FFFF` (nothing is written);
    /// [`EncodeError::BufferTooSmall`] if too little room remains.
    #[inline]
    pub fn put_u24_be(&mut self, v: u32) -> Result<(), EncodeError> {
        let [_, a, b, c] = fit_u24(v)?.to_be_bytes();
        self.put_array([a, b, c])
    }

    /// Writes an `i32` as a little-endian 24-bit two's complement integer (three bytes).
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is outside `-0x80_0000..=0x7F_FFFF` (nothing
    /// is written); [`EncodeError::BufferTooSmall`] if too little room remains.
    #[inline]
    pub fn put_i24_le(&mut self, v: i32) -> Result<(), EncodeError> {
        let [a, b, c, _] = fit_i24(v)?.to_le_bytes();
        self.put_array([a, b, c])
    }

    /// Writes an `i32` as a big-endian 24-bit two's complement integer (three bytes).
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] if `v` is outside `-0x80_0000..=0x7F_FFFF` (nothing
    /// is written); [`EncodeError::BufferTooSmall`] if too little room remains.
    #[inline]
    pub fn put_i24_be(&mut self, v: i32) -> Result<(), EncodeError> {
        let [_, a, b, c] = fit_i24(v)?.to_be_bytes();
        self.put_array([a, b, c])
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// Writes `v` with `put` and reads it back with `get`, giving the bytes.
    fn round_trip<T: Copy + PartialEq + core::fmt::Debug>(
        v: T,
        put: impl Fn(&mut Writer<'_>, T) -> Result<(), EncodeError>,
        get: impl Fn(&mut Reader<'_>) -> Result<T, DecodeError>,
    ) -> [u8; 3] {
        let mut buf = [0u8; 3];
        put(&mut Writer::new(&mut buf), v).unwrap();
        let mut r = Reader::new(&buf);
        assert_eq!(get(&mut r).unwrap(), v);
        r.finish().unwrap();
        buf
    }

    #[test]
    fn unsigned_values_take_three_bytes_in_either_order() {
        let le = round_trip(0x12_3456, |w, v| w.put_u24_le(v), |r| r.u24_le());
        let be = round_trip(0x12_3456, |w, v| w.put_u24_be(v), |r| r.u24_be());
        assert_eq!(le, [0x56, 0x34, 0x12]);
        assert_eq!(be, [0x12, 0x34, 0x56]);
        assert_eq!(
            round_trip(U24_MAX, |w, v| w.put_u24_le(v), |r| r.u24_le()),
            [0xFF; 3]
        );
        assert_eq!(
            round_trip(0, |w, v| w.put_u24_be(v), |r| r.u24_be()),
            [0; 3]
        );
    }

    #[test]
    fn signed_values_extend_their_sign_bit() {
        for v in [-0x80_0000, -1, 0, 1, 0x7F_FFFF, -0x12_3456] {
            let le = round_trip(v, |w, v| w.put_i24_le(v), |r| r.i24_le());
            let be = round_trip(v, |w, v| w.put_i24_be(v), |r| r.i24_be());
            assert_eq!(le, [be[2], be[1], be[0]]);
        }
        assert_eq!(Reader::new(&[0x00, 0x00, 0x80]).i24_le(), Ok(-0x80_0000));
        assert_eq!(Reader::new(&[0x80, 0x00, 0x00]).i24_be(), Ok(-0x80_0000));
        assert_eq!(Reader::new(&[0xFF, 0xFF, 0x7F]).i24_le(), Ok(0x7F_FFFF));
    }

    #[test]
    fn values_beyond_24_bits_are_errors_and_write_nothing() {
        let mut buf = [0xAAu8; 4];
        let mut w = Writer::new(&mut buf);
        assert_eq!(
            w.put_u24_le(U24_MAX + 1),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            w.put_u24_be(u32::MAX),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            w.put_i24_le(0x80_0000),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            w.put_i24_be(-0x80_0001),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(w.position(), 0);
        assert_eq!(buf, [0xAA; 4]);
    }

    #[test]
    fn short_input_and_buffer_are_errors() {
        assert_eq!(
            Reader::new(&[1, 2]).u24_be(),
            Err(DecodeError::Truncated {
                needed: 3,
                available: 2
            })
        );
        let mut buf = [0u8; 2];
        assert_eq!(
            Writer::new(&mut buf).put_i24_le(1),
            Err(EncodeError::BufferTooSmall {
                needed: 3,
                available: 2
            })
        );
    }
}
