//! Fixed-size text fields: a C `char[N]` (u-blox MON-VER's `swVersion`, MAVLink's
//! `param_id`), NUL-padded on the wire.
//!
//! A [`FixedStr`] holds the field's `N` bytes exactly as they were received, so decoding then
//! encoding gives the same bytes even when the text is not UTF-8 or bytes follow its first NUL
//! (a sender that reuses a buffer without clearing it). The text is the bytes before the first
//! NUL ([`FixedStr::text`]); [`FixedStr::as_str`] gives it as a `&str` when it is UTF-8.
//!
//! A [`NulStr`] is a NUL-terminated text of at most `N` bytes (CRSF's flight mode): on the wire
//! its bytes then one NUL, so its size varies and fields may follow it. Its text holds no NUL,
//! so the wire bytes are exactly the text and its terminator: they round-trip. Decoding
//! without a NUL within `N + 1` bytes is [`DecodeError::Unterminated`]; a text with a NUL or
//! longer than `N` bytes is no `NulStr` ([`NulStr::from_text`] gives `None`), so it cannot be
//! encoded, and is never cut.

use core::fmt;
use core::str::Utf8Error;

use crate::encoder::Payload;
use crate::error::{DecodeError, EncodeError};
use crate::wire::{Reader, Writer};

/// The text of a NUL-padded field's bytes: the bytes before the first NUL (all of them when
/// there is none).
pub fn text_of(bytes: &[u8]) -> &[u8] {
    bytes.split(|&b| b == 0).next().unwrap_or(bytes)
}

/// Whether a NUL-padded field's bytes are what [`pad_text`] makes of their text: UTF-8, and
/// only NUL bytes after it.
pub fn is_canonical(bytes: &[u8]) -> bool {
    let text = text_of(bytes);
    let rest = bytes.get(text.len()..).unwrap_or_default();
    core::str::from_utf8(text).is_ok() && rest.iter().all(|&b| b == 0)
}

/// Fills `out` with `text` followed by NUL bytes; `None` (and `out` untouched) when the text
/// is longer than `out`.
pub fn pad_text(text: &[u8], out: &mut [u8]) -> Option<()> {
    let (head, tail) = out.split_at_mut_checked(text.len())?;
    head.copy_from_slice(text);
    tail.fill(0);
    Some(())
}

/// `N` bytes of NUL-padded text, stored inline (no heap).
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct FixedStr<const N: usize> {
    bytes: [u8; N],
}

impl<const N: usize> FixedStr<N> {
    /// The empty text: `N` NUL bytes.
    pub const fn new() -> Self {
        Self { bytes: [0; N] }
    }

    /// `text` followed by NUL bytes up to `N`; `None` if it is longer than `N` bytes.
    ///
    /// A text of exactly `N` bytes fills the field with no NUL, as C senders do.
    pub fn from_text(text: &str) -> Option<Self> {
        Self::from_text_bytes(text.as_bytes())
    }

    /// [`from_text`](Self::from_text) of bytes that need not be UTF-8.
    pub fn from_text_bytes(text: &[u8]) -> Option<Self> {
        let mut bytes = [0; N];
        pad_text(text, &mut bytes)?;
        Some(Self { bytes })
    }

    /// All `N` bytes, as they are on the wire.
    pub const fn from_bytes(bytes: [u8; N]) -> Self {
        Self { bytes }
    }

    /// All `N` bytes, as they are on the wire (the NUL padding, and any bytes after it).
    pub const fn as_bytes(&self) -> &[u8; N] {
        &self.bytes
    }

    /// The text: the bytes before the first NUL (all of them when there is none).
    pub fn text(&self) -> &[u8] {
        text_of(&self.bytes)
    }

    /// The text as a `&str`.
    ///
    /// # Errors
    /// When the text is not UTF-8.
    pub fn as_str(&self) -> Result<&str, Utf8Error> {
        core::str::from_utf8(self.text())
    }

    /// Whether the bytes are what [`from_text`](Self::from_text) makes of the text: UTF-8, and
    /// only NUL bytes after its end. A value that is not canonical keeps its other bytes.
    pub fn is_canonical(&self) -> bool {
        is_canonical(&self.bytes)
    }
}

impl<const N: usize> Default for FixedStr<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> Payload for FixedStr<N> {
    const SIZE: usize = N;
    const READ_NEEDS_ONLY_BYTES: bool = true;

    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        w.put_array(self.bytes)
    }

    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        Ok(Self {
            bytes: r.bytes::<N>()?,
        })
    }
}

impl<const N: usize> fmt::Debug for FixedStr<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        TextDebug(&self.bytes).fmt(f)
    }
}

/// The `Debug` form of a NUL-padded text's bytes: the text, quoted (bytes that are not
/// printable ASCII as `\xNN`), then all the bytes when they are not canonical.
pub struct TextDebug<'a>(pub &'a [u8]);

impl fmt::Debug for TextDebug<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\"", text_of(self.0).escape_ascii())?;
        if !is_canonical(self.0) {
            write!(f, " (bytes {:?})", self.0)?;
        }
        Ok(())
    }
}

/// The text, invalid UTF-8 replaced by U+FFFD.
impl<const N: usize> fmt::Display for FixedStr<N> {
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

/// The text of a NUL-terminated field of at most `max` bytes at the reader's position: the
/// bytes before the first NUL, which the reader moves past (the NUL too).
///
/// # Errors
///
/// [`DecodeError::Unterminated`] when no NUL comes within `max + 1` bytes or before the input
/// ends (the reader does not move).
///
/// ```
/// use protocol_runtime::{DecodeError, Reader, text::read_nul_text};
/// let mut r = Reader::new(b"ACRO\0\x07");
/// assert_eq!(read_nul_text(&mut r, 4), Ok(&b"ACRO"[..]));
/// assert_eq!(r.position(), 5);
/// assert_eq!(read_nul_text(&mut Reader::new(b"ACRO\0"), 3), Err(DecodeError::Unterminated { place: protocol_runtime::error::Place::NONE }));
/// assert_eq!(read_nul_text(&mut Reader::new(b"AC"), 3), Err(DecodeError::Unterminated { place: protocol_runtime::error::Place::NONE }));
/// ```
#[inline]
pub fn read_nul_text<'a>(r: &mut Reader<'a>, max: usize) -> Result<&'a [u8], DecodeError> {
    let rest = r.rest();
    let window = rest.get(..max.saturating_add(1)).unwrap_or(rest);
    let len = window
        .iter()
        .position(|&b| b == 0)
        .ok_or(DecodeError::Unterminated {
            place: crate::error::Place::NONE,
        })?;
    let text = r.take(len)?;
    r.skip(1)?;
    Ok(text)
}

/// Whether `text` can be a NUL-terminated field of at most `max` bytes: no longer, and no
/// NUL in it (which would end it early on the wire).
///
/// ```
/// use protocol_runtime::text::nul_text_fits;
/// assert!(nul_text_fits(b"ANGLE", 5));
/// assert!(!nul_text_fits(b"ANGLE", 4));
/// assert!(!nul_text_fits(b"AN\0LE", 8));
/// ```
#[inline]
pub fn nul_text_fits(text: &[u8], max: usize) -> bool {
    text.len() <= max && !text.contains(&0)
}

/// A NUL-terminated text of at most `N` bytes (the NUL not counted), stored inline (no heap).
///
/// ```
/// use protocol_runtime::{Payload, Reader, text::NulStr};
/// let mode = NulStr::<16>::from_text("ANGLE").unwrap();
/// assert_eq!(mode.wire_len(), 6);
/// assert_eq!(NulStr::<4>::from_text("ANGLE"), None);
/// assert_eq!(NulStr::<16>::from_text("A\0B"), None);
/// assert_eq!(NulStr::<16>::read(&mut Reader::new(b"ANGLE\0")), Ok(mode));
/// ```
#[derive(Clone, Copy)]
pub struct NulStr<const N: usize> {
    len: usize,
    bytes: [u8; N],
}

impl<const N: usize> NulStr<N> {
    /// The empty text (on the wire, one NUL).
    pub const fn new() -> Self {
        Self {
            len: 0,
            bytes: [0; N],
        }
    }

    /// The text; `None` if it is longer than `N` bytes or holds a NUL.
    pub fn from_text(text: &str) -> Option<Self> {
        Self::from_text_bytes(text.as_bytes())
    }

    /// [`from_text`](Self::from_text) of bytes that need not be UTF-8.
    pub fn from_text_bytes(text: &[u8]) -> Option<Self> {
        if !nul_text_fits(text, N) {
            return None;
        }
        let mut out = Self::new();
        out.bytes.get_mut(..text.len())?.copy_from_slice(text);
        out.len = text.len();
        Some(out)
    }

    /// The text's bytes (without the NUL).
    pub fn text(&self) -> &[u8] {
        self.bytes.get(..self.len).unwrap_or_default()
    }

    /// The text as a `&str`.
    ///
    /// # Errors
    /// When the text is not UTF-8.
    pub fn as_str(&self) -> Result<&str, Utf8Error> {
        core::str::from_utf8(self.text())
    }
}

impl<const N: usize> Default for NulStr<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> PartialEq for NulStr<N> {
    fn eq(&self, other: &Self) -> bool {
        self.text() == other.text()
    }
}

impl<const N: usize> Eq for NulStr<N> {}

impl<const N: usize> core::hash::Hash for NulStr<N> {
    fn hash<H: core::hash::Hasher>(&self, state: &mut H) {
        self.text().hash(state);
    }
}

impl<const N: usize> Payload for NulStr<N> {
    const SIZE: usize = N.saturating_add(1);
    const MIN_SIZE: usize = 1;

    #[inline]
    fn wire_len(&self) -> usize {
        self.len.saturating_add(1)
    }

    fn write(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        w.put_bytes(self.text())?;
        w.put_u8(0)
    }

    fn read(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        let text = read_nul_text(r, N)?;
        Self::from_text_bytes(text).ok_or(DecodeError::Unterminated {
            place: crate::error::Place::NONE,
        })
    }
}

impl<const N: usize> fmt::Debug for NulStr<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "\"{}\"", self.text().escape_ascii())
    }
}

/// The text, invalid UTF-8 replaced by U+FFFD.
impl<const N: usize> fmt::Display for NulStr<N> {
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
    use super::*;

    #[test]
    fn text_is_padded_and_every_byte_round_trips() {
        let s = FixedStr::<8>::from_text("ROM").expect("fits");
        assert_eq!(s.as_bytes(), b"ROM\0\0\0\0\0");
        assert_eq!(s.as_str(), Ok("ROM"));
        assert!(s.is_canonical());
        assert_eq!(FixedStr::<2>::from_text("ROM"), None);
        // Bytes after the NUL and invalid UTF-8 are kept, never a panic.
        let raw = *b"A\xFF\0junk\0";
        let s = FixedStr::<8>::from_bytes(raw);
        assert!(s.as_str().is_err());
        assert!(!s.is_canonical());
        let mut buf = [0u8; 8];
        let mut w = Writer::new(&mut buf);
        s.write(&mut w).expect("room");
        assert_eq!(buf, raw);
        let mut r = Reader::new(&buf);
        assert_eq!(FixedStr::<8>::read(&mut r), Ok(s));
        // A text that fills the field has no NUL.
        let full = FixedStr::<3>::from_bytes(*b"abc");
        assert_eq!(full.as_str(), Ok("abc"));
    }

    #[test]
    fn nul_terminated_text_round_trips_its_bytes_and_refuses_what_it_cannot_hold() {
        // Invalid UTF-8 is kept; a text of exactly N bytes takes N + 1 on the wire.
        let s = NulStr::<3>::from_text_bytes(b"\xFFab").expect("fits");
        assert!(s.as_str().is_err());
        let mut buf = [0u8; 8];
        let mut w = Writer::new(&mut buf);
        s.write(&mut w).expect("room");
        assert_eq!(w.written(), b"\xFFab\0");
        let mut r = Reader::new(&buf[..5]);
        assert_eq!(NulStr::<3>::read(&mut r), Ok(s));
        assert_eq!(
            r.remaining(),
            1,
            "the byte after the NUL is the next field's"
        );
        // No NUL within N + 1 bytes, or none before the end: an error, the reader unmoved.
        let mut r = Reader::new(b"abcd\0");
        assert_eq!(
            NulStr::<3>::read(&mut r),
            Err(DecodeError::Unterminated {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(r.position(), 0);
        assert_eq!(
            NulStr::<8>::read(&mut Reader::new(b"ab")),
            Err(DecodeError::Unterminated {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            NulStr::<8>::read(&mut Reader::new(b"")),
            Err(DecodeError::Unterminated {
                place: crate::error::Place::NONE
            })
        );
        // The empty text is one NUL.
        assert_eq!(
            NulStr::<8>::read(&mut Reader::new(b"\0")),
            Ok(NulStr::new())
        );
        // Never truncated: too long or holding a NUL is no value.
        assert_eq!(NulStr::<2>::from_text("abc"), None);
        assert_eq!(NulStr::<8>::from_text("a\0"), None);
    }
}
