//! The header and buffer helpers generated code calls around a payload: reading and writing
//! a header value, the payload of a frame, the room a frame or payload takes in a buffer, and
//! the presence of a header field of one direction.

use crate::error::{DecodeError, EncodeError};
use crate::layout::WordField;

/// Reads a header value of `frame` at `field`; a frame too short for it is
/// [`DecodeError::Truncated`], needing the `header_len` bytes every frame of its format has.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if `frame` ends before the field.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn header_value(frame: &[u8], field: WordField, header_len: usize) -> Result<u64, DecodeError> {
    field.read(frame).ok_or(DecodeError::Truncated {
        needed: header_len,
        available: frame.len(),
    })
}

/// The error of a frame whose dispatch key `key` names no command.
#[cfg_attr(not(protocol_opt0), inline(always))]
#[must_use]
pub const fn unknown_command(key: u64) -> DecodeError {
    DecodeError::UnknownCommand { key }
}

/// The payload of a checked frame: its bytes between the `header_len` bytes of its header and
/// the `trailer_len` bytes of its trailer.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if `frame` is shorter than its header and trailer.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn payload_of(
    frame: &[u8],
    header_len: usize,
    trailer_len: usize,
) -> Result<&[u8], DecodeError> {
    frame
        .get(header_len..frame.len().saturating_sub(trailer_len))
        .ok_or(DecodeError::Truncated {
            needed: header_len.saturating_add(trailer_len),
            available: frame.len(),
        })
}

/// Where an encoder writes a payload into `buf`: from `start` up to the `trailer_len` bytes the
/// trailer needs at the end, once `buf` is known to hold the `needed` bytes of the frame.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `needed` or than `start` and the
/// trailer.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn payload_room(
    buf: &mut [u8],
    needed: usize,
    start: usize,
    trailer_len: usize,
) -> Result<&mut [u8], EncodeError> {
    let available = buf.len();
    if available < needed {
        return Err(EncodeError::BufferTooSmall { needed, available });
    }
    buf.get_mut(start..available.saturating_sub(trailer_len))
        .ok_or(EncodeError::BufferTooSmall { needed, available })
}

/// The first `total` bytes of `buf`: the frame an encoder seals.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if `buf` is shorter than `total`.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn frame_room(buf: &mut [u8], total: usize) -> Result<&mut [u8], EncodeError> {
    let available = buf.len();
    buf.get_mut(..total).ok_or(EncodeError::BufferTooSmall {
        needed: total,
        available,
    })
}

/// Writes a header value into `frame` at `field`.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if the value does not fit the field or the field lies
/// outside the frame.
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn write_header(frame: &mut [u8], field: WordField, value: u64) -> Result<(), EncodeError> {
    field
        .write(frame, value)
        .ok_or(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
}

/// Refuses a header value of another direction's frames: a frame of a direction without that
/// field (Sensirion SHDLC's state byte, in a command) has no place for it, so it is `None`
/// there; a value would not decode back.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `value` is `Some`.
///
/// # Examples
///
/// ```
/// use protocol_runtime::EncodeError;
/// use protocol_runtime::encoder::absent_header;
/// assert_eq!(absent_header::<u8>(None), Ok(()));
/// assert!(matches!(absent_header(Some(3u8)), Err(EncodeError::ValueOutOfRange { .. })));
/// ```
#[inline]
pub fn absent_header<T>(value: Option<T>) -> Result<(), EncodeError> {
    match value {
        None => Ok(()),
        Some(_) => Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        }),
    }
}

/// The value of a header field of one direction, in a frame of that direction: every such
/// frame has it, so a `None` would not decode back.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `value` is `None`.
///
/// # Examples
///
/// ```
/// use protocol_runtime::EncodeError;
/// use protocol_runtime::encoder::present_header;
/// assert_eq!(present_header(Some(3u8)), Ok(3));
/// assert!(matches!(present_header::<u8>(None), Err(EncodeError::ValueOutOfRange { .. })));
/// ```
#[inline]
pub fn present_header<T>(value: Option<T>) -> Result<T, EncodeError> {
    value.ok_or(EncodeError::ValueOutOfRange {
        place: crate::error::Place::NONE,
    })
}
