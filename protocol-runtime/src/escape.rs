//! Byte escaping of whole frames, as HDLC, PPP, SLIP and Sensirion SHDLC do it: every frame
//! opens and closes with a flag byte, and between the flags each reserved byte (the flag, the
//! escape byte, and whatever else the link reserves) is sent as the escape byte followed by a
//! substitute.
//!
//! This module owns the rule as data ([`Escape`]) and its three uses on whole frames: the
//! escaped length, escaping in place after a frame is sealed, and unescaping one frame into a
//! caller's buffer. The stream engine unescapes byte by byte with [`Escape::original`]
//! (`decoder/escaped.rs`). The [`FrameLayout`] of an escaped format
//! describes the frame unescaped (its sync and its end marker are the flag), so lengths and
//! checks count and cover the bytes before escaping, as HDLC's FCS does.
//!
//! Both the XOR form (HDLC: `7D`, then the byte XOR `0x20`) and a table (SLIP: `C0` as
//! `DB DC`, `DB` as `DB DD`) are a table of pairs here: the front end lowers the XOR form
//! to its pairs, so one rule serves both.

use crate::decoder::Reject;
use crate::error::{DecodeError, EncodeError};
use crate::layout::FrameLayout;

/// The escaping of a frame format.
///
/// ```
/// use protocol_runtime::escape::Escape;
///
/// // Sensirion SHDLC: 7E, 7D, 11 and 13 go as 7D and the byte XOR 0x20.
/// let shdlc = Escape { flag: 0x7E, escape: 0x7D, pairs: &[[0x7E, 0x5E], [0x7D, 0x5D], [0x11, 0x31], [0x13, 0x33]] };
/// let mut buf = [0x7E, 0x00, 0x7E, 0x11, 0x42, 0x7E, 0, 0];
/// assert_eq!(shdlc.escape_in_place(&mut buf, 6), Ok(8));
/// assert_eq!(buf, [0x7E, 0x00, 0x7D, 0x5E, 0x7D, 0x31, 0x42, 0x7E]);
/// let mut frame = [0u8; 8];
/// assert_eq!(shdlc.unescape(&buf, &mut frame), Ok(6));
/// assert_eq!(frame[..6], [0x7E, 0x00, 0x7E, 0x11, 0x42, 0x7E]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Escape<'a> {
    /// The byte that opens and closes every frame (HDLC `7E`, SLIP `C0`).
    pub flag: u8,
    /// The byte that announces a substitute (HDLC `7D`, SLIP `DB`).
    pub escape: u8,
    /// Each reserved byte and the substitute sent after the escape byte in its place. The
    /// reserved bytes include the flag and the escape byte; the substitutes are distinct and
    /// none is the flag (the front end checks both).
    pub pairs: &'a [[u8; 2]],
}

impl Escape<'_> {
    /// The substitute `byte` is sent as after the escape byte, if it is reserved.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn substitute(&self, byte: u8) -> Option<u8> {
        self.pairs
            .iter()
            .find(|[reserved, _]| *reserved == byte)
            .map(|[_, sub]| *sub)
    }

    /// The byte that `substitute`, received after the escape byte, stands for; `None` if it
    /// is no substitute (the frame is damaged).
    #[cfg_attr(not(protocol_opt0), inline(always))]
    #[must_use]
    pub fn original(&self, substitute: u8) -> Option<u8> {
        self.pairs
            .iter()
            .find(|[_, sub]| *sub == substitute)
            .map(|[reserved, _]| *reserved)
    }

    /// The length on the wire of the unescaped `frame` (its first and last bytes the flags,
    /// which are sent as they are).
    #[must_use]
    pub fn escaped_len(&self, frame: &[u8]) -> usize {
        let inner = frame
            .get(1..frame.len().saturating_sub(1))
            .unwrap_or_default();
        let reserved = inner
            .iter()
            .filter(|b| self.substitute(**b).is_some())
            .count();
        frame.len().saturating_add(reserved)
    }

    /// Escapes the frame `buf[..len]` in place (its first and last bytes, the flags, stay as
    /// they are; every reserved byte between them becomes the escape byte and its substitute),
    /// moving the bytes towards the end of `buf` from the back, so each moves once. Returns
    /// the escaped length.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `len` or than the escaped
    /// frame; `buf` is then unchanged.
    pub fn escape_in_place(&self, buf: &mut [u8], len: usize) -> Result<usize, EncodeError> {
        let available = buf.len();
        let frame = buf.get(..len).ok_or(EncodeError::BufferTooSmall {
            needed: len,
            available,
        })?;
        let total = self.escaped_len(frame);
        if total > available {
            return Err(EncodeError::BufferTooSmall {
                needed: total,
                available,
            });
        }
        if len < 2 {
            return Ok(len);
        }
        // `w` is where the last byte written from the back went; it never falls below the
        // byte being read, so no byte is overwritten before it is read.
        let mut w = total.saturating_sub(1);
        for i in (1..len.saturating_sub(1)).rev() {
            let byte = buf.get(i).copied().unwrap_or_default();
            w = w.saturating_sub(1);
            match self.substitute(byte) {
                Some(sub) => {
                    set(buf, w, sub);
                    w = w.saturating_sub(1);
                    set(buf, w, self.escape);
                }
                None => set(buf, w, byte),
            }
        }
        set(buf, total.saturating_sub(1), self.flag);
        Ok(total)
    }

    /// Unescapes the frame at the start of `wire` (from its opening flag to the next flag;
    /// the bytes after are ignored) into `out`; returns the unescaped length, flags included:
    /// the bytes [`FrameLayout::parse`] takes.
    ///
    /// # Errors
    ///
    /// [`DecodeError::Frame`] with [`Reject::BadHeader`] if `wire` does not open with the
    /// flag, [`Reject::BadEscape`] if an escape byte is not followed by a substitute,
    /// [`Reject::BadLength`] if `out` is too short; [`DecodeError::Truncated`] if no flag
    /// closes the frame.
    pub fn unescape(&self, wire: &[u8], out: &mut [u8]) -> Result<usize, DecodeError> {
        let Some((&first, inner)) = wire.split_first() else {
            return Err(DecodeError::Truncated {
                needed: 1,
                available: 0,
            });
        };
        if first != self.flag {
            return Err(DecodeError::Frame(Reject::BadHeader));
        }
        let mut n = 0usize;
        let mut push = |byte: u8| -> Result<(), DecodeError> {
            let slot = out
                .get_mut(n)
                .ok_or(DecodeError::Frame(Reject::BadLength))?;
            *slot = byte;
            n = n.saturating_add(1);
            Ok(())
        };
        push(self.flag)?;
        let mut escaped = false;
        for &byte in inner {
            if byte == self.flag {
                if escaped {
                    return Err(DecodeError::Frame(Reject::BadEscape));
                }
                push(self.flag)?;
                return Ok(n);
            }
            if escaped {
                let original = self.original(byte);
                push(original.ok_or(DecodeError::Frame(Reject::BadEscape))?)?;
                escaped = false;
            } else if byte == self.escape {
                escaped = true;
            } else {
                push(byte)?;
            }
        }
        Err(DecodeError::Truncated {
            needed: wire.len().saturating_add(1),
            available: wire.len(),
        })
    }
}

impl FrameLayout<'_> {
    /// [`parse`](Self::parse) for bytes as they are on the wire: a format that escapes its
    /// frames ([`escape`](Self::escape)) has the frame at the start of `wire` unescaped into
    /// `out` first (a buffer of [`max_len`](Self::max_len) bytes holds every frame); any other
    /// is parsed as it is and copied there. Returns the frame, in `out`.
    ///
    /// # Errors
    ///
    /// The errors of [`Escape::unescape`] and of [`parse`](Self::parse);
    /// [`DecodeError::Frame`] with [`Reject::BadLength`] if `out` is too short.
    pub fn parse_wire<'o>(&self, wire: &[u8], out: &'o mut [u8]) -> Result<&'o [u8], DecodeError> {
        let len = match self.escape {
            Some(escape) => escape.unescape(wire, out)?,
            None => {
                let frame = self.parse(wire)?;
                let dst = out
                    .get_mut(..frame.len())
                    .ok_or(DecodeError::Frame(Reject::BadLength))?;
                dst.copy_from_slice(frame);
                frame.len()
            }
        };
        let frame = out.get(..len).unwrap_or_default();
        self.parse(frame)
    }
}

/// Writes `byte` at `at` if `buf` reaches it (the callers have checked that it does).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn set(buf: &mut [u8], at: usize, byte: u8) {
    if let Some(slot) = buf.get_mut(at) {
        *slot = byte;
    }
}

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]
mod tests {
    use super::*;

    const SLIP: Escape<'static> = Escape {
        flag: 0xC0,
        escape: 0xDB,
        pairs: &[[0xC0, 0xDC], [0xDB, 0xDD]],
    };

    #[test]
    fn slip_escapes_end_and_esc_and_back() {
        let frame = [0xC0, 0x01, 0xC0, 0xDB, 0x02, 0xC0];
        let mut buf = [0u8; 16];
        buf[..6].copy_from_slice(&frame);
        let n = SLIP.escape_in_place(&mut buf, 6).unwrap();
        assert_eq!(buf[..n], [0xC0, 0x01, 0xDB, 0xDC, 0xDB, 0xDD, 0x02, 0xC0]);
        assert_eq!(n, SLIP.escaped_len(&frame));
        let mut out = [0u8; 16];
        let m = SLIP.unescape(&buf[..n], &mut out).unwrap();
        assert_eq!(out[..m], frame);
    }

    #[test]
    fn a_short_buffer_is_left_unchanged() {
        let mut buf = [0xC0, 0xDB, 0xC0];
        assert_eq!(
            SLIP.escape_in_place(&mut buf, 3),
            Err(EncodeError::BufferTooSmall {
                needed: 4,
                available: 3
            })
        );
        assert_eq!(buf, [0xC0, 0xDB, 0xC0]);
    }

    #[test]
    fn unescape_rejects_damage() {
        let mut out = [0u8; 8];
        let bad = |wire: &[u8], out: &mut [u8]| SLIP.unescape(wire, out).unwrap_err();
        let escape = DecodeError::Frame(Reject::BadEscape);
        assert_eq!(bad(&[0xC0, 0xDB, 0x01, 0xC0], &mut out), escape);
        assert_eq!(bad(&[0xC0, 0x01, 0xDB, 0xC0], &mut out), escape);
        let header = DecodeError::Frame(Reject::BadHeader);
        assert_eq!(bad(&[0x01, 0x02, 0xC0], &mut out), header);
        let cut = DecodeError::Truncated {
            needed: 3,
            available: 2,
        };
        assert_eq!(bad(&[0xC0, 0x01], &mut out), cut);
        let length = DecodeError::Frame(Reject::BadLength);
        assert_eq!(bad(&[0xC0, 1, 2, 3, 0xC0], &mut out[..3]), length);
    }

    #[test]
    fn every_byte_round_trips() {
        for byte in 0..=255u8 {
            let mut buf = [0xC0, byte, byte, 0xC0, 0, 0];
            let n = SLIP.escape_in_place(&mut buf, 4).unwrap();
            assert!(!buf[1..n - 1].contains(&0xC0), "{byte:#x}");
            let mut out = [0u8; 6];
            let m = SLIP.unescape(&buf[..n], &mut out).unwrap();
            assert_eq!(out[..m], [0xC0, byte, byte, 0xC0]);
        }
    }
}
