//! Field semantics: the rules that turn a payload field's wire value into its Rust value and
//! back, once for every codec. Generated payload code calls these functions with its field's
//! constants (so each call folds to the same straight-line code a hand-written codec has), and
//! the run-time codec calls them with the values of its spec.
//!
//! - scaled fields: `physical = raw * factor + offset` ([`to_physical`]), computed in the
//!   field's Rust type ([`Float`]: `f32` or `f64`); encoding clamps the
//!   physical value when the spec gives a clamp range ([`clamp`]), divides back and rounds
//!   ([`quantize`] by a [`Rounding`]), and a raw value that does not fit its integer type is an
//!   error ([`fit`]), never a saturated value; decoding refuses a value outside the clamp range
//!   ([`check_clamp`]), which could not encode back to the same bytes; a float on the wire
//!   takes the same scaling, and encodes by the inverse ([`unscale`]) without rounding;
//! - enums: an unknown value is an error or kept, by the enum's [`UnknownPolicy`]; a value
//!   encodes only if it decodes back to itself ([`enum_raw`]);
//! - bitfields: members are `width` bits at `shift` of an unsigned word ([`get_bits`],
//!   [`set_bits`]); a member value wider than its bits is an error, bits no member declares are
//!   written as zero and ignored when read;
//! - sized bytes and arrays: a run of bytes or elements whose length another field states
//!   ([`take_sized`], [`array_len`], [`check_stated_len`]);
//! - fields a mask announces: a value present when a bit of an earlier field is set
//!   ([`mask_bit`], [`check_mask_bit`]), an array of one element per set bit ([`mask_count`]);
//! - optional fields and repeated groups: present while bytes remain ([`more`]); a group that
//!   holds more elements than its capacity is a payload of the wrong length ([`group_full`]);
//!   a field that takes every byte left but a check after it reads to that check
//!   ([`rest_but`]);
//! - checks inside a payload: a check value over a run of the payload's fields, verified on
//!   decode ([`verify_check`]) and computed on encode ([`put_check`]);
//! - a packet carried in a payload: the command an earlier key field names
//!   ([`carried_command`]), and a message written into the carrying bytes ([`seal_carried`])
//!   with its key ([`carried_key`]).
//!
//! It does not own the wire cursors ([`crate::wire`]) or the payload trait
//! ([`crate::Payload`]).

mod carried;
mod mask;
mod scale;

pub use carried::{carried_command, carried_key, seal_carried};

pub use mask::{check_mask_bit, mask_bit, mask_count};
pub use scale::{
    RawInt, Rounding, check_clamp, clamp, fit, quantize, to_physical, unscale, within_clamp,
};

use crate::checksum::Checksum;
use crate::error::{DecodeError, EncodeError};
pub use crate::float::Float;
use crate::layout::ByteOrder;
use crate::wire::{Reader, Writer, read_uint, write_uint};

/// What an enum does with a wire value that names none of its variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum UnknownPolicy {
    /// The value is a decode error ([`DecodeError::InvalidEnum`]).
    #[default]
    Reject,
    /// The value is kept as it was on the wire (a generated enum's `Unknown(raw)`).
    Keep,
}

impl UnknownPolicy {
    /// Decoding `raw`, which names no variant.
    ///
    /// # Errors
    ///
    /// [`DecodeError::InvalidEnum`] with `raw` when unknown values are rejected.
    ///
    /// ```
    /// use protocol_runtime::{DecodeError, field::UnknownPolicy};
    /// assert_eq!(UnknownPolicy::Keep.unknown(9), Ok(()));
    /// assert_eq!(UnknownPolicy::Reject.unknown(9), Err(DecodeError::InvalidEnum { value: 9, place: protocol_runtime::error::Place::NONE }));
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn unknown(self, raw: u64) -> Result<(), DecodeError> {
        match self {
            UnknownPolicy::Keep => Ok(()),
            UnknownPolicy::Reject => Err(DecodeError::InvalidEnum {
                value: raw,
                place: crate::error::Place::NONE,
            }),
        }
    }

    /// Encoding a raw value; `known` says whether it names a variant.
    ///
    /// # Errors
    ///
    /// [`EncodeError::ValueOutOfRange`] for an unknown value when unknown values are rejected.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn encode(self, known: bool) -> Result<(), EncodeError> {
        match (self, known) {
            (UnknownPolicy::Reject, false) => Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE,
            }),
            _ => Ok(()),
        }
    }
}

/// The raw value of an enum value, if it decodes back to the same value: an `Unknown(raw)`
/// holding a known variant's value would decode as that variant, so it is refused.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `from_raw(to_raw(value))` is not `value`.
///
/// ```
/// use protocol_runtime::{DecodeError, EncodeError, field::enum_raw};
///
/// #[derive(Debug, Clone, Copy, PartialEq)]
/// enum Mode { Idle, Unknown(u8) }
/// fn to_raw(m: Mode) -> u8 { match m { Mode::Idle => 0, Mode::Unknown(r) => r } }
/// fn from_raw(r: u8) -> Result<Mode, DecodeError> {
///     Ok(match r { 0 => Mode::Idle, r => Mode::Unknown(r) })
/// }
/// assert_eq!(enum_raw(Mode::Unknown(7), to_raw, from_raw), Ok(7));
/// assert_eq!(enum_raw(Mode::Unknown(0), to_raw, from_raw), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn enum_raw<E: Copy + PartialEq, R: Copy>(
    value: E,
    to_raw: fn(E) -> R,
    from_raw: fn(R) -> Result<E, DecodeError>,
) -> Result<R, EncodeError> {
    let raw = to_raw(value);
    match from_raw(raw) {
        Ok(back) if back == value => Ok(raw),
        _ => Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        }),
    }
}

/// The mask of a bit member `width` bits wide (all bits from 64 on).
///
/// ```
/// assert_eq!(protocol_runtime::field::bit_mask(4), 0xF);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn bit_mask(width: u32) -> u64 {
    match 1u64.checked_shl(width) {
        Some(bit) => bit.wrapping_sub(1),
        None => u64::MAX,
    }
}

/// The value of the bit member `width` bits wide at bit `shift` of `word`.
///
/// ```
/// assert_eq!(protocol_runtime::field::get_bits(0b1011_0110, 4, 3), 0b011);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn get_bits(word: u64, shift: u32, width: u32) -> u64 {
    match word.checked_shr(shift) {
        Some(bits) => bits & bit_mask(width),
        None => 0,
    }
}

/// `word` with the bit member `width` bits wide at bit `shift` set to `value` (or-ed in: the
/// member's bits of `word` start as zero).
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `value` does not fit `width` bits: the member would be
/// cut, and decode as another value.
///
/// ```
/// use protocol_runtime::{EncodeError, field::set_bits};
/// assert_eq!(set_bits(0b0001, 0b101, 1, 3), Ok(0b1011));
/// assert_eq!(set_bits(0, 16, 0, 4), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn set_bits(word: u64, value: u64, shift: u32, width: u32) -> Result<u64, EncodeError> {
    if value > bit_mask(width) {
        return Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        });
    }
    match value.checked_shl(shift) {
        Some(bits) => Ok(word | bits),
        None => Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        }),
    }
}

/// The `len` bytes of a sized-bytes field, at most `max`, from `r`.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if fewer than `len` bytes remain, [`DecodeError::SizeMismatch`]
/// if `len` exceeds `max`.
///
/// ```
/// use protocol_runtime::{DecodeError, Reader, field::take_sized};
/// let mut r = Reader::new(&[1, 2, 3]);
/// assert_eq!(take_sized(&mut r, 2, 4), Ok(&[1, 2][..]));
/// assert_eq!(take_sized(&mut Reader::new(&[1, 2, 3]), 3, 2), Err(DecodeError::SizeMismatch { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn take_sized<'a>(r: &mut Reader<'a>, len: u64, max: usize) -> Result<&'a [u8], DecodeError> {
    let taken = r.take(usize::try_from(len).unwrap_or(usize::MAX))?;
    if taken.len() > max {
        return Err(DecodeError::SizeMismatch {
            place: crate::error::Place::NONE,
        });
    }
    Ok(taken)
}

/// The number of elements of a variable-length array that another field states, `len`, when
/// the array holds it: at most `max`.
///
/// # Errors
///
/// [`DecodeError::SizeMismatch`] if `len` exceeds `max`.
///
/// ```
/// use protocol_runtime::{DecodeError, field::array_len};
/// assert_eq!(array_len(3, 4), Ok(3));
/// assert_eq!(array_len(5, 4), Err(DecodeError::SizeMismatch { place: protocol_runtime::error::Place::NONE }));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn array_len(len: u64, max: usize) -> Result<usize, DecodeError> {
    match usize::try_from(len) {
        Ok(n) if n <= max => Ok(n),
        _ => Err(DecodeError::SizeMismatch {
            place: crate::error::Place::NONE,
        }),
    }
}

/// Whether sized bytes of `len` bytes agree with the field that states their length.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when `stated` is not `len`.
///
/// ```
/// use protocol_runtime::field::check_stated_len;
/// assert!(check_stated_len(3, 3).is_ok());
/// assert!(check_stated_len(3, 4).is_err());
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn check_stated_len(len: usize, stated: u64) -> Result<(), EncodeError> {
    if len as u64 == stated {
        Ok(())
    } else {
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
    }
}

/// Whether an optional field is present, or a repeated group has another element: bytes
/// remain.
///
/// ```
/// use protocol_runtime::{Reader, field::more};
/// assert!(more(&Reader::new(&[0])));
/// assert!(!more(&Reader::new(&[])));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn more(r: &Reader<'_>) -> bool {
    r.remaining() > 0
}

/// The error of a repeated group with more elements than its capacity: a payload longer than
/// its struct's largest wire size `size` (`actual` is every byte of the payload).
///
/// ```
/// use protocol_runtime::{DecodeError, Reader, field::group_full};
/// let r = Reader::new(&[0; 9]);
/// assert_eq!(group_full(&r, 8), DecodeError::PayloadLength { expected: 8, actual: 9 });
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn group_full(r: &Reader<'_>, size: usize) -> DecodeError {
    DecodeError::PayloadLength {
        expected: size,
        actual: r.position().saturating_add(r.remaining()),
    }
}

/// The bytes a field that takes every byte left reads when `keep` bytes of fixed fields (a
/// check) follow it: all but the last `keep` (none when fewer remain; the fields after it
/// then find the payload truncated).
///
/// ```
/// use protocol_runtime::{Reader, field::rest_but};
/// assert_eq!(rest_but(&Reader::new(&[1, 2, 3]), 1), &[1, 2][..]);
/// assert_eq!(rest_but(&Reader::new(&[1]), 2), &[][..]);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn rest_but<'a>(r: &Reader<'a>, keep: usize) -> &'a [u8] {
    let rest = r.rest();
    rest.get(..rest.len().saturating_sub(keep))
        .unwrap_or_default()
}

/// Reads a check inside a payload at the reader's position and verifies it: its value, of
/// the check's width in byte order `order`, must be the check of the bytes from `start` (a
/// copy of the reader where the covered fields begin) to position `end`.
///
/// # Errors
///
/// [`DecodeError::Truncated`] if the value's bytes are missing, [`DecodeError::PayloadCheck`]
/// if it does not match.
///
/// ```
/// use protocol_runtime::{Checksum, DecodeError, Reader, field::verify_check};
/// use protocol_runtime::layout::ByteOrder;
/// let bytes = [0x01, 0x02, 0x03];
/// let mut r = Reader::new(&bytes);
/// let start = r.clone();
/// r.skip(2)?;
/// assert_eq!(verify_check(&mut r, &start, 2, &Checksum::Sum8, ByteOrder::Big), Ok(()));
/// let bad = [0x01, 0x02, 0x04];
/// let mut r = Reader::new(&bad);
/// let start = r.clone();
/// r.skip(2)?;
/// assert_eq!(verify_check(&mut r, &start, 2, &Checksum::Sum8, ByteOrder::Big), Err(DecodeError::PayloadCheck { place: protocol_runtime::error::Place::NONE }));
/// # Ok::<(), DecodeError>(())
/// ```
#[inline]
pub fn verify_check(
    r: &mut Reader<'_>,
    start: &Reader<'_>,
    end: usize,
    check: &Checksum<'_>,
    order: ByteOrder,
) -> Result<(), DecodeError> {
    let width = check.width();
    let stored = read_uint(r.take(width)?, 0, width as u8, order);
    let covered = start
        .rest()
        .get(..end.saturating_sub(start.position()))
        .unwrap_or_default();
    if stored == Some(check.compute(covered)) {
        Ok(())
    } else {
        Err(DecodeError::PayloadCheck {
            place: crate::error::Place::NONE,
        })
    }
}

/// Writes a check inside a payload at the writer's position: the check of the bytes written
/// from position `start` to `end`, of the check's width in byte order `order`.
///
/// # Errors
///
/// [`EncodeError::BufferTooSmall`] if the writer has too little room.
///
/// ```
/// use protocol_runtime::{Checksum, Writer, field::put_check};
/// use protocol_runtime::layout::ByteOrder;
/// let mut buf = [0u8; 3];
/// let mut w = Writer::new(&mut buf);
/// w.put_bytes(&[0x01, 0x02])?;
/// put_check(&mut w, 0, 2, &Checksum::Sum8, ByteOrder::Big)?;
/// assert_eq!(buf, [0x01, 0x02, 0x03]);
/// # Ok::<(), protocol_runtime::EncodeError>(())
/// ```
#[inline]
pub fn put_check(
    w: &mut Writer<'_>,
    start: usize,
    end: usize,
    check: &Checksum<'_>,
    order: ByteOrder,
) -> Result<(), EncodeError> {
    let covered = w.written().get(start..end).unwrap_or_default();
    let value = check.compute_written(covered);
    let width = check.width();
    let mut bytes = [0u8; 8];
    write_uint(&mut bytes, 0, width as u8, order, value).ok_or(EncodeError::ValueOutOfRange {
        place: crate::error::Place::NONE,
    })?;
    w.put_bytes(bytes.get(..width).unwrap_or_default())
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::float_cmp)]
mod tests {
    use super::*;

    #[test]
    fn fit_accepts_every_integer_of_the_type_and_nothing_else() {
        assert_eq!(
            fit::<u64>(18_446_744_073_709_549_568.0),
            Ok(u64::MAX - 2047)
        );
        assert!(fit::<u64>(18_446_744_073_709_551_616.0).is_err());
        assert_eq!(fit::<i64>(-9_223_372_036_854_775_808.0), Ok(i64::MIN));
        assert!(fit::<i64>(9_223_372_036_854_775_808.0).is_err());
        assert_eq!(fit::<i32>(-2_147_483_648.9), Ok(i32::MIN));
        assert!(fit::<i32>(-2_147_483_649.0).is_err());
        assert_eq!(fit::<u8>(-0.9), Ok(0));
        assert!(fit::<u8>(f64::INFINITY).is_err());
    }

    #[test]
    fn quantize_rounds_halves_away_from_zero() {
        assert_eq!(
            fit::<i16>(quantize(-2.5, 1.0, 0.0, Rounding::Nearest)),
            Ok(-3)
        );
        assert_eq!(
            fit::<i16>(quantize(2.5, 1.0, 0.0, Rounding::Nearest)),
            Ok(3)
        );
        assert_eq!(
            fit::<i16>(quantize(-2.7, 1.0, 0.0, Rounding::Truncate)),
            Ok(-2)
        );
    }

    #[test]
    fn bits_round_trip_at_every_position() {
        for shift in 0..60 {
            let word = set_bits(0, 0b1010, shift, 4).unwrap();
            assert_eq!(get_bits(word, shift, 4), 0b1010);
        }
        assert_eq!(get_bits(u64::MAX, 0, 64), u64::MAX);
    }
}
