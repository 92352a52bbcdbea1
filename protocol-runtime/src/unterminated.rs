//! [`Str`]: text without a terminator, of variable length up to a fixed capacity, without a
//! heap. Its end is the payload's end (a log message's text, SBP's `MSG_LOG`) or the length
//! another field states, never a NUL: every byte is text, a NUL included.
//!
//! The bytes are kept as received, so decoding then encoding gives the same bytes even when
//! they are not UTF-8; [`Str::as_str`] gives the text when they are. It reads and writes as
//! [`Bytes`] does (the rules of where it ends are theirs).

use core::fmt;
use core::hash::{Hash, Hasher};
use core::str::Utf8Error;

use crate::bytes::Bytes;
use crate::encoder::Payload;
use crate::error::{DecodeError, EncodeError};
use crate::wire::{Reader, Writer};

/// A text of up to `N` bytes without a terminator, stored inline.
///
/// ```
/// use protocol_runtime::{Payload, Reader, Str};
/// let text = Str::<16>::from_text("GNSS fix").unwrap();
/// assert_eq!(text.wire_len(), 8);
/// assert_eq!(Str::<4>::from_text("GNSS fix"), None);
/// assert_eq!(Str::<16>::read(&mut Reader::new(b"GNSS fix")), Ok(text));
/// assert_eq!(text.as_str(), Ok("GNSS fix"));
/// ```
#[derive(Clone, Copy, Default, PartialEq, Eq)]
pub struct Str<const N: usize>(Bytes<N>);

impl<const N: usize> Str<N> {
    /// The empty text.
    pub const fn new() -> Self {
        Str(Bytes::new())
    }

    /// The text; `None` if it is longer than `N` bytes (a text is never cut).
    pub fn from_text(text: &str) -> Option<Self> {
        Self::from_text_bytes(text.as_bytes())
    }

    /// [`from_text`](Self::from_text) of bytes that need not be UTF-8.
    pub fn from_text_bytes(text: &[u8]) -> Option<Self> {
        Bytes::from_slice(text).map(Str)
    }

    /// The text's bytes.
    pub fn text(&self) -> &[u8] {
        self.0.as_slice()
    }

    /// The text as a `&str`.
    ///
    /// # Errors
    /// When the text is not UTF-8.
    pub fn as_str(&self) -> Result<&str, Utf8Error> {
        core::str::from_utf8(self.text())
    }

    /// Bytes of the text.
    pub fn len(&self) -> usize {
        self.text().len()
    }

    /// Whether the text is empty.
    pub fn is_empty(&self) -> bool {
        self.text().is_empty()
    }

    /// Reads every byte left in `r`.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if more than `N` bytes are left.
    pub fn read_rest(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Self::read_rest_but(r, 0)
    }

    /// Reads every byte left in `r` but the last `keep` ([`Bytes::read_rest_but`]).
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if more than `N + keep` bytes are left.
    pub fn read_rest_but(r: &mut Reader<'_>, keep: usize) -> Result<Self, DecodeError> {
        Bytes::read_rest_but(r, keep).map(Str)
    }

    /// Reads `len` bytes, the length another field states ([`Bytes::read_sized`]).
    ///
    /// # Errors
    ///
    /// [`DecodeError::Truncated`] if fewer than `len` bytes remain,
    /// [`DecodeError::SizeMismatch`] if `len` exceeds `N`.
    #[inline]
    pub fn read_sized(r: &mut Reader<'_>, len: u64) -> Result<Self, DecodeError> {
        Bytes::read_sized(r, len).map(Str)
    }

    /// Writes the text's bytes at the writer's position.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if the writer has too little room.
    pub fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        self.0.write(w)
    }
}

/// Every byte left: the text of a message whose payload is a text alone.
impl<const N: usize> Payload for Str<N> {
    const SIZE: usize = N;
    const MIN_SIZE: usize = 0;

    #[inline]
    fn wire_len(&self) -> usize {
        self.len()
    }

    #[inline]
    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        Str::write(self, w)
    }

    #[inline]
    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Self::read_rest(r)
    }
}

impl<const N: usize> Hash for Str<N> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.text().hash(state);
    }
}

impl<const N: usize> fmt::Debug for Str<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\"", self.text().escape_ascii())
    }
}

/// The text, invalid UTF-8 replaced by U+FFFD.
impl<const N: usize> fmt::Display for Str<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for chunk in self.text().utf8_chunks() {
            f.write_str(chunk.valid())?;
            if !chunk.invalid().is_empty() {
                f.write_str("\u{FFFD}")?;
            }
        }
        Ok(())
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
    extern crate std;
    use std::string::ToString;

    use super::*;

    #[test]
    fn every_byte_is_text_and_round_trips() {
        // A NUL and invalid UTF-8 are text like any byte.
        let raw = b"ok\0\xFFend";
        let mut r = Reader::new(raw);
        let s = Str::<8>::read(&mut r).expect("fits");
        assert_eq!(r.remaining(), 0);
        assert_eq!(s.text(), raw);
        assert!(s.as_str().is_err());
        assert_eq!(s.to_string(), "ok\0\u{FFFD}end");
        let mut buf = [0u8; 8];
        let mut w = Writer::new(&mut buf);
        s.write(&mut w).expect("room");
        assert_eq!(w.written(), raw);
        // The checks after it keep their bytes; too long is the payload's wrong length.
        let mut r = Reader::new(b"abc\x01\x02");
        assert_eq!(Str::<8>::read_rest_but(&mut r, 2).map(|s| s.len()), Ok(3));
        assert_eq!(r.remaining(), 2);
        assert_eq!(
            Str::<2>::read(&mut Reader::new(b"abc")),
            Err(DecodeError::PayloadLength {
                expected: 2,
                actual: 3
            })
        );
        assert_eq!(Str::<2>::from_text("abc"), None);
        assert!(Str::<2>::new().is_empty());
    }
}
