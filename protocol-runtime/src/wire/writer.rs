//! [`Writer`]: the cursor that writes a payload's values into a caller's buffer.

use crate::error::EncodeError;

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

    /// Writes an inverted `bool` (a spec's `invert = true`): `true` as 0, `false` as 1.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the buffer is full.
    ///
    /// ```
    /// use protocol_runtime::Writer;
    /// let mut buf = [9u8; 2];
    /// let mut w = Writer::new(&mut buf);
    /// w.put_bool_inverted(true)?;
    /// w.put_bool_inverted(false)?;
    /// assert_eq!(buf, [0, 1]);
    /// # Ok::<(), protocol_runtime::EncodeError>(())
    /// ```
    #[inline]
    pub fn put_bool_inverted(&mut self, v: bool) -> Result<(), EncodeError> {
        self.put_array([u8::from(!v)])
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
