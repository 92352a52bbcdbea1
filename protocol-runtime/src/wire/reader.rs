//! [`Reader`]: the cursor that reads a payload's values from the front of a byte slice.

use crate::error::DecodeError;

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

// The reads match their results rather than `map` them: unoptimised (cargo's default `dev`
// profile), each `map` with its closure is a function of `core` per type read, linked into
// every firmware; a `match` is a few instructions in the read itself.
macro_rules! reader_numbers {
    ($($t:ident: $le:ident, $be:ident;)*) => {$(
        #[doc = concat!("Reads a little-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`DecodeError::Truncated`] if too few bytes remain.
        #[inline]
        pub fn $le(&mut self) -> Result<$t, DecodeError> {
            match self.bytes() {
                Ok(b) => Ok($t::from_le_bytes(b)),
                Err(e) => Err(e),
            }
        }

        #[doc = concat!("Reads a big-endian `", stringify!($t), "`.")]
        ///
        /// # Errors
        ///
        /// [`DecodeError::Truncated`] if too few bytes remain.
        #[inline]
        pub fn $be(&mut self) -> Result<$t, DecodeError> {
            match self.bytes() {
                Ok(b) => Ok($t::from_be_bytes(b)),
                Err(e) => Err(e),
            }
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
        match self.take(n) {
            Ok(_) => Ok(()),
            Err(e) => Err(e),
        }
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
    #[cfg_attr(not(protocol_opt0), inline(always))]
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
        match self.take(n) {
            Ok(_) => Ok(self),
            Err(e) => Err(e),
        }
    }

    /// Reads a `u8`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn u8(&mut self) -> Result<u8, DecodeError> {
        match self.bytes() {
            Ok(b) => Ok(u8::from_le_bytes(b)),
            Err(e) => Err(e),
        }
    }

    /// Reads an `i8`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn i8(&mut self) -> Result<i8, DecodeError> {
        match self.bytes() {
            Ok(b) => Ok(i8::from_le_bytes(b)),
            Err(e) => Err(e),
        }
    }

    /// Reads a `bool`: 0 is `false`, anything else `true`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    #[inline]
    pub fn bool(&mut self) -> Result<bool, DecodeError> {
        match self.u8() {
            Ok(b) => Ok(b != 0),
            Err(e) => Err(e),
        }
    }

    /// Reads an inverted `bool` (a spec's `invert = true`, an active-low flag): 0 is `true`,
    /// anything else `false`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if no byte remains.
    ///
    /// ```
    /// use protocol_runtime::Reader;
    /// assert_eq!(Reader::new(&[0]).bool_inverted(), Ok(true));
    /// assert_eq!(Reader::new(&[7]).bool_inverted(), Ok(false));
    /// ```
    #[inline]
    pub fn bool_inverted(&mut self) -> Result<bool, DecodeError> {
        match self.u8() {
            Ok(b) => Ok(b == 0),
            Err(e) => Err(e),
        }
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
