//! [`Bytes`]: a run of raw bytes of variable length up to a fixed capacity, without a heap. A
//! payload struct may end with one (user data of a RoboMaster interactive frame, the data of an
//! echo command): it takes every byte left in the payload.

use core::fmt;
use core::hash::{Hash, Hasher};
use core::ops::Deref;

use crate::encoder::Payload;
use crate::error::{DecodeError, EncodeError};
use crate::wire::{Reader, Writer};

/// Up to `N` bytes, stored inline.
#[derive(Clone, Copy)]
pub struct Bytes<const N: usize> {
    len: usize,
    buf: [u8; N],
}

impl<const N: usize> Bytes<N> {
    /// No bytes.
    pub const fn new() -> Self {
        Bytes {
            len: 0,
            buf: [0; N],
        }
    }

    /// A copy of `bytes`, or `None` if it holds more than `N`.
    pub fn from_slice(bytes: &[u8]) -> Option<Self> {
        let mut out = Self::new();
        out.buf.get_mut(..bytes.len())?.copy_from_slice(bytes);
        out.len = bytes.len();
        Some(out)
    }

    /// The bytes.
    pub fn as_slice(&self) -> &[u8] {
        self.buf.get(..self.len).unwrap_or(&[])
    }

    /// The capacity `N`.
    pub const fn capacity(&self) -> usize {
        N
    }

    /// Reads every byte left in `r`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if more than `N` bytes are left (`expected` is then the
    /// reader's position plus `N`).
    pub fn read_rest(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Self::read_rest_but(r, 0)
    }

    /// Reads every byte left in `r` but the last `keep` (the checks after the field:
    /// [`crate::field::rest_but`]).
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if more than `N + keep` bytes are left (`expected` is
    /// then the reader's position plus `N + keep`).
    pub fn read_rest_but(r: &mut Reader<'_>, keep: usize) -> Result<Self, DecodeError> {
        let start = r.position();
        let rest = crate::field::rest_but(r, keep);
        let out = Self::from_slice(rest).ok_or(DecodeError::PayloadLength {
            expected: start.saturating_add(N).saturating_add(keep),
            actual: start.saturating_add(r.remaining()),
        })?;
        r.skip(rest.len())?;
        Ok(out)
    }

    /// Reads `len` bytes, the length another field states ([`crate::field::take_sized`]).
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `len` bytes remain,
    /// [`DecodeError::SizeMismatch`] if `len` exceeds `N`.
    #[inline]
    pub fn read_sized(r: &mut Reader<'_>, len: u64) -> Result<Self, DecodeError> {
        Self::from_slice(crate::field::take_sized(r, len, N)?).ok_or(DecodeError::SizeMismatch {
            place: crate::error::Place::NONE,
        })
    }

    /// Writes the bytes at the writer's position.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the writer has too little room.
    pub fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        w.put_bytes(self.as_slice())
    }
}

/// Every byte left: the data of an acknowledgement, as a message's payload.
impl<const N: usize> Payload for Bytes<N> {
    const SIZE: usize = N;
    const MIN_SIZE: usize = 0;

    #[inline]
    fn wire_len(&self) -> usize {
        self.len
    }

    #[inline]
    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        Bytes::write(self, w)
    }

    #[inline]
    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Self::read_rest(r)
    }
}

impl<const N: usize> Default for Bytes<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Deref for Bytes<N> {
    type Target = [u8];
    fn deref(&self) -> &[u8] {
        self.as_slice()
    }
}

impl<const N: usize> PartialEq for Bytes<N> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<const N: usize> Eq for Bytes<N> {}

impl<const N: usize> Hash for Bytes<N> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.as_slice().hash(state);
    }
}

impl<const N: usize> fmt::Debug for Bytes<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Bytes(")?;
        for b in self.as_slice() {
            write!(f, "{b:02x}")?;
        }
        write!(f, ")")
    }
}

impl<const N: usize> TryFrom<&[u8]> for Bytes<N> {
    type Error = EncodeError;
    fn try_from(bytes: &[u8]) -> Result<Self, EncodeError> {
        Self::from_slice(bytes).ok_or(EncodeError::PayloadTooLarge {
            len: bytes.len(),
            max: N,
        })
    }
}

#[cfg(test)]
// Tests may index and unwrap: a panic there is a failed test, not a runtime fault.
#[allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_rest_and_refuses_too_many() {
        let data = [1u8, 2, 3, 4];
        let mut r = Reader::new(&data);
        assert_eq!(r.u8(), Ok(1));
        let b = Bytes::<4>::read_rest(&mut r).expect("fits");
        assert_eq!(b.as_slice(), &[2, 3, 4]);
        assert_eq!(r.remaining(), 0);
        let mut r = Reader::new(&data);
        assert_eq!(
            Bytes::<3>::read_rest(&mut r),
            Err(DecodeError::PayloadLength {
                expected: 3,
                actual: 4
            })
        );
        let mut out = [0u8; 3];
        let mut w = Writer::new(&mut out);
        b.write(&mut w).expect("room");
        assert_eq!(out, [2, 3, 4]);
        assert_eq!(
            Bytes::<2>::try_from(&data[..]),
            Err(EncodeError::PayloadTooLarge { len: 4, max: 2 })
        );
    }
}
