//! Cursors over payload bytes ([`Reader`], [`Writer`]) and words at fixed positions of a frame
//! ([`read_uint`], [`write_uint`], [`WordField`]).
//!
//! This module owns every primitive read and write of the runtime: numbers of each width and
//! byte order, raw byte runs, and bit fields inside a word. Nothing here panics or indexes
//! without a check: a short input is [`DecodeError::Truncated`], a short buffer
//! [`EncodeError::BufferTooSmall`], a position outside the frame `None`. The cursors are the hot
//! path of generated payload code, so every method is `#[inline]` and reads fixed-size chunks
//! with `split_first_chunk`. What the bytes mean (structs, enums, scaling) is generated code's
//! business.
//!
//! ```
//! use protocol_runtime::{Reader, Writer};
//!
//! let mut buf = [0u8; 7];
//! let mut w = Writer::new(&mut buf);
//! w.put_u16_be(0x0102)?;
//! w.put_f32_le(1.5)?;
//! w.put_bool(true)?;
//! assert_eq!(w.remaining(), 0);
//!
//! let mut r = Reader::new(&buf);
//! assert_eq!(r.u16_be()?, 0x0102);
//! assert_eq!(r.f32_le()?, 1.5);
//! assert!(r.bool()?);
//! r.finish()?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::error::{DecodeError, EncodeError};
use crate::layout::{ByteOrder, WordField};

/// A cursor that reads values from the front of a byte slice.
///
/// Every read either returns the value and advances, or returns
/// [`DecodeError::Truncated`] and leaves the cursor where it was.
///
/// ```
/// use protocol_runtime::{DecodeError, Reader};
///
/// let mut r = Reader::new(&[0x34, 0x12, 0xFF]);
/// assert_eq!(r.u16_le()?, 0x1234);
/// assert_eq!(r.position(), 2);
/// assert_eq!(r.i8()?, -1);
/// assert_eq!(r.u8(), Err(DecodeError::Truncated { needed: 4, available: 3 }));
/// # Ok::<(), DecodeError>(())
/// ```
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    /// Bytes not read yet.
    rest: &'a [u8],
    /// Length of the whole input.
    total: usize,
}

macro_rules! reader_numbers {
    ($($t:ident: $le:ident, $be:ident;)*) => {$(
        #[doc = concat!("Reads a little-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`DecodeError::Truncated`] if too few bytes remain.
        #[inline]
        pub fn $le(&mut self) -> Result<$t, DecodeError> {
            self.bytes().map($t::from_le_bytes)
        }

        #[doc = concat!("Reads a big-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`DecodeError::Truncated`] if too few bytes remain.
        #[inline]
        pub fn $be(&mut self) -> Result<$t, DecodeError> {
            self.bytes().map($t::from_be_bytes)
        }
    )*};
}

impl<'a> Reader<'a> {
    /// A reader at the start of `bytes`.
    #[inline]
    pub const fn new(bytes: &'a [u8]) -> Self {
        Self {
            rest: bytes,
            total: bytes.len(),
        }
    }

    /// Bytes not read yet.
    #[inline]
    pub fn remaining(&self) -> usize {
        self.rest.len()
    }

    /// Bytes read so far.
    #[inline]
    pub fn position(&self) -> usize {
        // `rest` is always a suffix of the input.
        self.total.wrapping_sub(self.rest.len())
    }

    /// The bytes not read yet, without advancing.
    #[inline]
    pub fn rest(&self) -> &'a [u8] {
        self.rest
    }

    #[cold]
    fn truncated(&self, n: usize) -> DecodeError {
        DecodeError::Truncated {
            needed: self.position().saturating_add(n),
            available: self.total,
        }
    }

    /// Reads `N` bytes as an array.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `N` bytes remain.
    #[inline]
    pub fn bytes<const N: usize>(&mut self) -> Result<[u8; N], DecodeError> {
        match self.rest.split_first_chunk::<N>() {
            Some((head, tail)) => {
                self.rest = tail;
                Ok(*head)
            }
            None => Err(self.truncated(N)),
        }
    }

    /// Reads `n` bytes as a slice of the input.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `n` bytes remain.
    #[inline]
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], DecodeError> {
        match self.rest.split_at_checked(n) {
            Some((head, tail)) => {
                self.rest = tail;
                Ok(head)
            }
            None => Err(self.truncated(n)),
        }
    }

    /// Skips `n` bytes (padding, reserved bytes).
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `n` bytes remain.
    #[inline]
    pub fn skip(&mut self, n: usize) -> Result<(), DecodeError> {
        self.take(n).map(|_| ())
    }

    /// Reads a `u8`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn u8(&mut self) -> Result<u8, DecodeError> {
        self.bytes().map(u8::from_le_bytes)
    }

    /// Reads an `i8`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn i8(&mut self) -> Result<i8, DecodeError> {
        self.bytes().map(i8::from_le_bytes)
    }

    /// Reads a `bool`: 0 is `false`, anything else `true`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn bool(&mut self) -> Result<bool, DecodeError> {
        self.u8().map(|b| b != 0)
    }

    reader_numbers! {
        u16: u16_le, u16_be;
        i16: i16_le, i16_be;
        u32: u32_le, u32_be;
        i32: i32_le, i32_be;
        u64: u64_le, u64_be;
        i64: i64_le, i64_be;
        f32: f32_le, f32_be;
        f64: f64_le, f64_be;
    }

    /// Ends reading: the whole input must have been read.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] with `expected` the bytes read and `actual` the input's
    /// length if bytes remain.
    #[inline]
    pub fn finish(self) -> Result<(), DecodeError> {
        if self.rest.is_empty() {
            Ok(())
        } else {
            Err(DecodeError::PayloadLength {
                expected: self.position(),
                actual: self.total,
            })
        }
    }
}

/// A cursor that writes values at the front of a byte buffer.
///
/// Every write either writes the whole value and advances, or returns
/// [`EncodeError::BufferTooSmall`] and leaves the cursor where it was.
///
/// ```
/// use protocol_runtime::{EncodeError, Writer};
///
/// let mut buf = [0u8; 4];
/// let mut w = Writer::new(&mut buf);
/// w.put_i16_le(-2)?;
/// w.zeros(1)?;
/// assert_eq!(w.put_u16_le(1), Err(EncodeError::BufferTooSmall { needed: 5, available: 4 }));
/// assert_eq!(w.written(), [0xFE, 0xFF, 0x00]);
/// # Ok::<(), EncodeError>(())
/// ```
#[derive(Debug)]
pub struct Writer<'a> {
    /// The whole output buffer.
    buf: &'a mut [u8],
    /// Bytes written so far; never more than `buf.len()`.
    pos: usize,
}

macro_rules! writer_numbers {
    ($($t:ident: $le:ident, $be:ident;)*) => {$(
        #[doc = concat!("Writes a little-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`EncodeError::BufferTooSmall`] if too little room remains.
        #[inline]
        pub fn $le(&mut self, v: $t) -> Result<(), EncodeError> {
            self.put_array(v.to_le_bytes())
        }

        #[doc = concat!("Writes a big-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`EncodeError::BufferTooSmall`] if too little room remains.
        #[inline]
        pub fn $be(&mut self, v: $t) -> Result<(), EncodeError> {
            self.put_array(v.to_be_bytes())
        }
    )*};
}

impl<'a> Writer<'a> {
    /// A writer at the start of `buf`.
    #[inline]
    pub const fn new(buf: &'a mut [u8]) -> Self {
        Self { buf, pos: 0 }
    }

    /// Bytes written so far.
    #[inline]
    pub fn position(&self) -> usize {
        self.pos
    }

    /// Room left in the buffer.
    #[inline]
    pub fn remaining(&self) -> usize {
        self.buf.len().saturating_sub(self.pos)
    }

    /// The bytes written so far.
    #[inline]
    pub fn written(&self) -> &[u8] {
        self.buf.get(..self.pos).unwrap_or_default()
    }

    #[cold]
    fn too_small(&self, n: usize) -> EncodeError {
        EncodeError::BufferTooSmall {
            needed: self.pos.saturating_add(n),
            available: self.buf.len(),
        }
    }

    /// Writes an array of `N` bytes.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if fewer than `N` bytes of room remain.
    #[inline]
    pub fn put_array<const N: usize>(&mut self, bytes: [u8; N]) -> Result<(), EncodeError> {
        match self
            .buf
            .get_mut(self.pos..)
            .and_then(<[u8]>::first_chunk_mut::<N>)
        {
            Some(dst) => {
                *dst = bytes;
                // The chunk exists, so `pos + N <= buf.len()`.
                self.pos = self.pos.wrapping_add(N);
                Ok(())
            }
            None => Err(self.too_small(N)),
        }
    }

    /// Writes a run of bytes.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if too little room remains; nothing is written then.
    #[inline]
    pub fn put_bytes(&mut self, b: &[u8]) -> Result<(), EncodeError> {
        let dst = self
            .pos
            .checked_add(b.len())
            .and_then(|end| self.buf.get_mut(self.pos..end));
        match dst {
            Some(dst) => {
                dst.copy_from_slice(b);
                self.pos = self.pos.wrapping_add(b.len());
                Ok(())
            }
            None => Err(self.too_small(b.len())),
        }
    }

    /// Writes `n` zero bytes (padding, reserved bytes).
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if too little room remains; nothing is written then.
    #[inline]
    pub fn zeros(&mut self, n: usize) -> Result<(), EncodeError> {
        let dst = self
            .pos
            .checked_add(n)
            .and_then(|end| self.buf.get_mut(self.pos..end));
        match dst {
            Some(dst) => {
                dst.fill(0);
                self.pos = self.pos.wrapping_add(n);
                Ok(())
            }
            None => Err(self.too_small(n)),
        }
    }

    /// Writes a `u8`.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the buffer is full.
    #[inline]
    pub fn put_u8(&mut self, v: u8) -> Result<(), EncodeError> {
        self.put_array([v])
    }

    /// Writes an `i8`.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the buffer is full.
    #[inline]
    pub fn put_i8(&mut self, v: i8) -> Result<(), EncodeError> {
        self.put_array(v.to_le_bytes())
    }

    /// Writes a `bool` as 1 or 0.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the buffer is full.
    #[inline]
    pub fn put_bool(&mut self, v: bool) -> Result<(), EncodeError> {
        self.put_array([u8::from(v)])
    }

    writer_numbers! {
        u16: put_u16_le, put_u16_be;
        i16: put_i16_le, put_i16_be;
        u32: put_u32_le, put_u32_be;
        i32: put_i32_le, put_i32_be;
        u64: put_u64_le, put_u64_be;
        i64: put_i64_le, put_i64_be;
        f32: put_f32_le, put_f32_be;
        f64: put_f64_le, put_f64_be;
    }
}

/// The `N` bytes at `offset`, if they exist.
#[inline(always)]
fn chunk_at<const N: usize>(bytes: &[u8], offset: usize) -> Option<[u8; N]> {
    bytes.get(offset..)?.first_chunk::<N>().copied()
}

/// Reads an unsigned word of `size` bytes (1 to 8) at `offset`.
///
/// Returns `None` if the word does not lie inside `bytes` or `size` is not in `1..=8`.
///
/// ```
/// use protocol_runtime::layout::ByteOrder;
/// use protocol_runtime::wire::read_uint;
///
/// let bytes = [0x00, 0x12, 0x34, 0x56];
/// assert_eq!(read_uint(&bytes, 1, 2, ByteOrder::Big), Some(0x1234));
/// assert_eq!(read_uint(&bytes, 1, 3, ByteOrder::Little), Some(0x56_3412));
/// assert_eq!(read_uint(&bytes, 3, 2, ByteOrder::Big), None);
/// ```
#[inline]
pub fn read_uint(bytes: &[u8], offset: usize, size: u8, order: ByteOrder) -> Option<u64> {
    // One fixed-size load per common size: no byte loop, no call to memcpy.
    match (size, order) {
        (1, _) => bytes.get(offset).map(|&b| u64::from(b)),
        (2, ByteOrder::Little) => chunk_at(bytes, offset).map(|w| u64::from(u16::from_le_bytes(w))),
        (2, ByteOrder::Big) => chunk_at(bytes, offset).map(|w| u64::from(u16::from_be_bytes(w))),
        (4, ByteOrder::Little) => chunk_at(bytes, offset).map(|w| u64::from(u32::from_le_bytes(w))),
        (4, ByteOrder::Big) => chunk_at(bytes, offset).map(|w| u64::from(u32::from_be_bytes(w))),
        (8, ByteOrder::Little) => chunk_at(bytes, offset).map(u64::from_le_bytes),
        (8, ByteOrder::Big) => chunk_at(bytes, offset).map(u64::from_be_bytes),
        (3 | 5 | 6 | 7, _) => {
            let word = bytes.get(offset..offset.checked_add(usize::from(size))?)?;
            let push = |acc: u64, b: &u8| (acc << 8) | u64::from(*b);
            Some(match order {
                ByteOrder::Little => word.iter().rev().fold(0, push),
                ByteOrder::Big => word.iter().fold(0, push),
            })
        }
        _ => None,
    }
}

/// Writes `value` as an unsigned word of `size` bytes (1 to 8) at `offset`.
///
/// Returns `None`, writing nothing, if the word does not lie inside `bytes`, `size` is not in
/// `1..=8` or `value` does not fit in `size` bytes.
///
/// ```
/// use protocol_runtime::layout::ByteOrder;
/// use protocol_runtime::wire::write_uint;
///
/// let mut bytes = [0u8; 3];
/// assert_eq!(write_uint(&mut bytes, 1, 2, ByteOrder::Little, 0x1234), Some(()));
/// assert_eq!(bytes, [0x00, 0x34, 0x12]);
/// assert_eq!(write_uint(&mut bytes, 0, 1, ByteOrder::Big, 0x100), None);
/// ```
#[inline]
pub fn write_uint(
    bytes: &mut [u8],
    offset: usize,
    size: u8,
    order: ByteOrder,
    value: u64,
) -> Option<()> {
    if size == 0 || size > 8 {
        return None;
    }
    // A shift by 64 (an 8-byte word) is `None`: every value fits.
    if value
        .checked_shr(u32::from(size).wrapping_mul(8))
        .unwrap_or(0)
        != 0
    {
        return None;
    }
    let word = bytes.get_mut(offset..offset.checked_add(usize::from(size))?)?;
    match order {
        ByteOrder::Little => word
            .iter_mut()
            .zip(value.to_le_bytes())
            .for_each(|(d, s)| *d = s),
        ByteOrder::Big => {
            word.iter_mut()
                .rev()
                .zip(value.to_be_bytes().into_iter().rev())
                .for_each(|(d, s)| *d = s);
        }
    }
    Some(())
}

impl WordField {
    /// Whether the field is well formed: `size` in `1..=8`, `width >= 1` and the bits
    /// `shift..shift + width` inside the word. Reads and writes of a malformed field return
    /// `None`.
    #[inline]
    pub const fn is_valid(&self) -> bool {
        let bits = (self.size as u32).wrapping_mul(8);
        let top = (self.shift as u32).wrapping_add(self.width as u32);
        self.size >= 1 && self.size <= 8 && self.width >= 1 && top <= bits
    }

    /// The largest value the field holds: `2^width - 1`.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// let len = WordField { at: Pos::Start(1), size: 2, order: ByteOrder::Little, shift: 0, width: 10 };
    /// assert_eq!(len.max_value(), 1023);
    /// ```
    #[inline]
    pub const fn max_value(&self) -> u64 {
        if self.width == 0 {
            0
        } else if self.width >= 64 {
            u64::MAX
        } else {
            u64::MAX.wrapping_shr(64u32.wrapping_sub(self.width as u32))
        }
    }

    /// Reads the field from `frame`: resolves `at` against `frame.len()`, reads the word and
    /// extracts bits `shift..shift + width`.
    ///
    /// Returns `None` if the word lies outside `frame` or the field is malformed.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// // A 10-bit length and a 6-bit version sharing a little-endian u16.
    /// let len = WordField { at: Pos::Start(1), size: 2, order: ByteOrder::Little, shift: 0, width: 10 };
    /// let ver = WordField { shift: 10, width: 6, ..len };
    /// let frame = [0xAA, 0x2C, 0x0C];
    /// assert_eq!(len.read(&frame), Some(0x02C));
    /// assert_eq!(ver.read(&frame), Some(3));
    /// ```
    #[inline]
    pub fn read(&self, frame: &[u8]) -> Option<u64> {
        if !self.is_valid() {
            return None;
        }
        let offset = self.at.resolve(frame.len())?;
        let word = read_uint(frame, offset, self.size, self.order)?;
        Some(word.checked_shr(u32::from(self.shift))? & self.max_value())
    }

    /// Writes `value` into the field's bits of `frame`, keeping the word's other bits.
    ///
    /// Returns `None`, writing nothing, if the word lies outside `frame`, the field is malformed
    /// or `value` does not fit in `width` bits.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// let ver = WordField { at: Pos::Start(0), size: 2, order: ByteOrder::Little, shift: 10, width: 6 };
    /// let mut frame = [0xFF, 0x03];
    /// assert_eq!(ver.write(&mut frame, 5), Some(()));
    /// assert_eq!(frame, [0xFF, 0x17]);
    /// assert_eq!(ver.write(&mut frame, 64), None);
    /// ```
    #[inline]
    pub fn write(&self, frame: &mut [u8], value: u64) -> Option<()> {
        if !self.is_valid() || value > self.max_value() {
            return None;
        }
        let offset = self.at.resolve(frame.len())?;
        let word = read_uint(frame, offset, self.size, self.order)?;
        let shift = u32::from(self.shift);
        let mask = self.max_value().checked_shl(shift)?;
        let word = (word & !mask) | value.checked_shl(shift)?;
        write_uint(frame, offset, self.size, self.order, word)
    }
}

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::layout::Pos;

    #[test]
    fn every_number_round_trips_in_both_orders() {
        let mut buf = [0u8; 2 * (2 + 2 + 4 + 4 + 8 + 8 + 4 + 8) + 3];
        let mut w = Writer::new(&mut buf);
        w.put_u8(0xAB).unwrap();
        w.put_i8(-5).unwrap();
        w.put_bool(true).unwrap();
        w.put_u16_le(0x1234).unwrap();
        w.put_u16_be(0x1234).unwrap();
        w.put_i16_le(-2).unwrap();
        w.put_i16_be(-2).unwrap();
        w.put_u32_le(0xDEAD_BEEF).unwrap();
        w.put_u32_be(0xDEAD_BEEF).unwrap();
        w.put_i32_le(-7).unwrap();
        w.put_i32_be(-7).unwrap();
        w.put_u64_le(0x0102_0304_0506_0708).unwrap();
        w.put_u64_be(0x0102_0304_0506_0708).unwrap();
        w.put_i64_le(i64::MIN).unwrap();
        w.put_i64_be(i64::MIN).unwrap();
        w.put_f32_le(-1.25).unwrap();
        w.put_f32_be(-1.25).unwrap();
        w.put_f64_le(core::f64::consts::PI).unwrap();
        w.put_f64_be(core::f64::consts::PI).unwrap();
        assert_eq!(w.remaining(), 0);
        assert_eq!(&buf[3..7], &[0x34, 0x12, 0x12, 0x34]);

        let mut r = Reader::new(&buf);
        assert_eq!(r.u8().unwrap(), 0xAB);
        assert_eq!(r.i8().unwrap(), -5);
        assert!(r.bool().unwrap());
        assert_eq!(r.u16_le().unwrap(), 0x1234);
        assert_eq!(r.u16_be().unwrap(), 0x1234);
        assert_eq!(r.i16_le().unwrap(), -2);
        assert_eq!(r.i16_be().unwrap(), -2);
        assert_eq!(r.u32_le().unwrap(), 0xDEAD_BEEF);
        assert_eq!(r.u32_be().unwrap(), 0xDEAD_BEEF);
        assert_eq!(r.i32_le().unwrap(), -7);
        assert_eq!(r.i32_be().unwrap(), -7);
        assert_eq!(r.u64_le().unwrap(), 0x0102_0304_0506_0708);
        assert_eq!(r.u64_be().unwrap(), 0x0102_0304_0506_0708);
        assert_eq!(r.i64_le().unwrap(), i64::MIN);
        assert_eq!(r.i64_be().unwrap(), i64::MIN);
        assert_eq!(r.f32_le().unwrap(), -1.25);
        assert_eq!(r.f32_be().unwrap(), -1.25);
        assert_eq!(r.f64_le().unwrap(), core::f64::consts::PI);
        assert_eq!(r.f64_be().unwrap(), core::f64::consts::PI);
        r.finish().unwrap();
    }

    #[test]
    fn short_reads_fail_without_advancing() {
        let mut r = Reader::new(&[1, 2, 3]);
        assert_eq!(
            r.u32_be(),
            Err(DecodeError::Truncated {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            r.take(4),
            Err(DecodeError::Truncated {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            r.skip(usize::MAX),
            Err(DecodeError::Truncated {
                needed: usize::MAX,
                available: 3
            })
        );
        assert_eq!(r.position(), 0);
        assert_eq!(r.take(2).unwrap(), &[1, 2]);
        assert_eq!(r.rest(), &[3]);
        assert_eq!(
            r.clone().finish(),
            Err(DecodeError::PayloadLength {
                expected: 2,
                actual: 3
            })
        );
        assert_eq!(r.bytes::<1>().unwrap(), [3]);
        assert_eq!(r.bytes::<0>().unwrap(), []);
        r.finish().unwrap();
    }

    #[test]
    fn short_writes_fail_without_writing() {
        let mut buf = [9u8; 3];
        let mut w = Writer::new(&mut buf);
        w.put_u8(1).unwrap();
        assert_eq!(
            w.put_u32_le(0),
            Err(EncodeError::BufferTooSmall {
                needed: 5,
                available: 3
            })
        );
        assert_eq!(
            w.put_bytes(&[0; 3]),
            Err(EncodeError::BufferTooSmall {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(
            w.zeros(usize::MAX),
            Err(EncodeError::BufferTooSmall {
                needed: usize::MAX,
                available: 3
            })
        );
        assert_eq!(w.position(), 1);
        w.put_bytes(&[7]).unwrap();
        w.zeros(1).unwrap();
        assert_eq!(
            w.put_bool(false),
            Err(EncodeError::BufferTooSmall {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(buf, [1, 7, 0]);
    }

    #[test]
    fn uints_of_every_size() {
        let bytes = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        assert_eq!(
            read_uint(&bytes, 0, 8, ByteOrder::Big),
            Some(0x0102_0304_0506_0708)
        );
        assert_eq!(
            read_uint(&bytes, 1, 8, ByteOrder::Little),
            Some(0x0908_0706_0504_0302)
        );
        assert_eq!(read_uint(&bytes, 2, 0, ByteOrder::Little), None);
        assert_eq!(read_uint(&bytes, 0, 9, ByteOrder::Little), None);
        assert_eq!(read_uint(&bytes, usize::MAX, 1, ByteOrder::Little), None);
        let mut out = [0u8; 9];
        for size in 1..=8u8 {
            let max = u64::MAX >> (64 - 8 * u32::from(size));
            for order in [ByteOrder::Little, ByteOrder::Big] {
                write_uint(&mut out, 1, size, order, max - 1).unwrap();
                assert_eq!(read_uint(&out, 1, size, order), Some(max - 1));
                if size < 8 {
                    assert_eq!(write_uint(&mut out, 1, size, order, max + 1), None);
                }
            }
        }
        assert_eq!(write_uint(&mut out, 8, 2, ByteOrder::Big, 0), None);
    }

    #[test]
    fn word_fields_narrow_to_their_bits() {
        let field = WordField {
            at: Pos::End(3),
            size: 2,
            order: ByteOrder::Big,
            shift: 4,
            width: 8,
        };
        let mut frame = [0u8, 0xA0, 0x0B, 0xFF];
        assert_eq!(field.read(&frame), Some(0x00));
        field.write(&mut frame, 0xCD).unwrap();
        assert_eq!(frame, [0, 0xAC, 0xDB, 0xFF]);
        assert_eq!(field.read(&frame), Some(0xCD));
        assert_eq!(field.write(&mut frame, 0x100), None);
        assert_eq!(field.read(&frame[..1]), None);
        let bad = WordField { shift: 9, ..field };
        assert!(!bad.is_valid());
        assert_eq!(bad.read(&frame), None);
        let full = WordField {
            at: Pos::Start(0),
            size: 8,
            order: ByteOrder::Little,
            shift: 0,
            width: 64,
        };
        assert_eq!(full.max_value(), u64::MAX);
        let mut eight = [0u8; 8];
        full.write(&mut eight, u64::MAX).unwrap();
        assert_eq!(full.read(&eight), Some(u64::MAX));
        assert_eq!(WordField { width: 0, ..full }.max_value(), 0);
    }
}
