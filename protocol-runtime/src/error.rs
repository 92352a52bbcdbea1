//! The errors of decoding and encoding: [`DecodeError`] and [`EncodeError`].
//!
//! This module owns the error types shared by the cursors ([`crate::wire`]), the frame engine
//! ([`crate::decoder`]), sealing ([`crate::encoder`]) and generated code. Why a frame was
//! rejected ([`Reject`]) lives with the engine that decides it.
//!
//! Every error is `Copy`, small, `#[non_exhaustive]`, and implements [`Display`] and
//! [`core::error::Error`], so it works the same on firmware and on a host.
//!
//! [`Display`]: core::fmt::Display

use core::fmt;

use crate::decoder::Reject;

/// Why bytes could not be decoded into a value or a frame.
///
/// # Examples
///
/// ```
/// use protocol_runtime::{DecodeError, Reader};
///
/// let mut r = Reader::new(&[0x01]);
/// assert_eq!(r.u16_le(), Err(DecodeError::Truncated { needed: 2, available: 1 }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum DecodeError {
    /// The input ended early: `needed` bytes (counted from the start of the input) were
    /// required, only `available` exist.
    Truncated {
        /// Bytes the read needed, counted from the start of the input.
        needed: usize,
        /// Bytes the input holds.
        available: usize,
    },
    /// The payload's size does not match the command's struct.
    PayloadLength {
        /// Size the struct takes on the wire.
        expected: usize,
        /// Size of the payload received.
        actual: usize,
    },
    /// No command has this dispatch key. A key of several fields is the fields concatenated,
    /// the first field in the high bits.
    UnknownCommand {
        /// The dispatch key.
        key: u64,
    },
    /// The header matches no direction rule (for example an address outside every range).
    UnknownDirection,
    /// A value is not one of its enum's variants.
    InvalidEnum {
        /// The value on the wire.
        value: u64,
    },
    /// The bytes are not a valid frame.
    Frame(Reject),
    /// A stuffed payload holds the forbidden pattern without the byte stuffing inserts after
    /// it.
    InvalidStuffing,
    /// A scaled value lies outside the range its field clamps encoded values to: it could not
    /// be encoded back to the same bytes.
    ValueOutOfRange,
    /// A field that must have the size another field states does not (a repeated group's
    /// element that does not fit the declared data length).
    SizeMismatch,
    /// A NUL-terminated text has no NUL within its field's most bytes (or before the payload
    /// ends).
    Unterminated,
    /// A check inside the payload (a CRC over some of its fields) does not match the bytes it
    /// covers.
    PayloadCheck,
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            DecodeError::Truncated { needed, available } => {
                write!(
                    f,
                    "input truncated: {needed} bytes needed, {available} available"
                )
            }
            DecodeError::PayloadLength { expected, actual } => {
                write!(
                    f,
                    "payload length mismatch: expected {expected} bytes, got {actual}"
                )
            }
            DecodeError::UnknownCommand { key } => write!(f, "unknown command {key:#x}"),
            DecodeError::UnknownDirection => f.write_str("header matches no direction"),
            DecodeError::InvalidEnum { value } => write!(f, "invalid enum value {value:#x}"),
            DecodeError::InvalidStuffing => {
                write!(
                    f,
                    "stuffed payload: a forbidden pattern is not followed by its stuffing byte"
                )
            }
            DecodeError::ValueOutOfRange => {
                write!(f, "a scaled value lies outside its field's range")
            }
            DecodeError::SizeMismatch => write!(
                f,
                "a field's size does not match the size another field states"
            ),
            DecodeError::Unterminated => {
                f.write_str("a NUL-terminated text has no NUL within its most bytes")
            }
            DecodeError::PayloadCheck => {
                f.write_str("a check inside the payload does not match the bytes it covers")
            }
            DecodeError::Frame(reason) => write!(f, "invalid frame: {reason}"),
        }
    }
}

impl core::error::Error for DecodeError {
    fn source(&self) -> Option<&(dyn core::error::Error + 'static)> {
        match self {
            DecodeError::Frame(reason) => Some(reason),
            _ => None,
        }
    }
}

impl From<Reject> for DecodeError {
    #[inline]
    fn from(reason: Reject) -> Self {
        DecodeError::Frame(reason)
    }
}

/// Why a value or a frame could not be encoded.
///
/// # Examples
///
/// ```
/// use protocol_runtime::{EncodeError, Writer};
///
/// let mut buf = [0u8; 1];
/// let mut w = Writer::new(&mut buf);
/// assert_eq!(w.put_u16_be(7), Err(EncodeError::BufferTooSmall { needed: 2, available: 1 }));
/// ```
#[non_exhaustive]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum EncodeError {
    /// The output buffer is too small: `needed` bytes (counted from its start) were required,
    /// it holds `available`.
    BufferTooSmall {
        /// Bytes the write needed, counted from the start of the buffer.
        needed: usize,
        /// Bytes the buffer holds.
        available: usize,
    },
    /// The payload makes the frame longer than the format allows.
    PayloadTooLarge {
        /// Length that was asked for.
        len: usize,
        /// Largest length allowed.
        max: usize,
    },
    /// A value does not fit its field (for example a length or a bitfield).
    ValueOutOfRange,
}

impl fmt::Display for EncodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            EncodeError::BufferTooSmall { needed, available } => {
                write!(
                    f,
                    "buffer too small: {needed} bytes needed, {available} available"
                )
            }
            EncodeError::PayloadTooLarge { len, max } => {
                write!(f, "payload too large: {len} bytes, at most {max} allowed")
            }
            EncodeError::ValueOutOfRange => f.write_str("value does not fit its field"),
        }
    }
}

impl core::error::Error for EncodeError {}

/// The result of decoding a `T`.
pub type DecodeResult<T> = Result<T, DecodeError>;

/// The result of encoding: nothing, or why not.
pub type EncodeResult = Result<(), EncodeError>;
