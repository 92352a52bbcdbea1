//! Fields that an earlier field's bits announce: a value present when one bit of a mask field
//! is set ([`mask_bit`], [`check_mask_bit`]), and an array with one element per set bit
//! ([`mask_count`]). The mask is an unsigned integer field the sender sets: the codecs read
//! presence and counts from it, and an encoder refuses a value that disagrees with it rather
//! than rewrite a field whose other bits the application owns.

use crate::error::EncodeError;

/// Whether the field that bit `bit` of `mask` announces is present.
///
/// ```
/// use protocol_runtime::field::mask_bit;
/// assert!(mask_bit(0b1000, 3));
/// assert!(!mask_bit(0b0111, 3));
/// assert!(!mask_bit(u64::MAX, 64));
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn mask_bit(mask: u64, bit: u32) -> bool {
    bit < 64 && (mask >> bit) & 1 == 1
}

/// The number of elements of an array that a mask counts: its set bits.
///
/// ```
/// use protocol_runtime::field::mask_count;
/// assert_eq!(mask_count(0), 0);
/// assert_eq!(mask_count(0b1011_0001), 4);
/// assert_eq!(mask_count(u64::MAX), 64);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn mask_count(mask: u64) -> u64 {
    mask.count_ones() as u64
}

/// Whether a field announced by bit `bit` of `mask` agrees with it: present exactly when the
/// bit is set.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] when the value is present and the bit clear, or absent and
/// the bit set: what is written must decode to the same value.
///
/// ```
/// use protocol_runtime::field::check_mask_bit;
/// assert!(check_mask_bit(true, 0b100, 2).is_ok());
/// assert!(check_mask_bit(false, 0b011, 2).is_ok());
/// assert!(check_mask_bit(true, 0b011, 2).is_err());
/// assert!(check_mask_bit(false, 0b100, 2).is_err());
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn check_mask_bit(present: bool, mask: u64, bit: u32) -> Result<(), EncodeError> {
    if present == mask_bit(mask, bit) {
        Ok(())
    } else {
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })
    }
}
