//! Cursors over payload bytes ([`Reader`], [`Writer`]) and words at fixed positions of a frame
//! ([`read_uint`], [`write_uint`], [`WordField`](crate::layout::WordField)).
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

mod int24;
mod word;

pub use int24::{fit_i24, fit_u24};
pub use word::{read_uint, write_uint};

use crate::error::{DecodeError, EncodeError};

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

    /// Reads an array of `N` elements, each with `read`, in order (the read of an array
    /// field: `r.array(|r| r.u16_le())?`).
    ///
    /// ```
    /// use protocol_runtime::{DecodeError, Reader};
    ///
    /// let mut r = Reader::new(&[1, 0, 2, 0, 3]);
    /// assert_eq!(r.array(|r| r.u16_le()), Ok([1u16, 2]));
    /// assert_eq!(r.array::<u16, 1>(|r| r.u16_le()), Err(DecodeError::Truncated { needed: 6, available: 5 }));
    /// ```
    ///
    /// # Errors
    ///
    /// The first error of `read`.
    #[inline(always)]
    pub fn array<T: Copy + Default, const N: usize>(
        &mut self,
        mut read: impl FnMut(&mut Self) -> Result<T, DecodeError>,
    ) -> Result<[T; N], DecodeError> {
        let mut a = [T::default(); N];
        for e in a.iter_mut() {
            *e = read(self)?;
        }
        Ok(a)
    }

    /// Skips `n` bytes of padding and gives the reader back for the read of the field after
    /// them: `r.pad(3)?.u32_le()?`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `n` bytes remain.
    #[inline]
    pub fn pad(&mut self, n: usize) -> Result<&mut Self, DecodeError> {
        self.skip(n).map(|()| self)
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

    /// A writer over the next `n` bytes, which this one moves past: the room for a value of
    /// known size checked once, so that the writes into it (at constant offsets of a buffer of
    /// constant length, once inlined) need no check of their own.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if fewer than `n` bytes remain (nothing moves).
    ///
    /// ```
    /// use protocol_runtime::{EncodeError, Writer};
    ///
    /// let mut buf = [0u8; 6];
    /// let mut w = Writer::new(&mut buf);
    /// w.reserve(4)?.put_u32_be(0x0102_0304)?;
    /// assert_eq!(w.reserve(4).err(), Some(EncodeError::BufferTooSmall { needed: 8, available: 6 }));
    /// w.put_u16_le(5)?;
    /// assert_eq!(w.written(), [1, 2, 3, 4, 5, 0]);
    /// # Ok::<(), EncodeError>(())
    /// ```
    #[inline]
    pub fn reserve(&mut self, n: usize) -> Result<Writer<'_>, EncodeError> {
        let start = self.pos;
        let Some(end) = start.checked_add(n).filter(|&end| end <= self.buf.len()) else {
            return Err(self.too_small(n));
        };
        self.pos = end;
        // In bounds: checked above.
        Ok(Writer::new(
            self.buf.get_mut(start..end).unwrap_or_default(),
        ))
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

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::unwrap_used)]
mod tests {
    use super::*;

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
}
