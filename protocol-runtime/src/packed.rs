//! Bit-packed arrays: `count` unsigned elements of `bits` bits each (1 to 32), back to back
//! with no padding between them, in `ceil(count * bits / 8)` bytes. CRSF `RC_CHANNELS_PACKED`
//! and SBUS carry 16 channels of 11 bits in 22 bytes this way.
//!
//! [`BitOrder`] says how the stream of bits maps onto the bytes. Generated code and the
//! run-time codec read and write every element through [`get_packed`] and [`set_packed`].

use crate::error::EncodeError;
use crate::field::bit_mask;

/// How the bits of a packed array fill its bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BitOrder {
    /// The first element starts at bit 0 (the least significant) of byte 0, its least
    /// significant bit first; bits run up through each byte, then on to the next (CRSF, SBUS).
    LsbFirst,
    /// The first element starts at bit 7 (the most significant) of byte 0, its most
    /// significant bit first; bits run down through each byte, then on to the next.
    MsbFirst,
}

/// The bytes element `index` touches, and how many bits of the first byte precede it.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn span(len: usize, index: usize, bits: u32) -> Option<(usize, usize, u32)> {
    let start = index.checked_mul(bits as usize)?;
    let end = start.checked_add(bits as usize)?;
    let last = end.div_ceil(8);
    if bits == 0 || bits > 32 || last > len {
        return None;
    }
    Some((start / 8, last, (start % 8) as u32))
}

/// How far the element lies from bit 0 of the word its bytes make.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn shift(order: BitOrder, bytes: usize, skip: u32, bits: u32) -> u32 {
    match order {
        BitOrder::LsbFirst => skip,
        // The word is the bytes in order, most significant first: the element ends
        // `8 * bytes - skip - bits` bits above its least significant bit.
        BitOrder::MsbFirst => (bytes as u32)
            .wrapping_mul(8)
            .wrapping_sub(skip)
            .wrapping_sub(bits),
    }
}

/// The bytes as one word: little-endian for LSB-first, big-endian for MSB-first.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn word(bytes: &[u8], order: BitOrder) -> u64 {
    let push = |acc: u64, b: &u8| (acc << 8) | u64::from(*b);
    match order {
        BitOrder::LsbFirst => bytes.iter().rev().fold(0, push),
        BitOrder::MsbFirst => bytes.iter().fold(0, push),
    }
}

/// Element `index` of the packed array of `bits`-bit elements in `bytes`, or 0 when it does
/// not lie inside `bytes` (or `bits` is not in `1..=32`).
///
/// ```
/// use protocol_runtime::packed::{BitOrder, get_packed};
///
/// // Two 11-bit elements, 0x3E0 and 0x1F, LSB-first: 0b00_1111_1000 | 0x1F << 11.
/// let bytes = [0xE0, 0xFB, 0x00];
/// assert_eq!(get_packed(&bytes, 0, 11, BitOrder::LsbFirst), 0x3E0);
/// assert_eq!(get_packed(&bytes, 1, 11, BitOrder::LsbFirst), 0x1F);
/// ```
#[inline]
pub fn get_packed(bytes: &[u8], index: usize, bits: u32, order: BitOrder) -> u64 {
    let Some((first, last, skip)) = span(bytes.len(), index, bits) else {
        return 0;
    };
    let Some(b) = bytes.get(first..last) else {
        return 0;
    };
    let at = shift(order, b.len(), skip, bits);
    word(b, order).checked_shr(at).unwrap_or(0) & bit_mask(bits)
}

/// Sets element `index` of the packed array of `bits`-bit elements in `bytes` to `value`,
/// leaving every other bit as it is.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `value` does not fit `bits` bits (it would be cut and
/// decode as another value), or the element does not lie inside `bytes`; nothing is written
/// then.
///
/// ```
/// use protocol_runtime::packed::{BitOrder, set_packed};
/// use protocol_runtime::EncodeError;
///
/// let mut bytes = [0u8; 3];
/// set_packed(&mut bytes, 0, 11, BitOrder::MsbFirst, 0x7FF)?;
/// assert_eq!(bytes, [0xFF, 0xE0, 0x00]);
/// assert_eq!(set_packed(&mut bytes, 1, 11, BitOrder::MsbFirst, 0x800), Err(EncodeError::ValueOutOfRange { place: protocol_runtime::error::Place::NONE }));
/// # Ok::<(), EncodeError>(())
/// ```
#[inline]
pub fn set_packed(
    bytes: &mut [u8],
    index: usize,
    bits: u32,
    order: BitOrder,
    value: u64,
) -> Result<(), EncodeError> {
    let mask = bit_mask(bits);
    let (first, last, skip) = span(bytes.len(), index, bits)
        .filter(|_| value <= mask)
        .ok_or(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })?;
    let b = bytes
        .get_mut(first..last)
        .ok_or(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        })?;
    let at = shift(order, b.len(), skip, bits);
    let w = (word(b, order) & !(mask << at)) | (value << at);
    let n = b.len();
    for (i, byte) in b.iter_mut().enumerate() {
        // Byte `i` holds bits `8 * k .. 8 * k + 8` of the word, `k` counted from its least
        // significant end in the word's byte order.
        let k = match order {
            BitOrder::LsbFirst => i,
            BitOrder::MsbFirst => n.wrapping_sub(1).wrapping_sub(i),
        };
        *byte = w.checked_shr((k as u32).wrapping_mul(8)).unwrap_or(0) as u8;
    }
    Ok(())
}

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]
mod tests {
    use super::*;

    /// The bit-by-bit definition of each order, to check the word arithmetic against.
    fn slow_get(bytes: &[u8], index: usize, bits: u32, order: BitOrder) -> u64 {
        let mut v = 0u64;
        for j in 0..bits as usize {
            let k = index * bits as usize + j;
            match order {
                BitOrder::LsbFirst => v |= u64::from((bytes[k / 8] >> (k % 8)) & 1) << j,
                BitOrder::MsbFirst => {
                    v = (v << 1) | u64::from((bytes[k / 8] >> (7 - k % 8)) & 1);
                }
            }
        }
        v
    }

    #[test]
    fn every_width_and_position_matches_the_bit_by_bit_definition() {
        let bytes: [u8; 40] = core::array::from_fn(|i| (i * 37 + 11) as u8);
        for order in [BitOrder::LsbFirst, BitOrder::MsbFirst] {
            for bits in 1..=32 {
                let count = bytes.len() * 8 / bits as usize;
                for index in 0..count {
                    let v = get_packed(&bytes, index, bits, order);
                    assert_eq!(
                        v,
                        slow_get(&bytes, index, bits, order),
                        "{order:?} {bits} {index}"
                    );
                    let mut copy = bytes;
                    set_packed(&mut copy, index, bits, order, v ^ bit_mask(bits)).unwrap();
                    assert_eq!(get_packed(&copy, index, bits, order), v ^ bit_mask(bits));
                    set_packed(&mut copy, index, bits, order, v).unwrap();
                    assert_eq!(copy, bytes, "{order:?} {bits} {index}: other bits kept");
                }
            }
        }
    }

    #[test]
    fn out_of_range_values_and_positions_are_refused() {
        let mut bytes = [0u8; 22];
        assert_eq!(
            set_packed(&mut bytes, 0, 11, BitOrder::LsbFirst, 0x800),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            set_packed(&mut bytes, 16, 11, BitOrder::LsbFirst, 1),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(
            set_packed(&mut bytes, 0, 33, BitOrder::LsbFirst, 1),
            Err(EncodeError::ValueOutOfRange {
                place: crate::error::Place::NONE
            })
        );
        assert_eq!(bytes, [0u8; 22]);
        assert_eq!(get_packed(&bytes, 16, 11, BitOrder::LsbFirst), 0);
        assert_eq!(get_packed(&bytes, usize::MAX, 11, BitOrder::MsbFirst), 0);
    }
}
