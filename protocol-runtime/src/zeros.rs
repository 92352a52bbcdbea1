//! Trailing-zero payload truncation: a frame format may let its sender drop the zero bytes at
//! the end of a payload (MAVLink 2 does, to save air time on messages whose last fields are
//! unset). The length field counts the bytes sent and the checks cover them, so the stream
//! engine sees sent frames only; payload code zero-fills a short payload to its struct's size
//! before reading ([`read_zero_filled`]) and trims the zeros after writing
//! ([`trimmed_len`]).
//!
//! The first byte of a payload is always sent, even when it is zero, as the reference
//! implementations of MAVLink (pymavlink, the `mavlink` crate) do: an all-zero payload goes out
//! as one zero byte, never as an empty payload.

use crate::encoder::{Payload, payload_room};
use crate::error::{DecodeError, EncodeError};

/// The bytes of `payload` a sender keeps: all but its trailing zeros, and at least the first
/// byte of a non-empty payload.
///
/// ```
/// use protocol_runtime::zeros::trimmed_len;
/// assert_eq!(trimmed_len(&[0x16, 0x00, 0x04, 0x00, 0x00]), 3);
/// assert_eq!(trimmed_len(&[0x00, 0x00, 0x00]), 1);
/// assert_eq!(trimmed_len(&[0x00, 0x07]), 2);
/// assert_eq!(trimmed_len(&[]), 0);
/// ```
#[inline]
#[must_use]
pub fn trimmed_len(payload: &[u8]) -> usize {
    let kept = payload
        .iter()
        .rposition(|&b| b != 0)
        .map_or(0, |last| last.saturating_add(1));
    kept.max(payload.len().min(1))
}

/// Places `payload`, written aside, at `start` of `buf` without its trailing zeros
/// ([`trimmed_len`]): a frame of `start`, the kept bytes and `trailer_len` bytes after them
/// needs no more room than that, even when the whole payload would not fit. Returns the room
/// after `start` (up to `trailer_len` bytes before the end of `buf`) and the bytes kept.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if `buf` is shorter than the frame.
///
/// ```
/// use protocol_runtime::zeros::place_trimmed;
/// let mut buf = [0xAA; 6];
/// let (_, kept) = place_trimmed(&mut buf, 2, 2, &[7, 8, 0, 0, 0])?;
/// assert_eq!((kept, buf), (2, [0xAA, 0xAA, 7, 8, 0xAA, 0xAA]));
/// # Ok::<(), protocol_runtime::EncodeError>(())
/// ```
#[inline]
pub fn place_trimmed<'b>(
    buf: &'b mut [u8],
    start: usize,
    trailer_len: usize,
    payload: &[u8],
) -> Result<(&'b mut [u8], usize), EncodeError> {
    let kept = trimmed_len(payload);
    let needed = start.saturating_add(kept).saturating_add(trailer_len);
    let room = payload_room(buf, needed, start, trailer_len)?;
    for (to, from) in room.iter_mut().zip(payload.iter().take(kept)) {
        *to = *from;
    }
    Ok((room, kept))
}

/// `bytes` zero-filled to `size` bytes in `scratch`, or `bytes` itself when it is not shorter
/// than `size` (a longer payload is left to the reader to refuse).
///
/// # Errors
///
/// [`DecodeError::PayloadLength`] if `scratch` has fewer than `size` bytes (the payload cannot
/// be filled; generated code sizes `scratch` as the frame's largest payload, which validation
/// makes at least every struct's size).
///
/// ```
/// use protocol_runtime::zeros::zero_filled;
/// let mut scratch = [0xAA; 8];
/// assert_eq!(zero_filled(&[1, 2], 4, &mut scratch)?, &[1, 2, 0, 0]);
/// assert_eq!(zero_filled(&[1, 2, 3, 4, 5], 4, &mut scratch)?, &[1, 2, 3, 4, 5]);
/// # Ok::<(), protocol_runtime::DecodeError>(())
/// ```
#[inline]
pub fn zero_filled<'a>(
    bytes: &'a [u8],
    size: usize,
    scratch: &'a mut [u8],
) -> Result<&'a [u8], DecodeError> {
    if bytes.len() >= size {
        return Ok(bytes);
    }
    let too_small = DecodeError::PayloadLength {
        expected: size,
        actual: bytes.len(),
    };
    let filled = scratch.get_mut(..size).ok_or(too_small)?;
    let (sent, rest) = filled.split_at_mut(bytes.len());
    sent.copy_from_slice(bytes);
    rest.fill(0);
    Ok(filled)
}

/// The payload `P` read from `bytes` zero-filled to `P::SIZE` (in `scratch`): a payload whose
/// trailing zeros the sender dropped decodes to the full value.
///
/// # Errors
///
/// The errors of [`zero_filled`] and of [`Payload::from_bytes`] (a payload longer than
/// `P::SIZE` is [`DecodeError::PayloadLength`]).
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_zero_filled<P: Payload>(bytes: &[u8], scratch: &mut [u8]) -> Result<P, DecodeError> {
    P::from_bytes(zero_filled(bytes, P::SIZE, scratch)?)
}

/// [`read_zero_filled`] in a buffer of its own: the payload `P` read from `bytes` as they are
/// when they hold all of its `P::SIZE` bytes (the common case: nothing is copied), else from
/// `bytes` followed by zeros in an `N`-byte buffer, which only this case zeroes. Generated code
/// passes the struct's size as `N`, so the buffer and its copy have a size known at compile
/// time.
///
/// # Errors
///
/// [`DecodeError::PayloadLength`] if a short `bytes` does not fit `N` bytes or `N` is under
/// `P::SIZE`, and the errors of [`Payload::from_bytes`].
///
/// ```
/// use protocol_runtime::zeros::read_filled;
/// // A 4-byte payload whose last two bytes (zero) the sender dropped.
/// assert_eq!(read_filled::<[u8; 4], 4>(&[0x34, 0x12]), Ok([0x34, 0x12, 0, 0]));
/// assert_eq!(read_filled::<[u8; 4], 4>(&[1, 2, 3, 4]), Ok([1, 2, 3, 4]));
/// ```
#[inline(always)]
pub fn read_filled<P: Payload, const N: usize>(bytes: &[u8]) -> Result<P, DecodeError> {
    if bytes.len() >= P::SIZE {
        return P::from_bytes(bytes);
    }
    let mut filled = [0u8; N];
    let too_small = DecodeError::PayloadLength {
        expected: P::SIZE,
        actual: bytes.len(),
    };
    let sent = filled.get_mut(..bytes.len()).ok_or(too_small)?;
    sent.copy_from_slice(bytes);
    P::from_bytes(filled.get(..P::SIZE).ok_or(too_small)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trimming_keeps_every_byte_up_to_the_last_non_zero_one() {
        assert_eq!(trimmed_len(&[1, 0, 2]), 3);
        assert_eq!(trimmed_len(&[1, 0, 2, 0]), 3);
        assert_eq!(trimmed_len(&[0]), 1);
        assert_eq!(trimmed_len(&[5]), 1);
    }

    #[test]
    fn filling_then_trimming_gives_back_the_sent_bytes() {
        let sent = [0x16, 0x00, 0x04];
        let mut scratch = [0xFF; 10];
        let full = zero_filled(&sent, 10, &mut scratch);
        assert_eq!(full.map(<[u8]>::len), Ok(10));
        assert_eq!(full.map(|f| f.get(..trimmed_len(f))), Ok(Some(&sent[..])));
    }

    #[test]
    fn a_buffer_of_its_own_reads_as_the_scratch_does() {
        let sent = [0x16, 0x00, 0x04];
        let mut scratch = [0xFF; 8];
        let via_scratch: Result<[u8; 8], _> = read_zero_filled(&sent, &mut scratch);
        assert_eq!(read_filled::<[u8; 8], 8>(&sent), via_scratch);
        assert_eq!(
            read_filled::<[u8; 8], 8>(&sent),
            Ok([0x16, 0x00, 0x04, 0, 0, 0, 0, 0])
        );
        // Too small a buffer, or too long a payload: an error, never a panic.
        assert!(read_filled::<[u8; 8], 4>(&sent).is_err());
        assert!(read_filled::<[u8; 4], 4>(&[1, 2, 3, 4, 5]).is_err());
    }

    #[test]
    fn a_scratch_smaller_than_the_size_is_an_error_not_a_panic() {
        let mut scratch = [0u8; 2];
        assert_eq!(
            zero_filled(&[1], 4, &mut scratch),
            Err(DecodeError::PayloadLength {
                expected: 4,
                actual: 1
            })
        );
    }
}
