//! Bit streams: a run of bytes read as one stream of bits, most significant bit of the first
//! byte first, whose members have any width from 1 to 64 bits and straddle bytes as they fall
//! (RTCM 3: a 12-bit message number, a 12-bit station id, then 38-bit signed coordinates).
//! Also the rule of signed members of any width, in a bit stream or a bitfield word: two's
//! complement of the member's own width, sign-extended when read ([`sign_extend`]), refused
//! when written if the value does not fit ([`signed_bits`]).
//!
//! Generated code and the run-time codec read and write every member through [`get_stream`]
//! and [`set_stream`].

use crate::error::{EncodeError, Place};
use crate::field::bit_mask;

/// The bytes member `width` bits wide at bit `at` touches (at most nine), and the bits after
/// it in the last of them; `None` when it does not lie inside `len` bytes or `width` is not in
/// `1..=64`.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn span(len: usize, at: usize, width: u32) -> Option<(usize, usize, u32)> {
    let end = at.checked_add(width as usize)?;
    let last = end.div_ceil(8);
    if width == 0 || width > 64 || last > len {
        return None;
    }
    let after = last.checked_mul(8)?.checked_sub(end)?;
    Some((at / 8, last, after as u32))
}

/// The bytes in order, most significant first, as one integer (at most nine bytes).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn word(bytes: &[u8]) -> u128 {
    bytes
        .iter()
        .fold(0u128, |acc, b| (acc << 8) | u128::from(*b))
}

/// The `width`-bit member (1 to 64) at bit `at` of the stream `bytes` (bit 0 is the most
/// significant bit of byte 0), as an unsigned value; 0 when it does not lie inside `bytes`.
///
/// ```
/// use protocol_runtime::bitstream::get_stream;
///
/// // RTCM 3 message 1005 starts with the 12-bit number 1005 (0x3ED), then a 12-bit station id.
/// let bytes = [0x3E, 0xD0, 0x07];
/// assert_eq!(get_stream(&bytes, 0, 12), 1005);
/// assert_eq!(get_stream(&bytes, 12, 12), 7);
/// ```
#[inline]
pub fn get_stream(bytes: &[u8], at: usize, width: u32) -> u64 {
    let Some((first, last, after)) = span(bytes.len(), at, width) else {
        return 0;
    };
    let Some(b) = bytes.get(first..last) else {
        return 0;
    };
    (word(b).checked_shr(after).unwrap_or(0) as u64) & bit_mask(width)
}

/// Sets the `width`-bit member (1 to 64) at bit `at` of the stream `bytes` to `value`,
/// leaving every other bit as it is.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `value` does not fit `width` bits (it would be cut and
/// decode as another value) or the member does not lie inside `bytes`; nothing is written then.
///
/// ```
/// use protocol_runtime::bitstream::set_stream;
/// use protocol_runtime::EncodeError;
///
/// let mut bytes = [0u8; 3];
/// set_stream(&mut bytes, 0, 12, 1005)?;
/// set_stream(&mut bytes, 12, 12, 7)?;
/// assert_eq!(bytes, [0x3E, 0xD0, 0x07]);
/// assert!(set_stream(&mut bytes, 4, 4, 16).is_err());
/// # Ok::<(), EncodeError>(())
/// ```
#[inline]
pub fn set_stream(bytes: &mut [u8], at: usize, width: u32, value: u64) -> Result<(), EncodeError> {
    let out = EncodeError::ValueOutOfRange { place: Place::NONE };
    let mask = bit_mask(width);
    let (first, last, after) = span(bytes.len(), at, width)
        .filter(|_| value <= mask)
        .ok_or(out)?;
    let b = bytes.get_mut(first..last).ok_or(out)?;
    let keep = !(u128::from(mask) << after);
    let w = (word(b) & keep) | (u128::from(value) << after);
    let n = b.len();
    for (i, byte) in b.iter_mut().enumerate() {
        // Byte `i` holds bits `8 * k .. 8 * k + 8` of the word, `k` counted from its end.
        let k = n.wrapping_sub(1).wrapping_sub(i) as u32;
        *byte = w.checked_shr(k.wrapping_mul(8)).unwrap_or(0) as u8;
    }
    Ok(())
}

/// The `width`-bit two's complement value (1 to 64) in the low bits of `raw`, sign-extended:
/// its top bit copied into every bit above it.
///
/// ```
/// use protocol_runtime::bitstream::sign_extend;
/// assert_eq!(sign_extend(0x3F, 6), -1);
/// assert_eq!(sign_extend(0x1F, 6), 31);
/// assert_eq!(sign_extend(0x20_0000_0000, 38), -0x20_0000_0000);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub const fn sign_extend(raw: u64, width: u32) -> i64 {
    let unused = 64u32.saturating_sub(width);
    match (raw as i64).checked_shl(unused) {
        Some(up) => up >> unused,
        None => raw as i64,
    }
}

/// The low `width` bits (1 to 64) of `v` as two's complement, if `v` fits them: what a signed
/// member writes.
///
/// # Errors
///
/// [`EncodeError::ValueOutOfRange`] if `v` is outside `-2^(width-1)..2^(width-1)`: it would be
/// cut and decode as another value.
///
/// ```
/// use protocol_runtime::bitstream::signed_bits;
/// assert_eq!(signed_bits(-1, 6), Ok(0x3F));
/// assert_eq!(signed_bits(31, 6), Ok(0x1F));
/// assert!(signed_bits(32, 6).is_err());
/// assert!(signed_bits(-33, 6).is_err());
/// ```
#[inline]
pub fn signed_bits(v: i64, width: u32) -> Result<u64, EncodeError> {
    let fits = crate::wire::fit_signed(v, width)?;
    Ok(fits as u64 & bit_mask(width))
}

#[cfg(test)]
#[allow(
    clippy::unwrap_used,
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects
)]
mod tests {
    use super::*;

    /// The bit-by-bit definition, to check the word arithmetic against.
    fn slow_get(bytes: &[u8], at: usize, width: u32) -> u64 {
        (at..at + width as usize).fold(0u64, |v, k| {
            (v << 1) | u64::from((bytes[k / 8] >> (7 - k % 8)) & 1)
        })
    }

    #[test]
    fn every_width_and_position_matches_the_bit_by_bit_definition() {
        let bytes: [u8; 24] = core::array::from_fn(|i| (i * 37 + 11) as u8);
        // Miri interprets every step: there, every eleventh position, which still meets each
        // width at every bit offset within a byte.
        let step = if cfg!(miri) { 11 } else { 1 };
        for width in 1..=64u32 {
            for at in (0..=(bytes.len() * 8 - width as usize)).step_by(step) {
                let v = get_stream(&bytes, at, width);
                assert_eq!(v, slow_get(&bytes, at, width), "{width} at {at}");
                let mut copy = bytes;
                set_stream(&mut copy, at, width, v ^ bit_mask(width)).unwrap();
                assert_eq!(get_stream(&copy, at, width), v ^ bit_mask(width));
                set_stream(&mut copy, at, width, v).unwrap();
                assert_eq!(copy, bytes, "{width} at {at}: other bits kept");
            }
        }
    }

    #[test]
    fn out_of_range_values_and_positions_are_refused() {
        let mut bytes = [0u8; 4];
        assert!(set_stream(&mut bytes, 0, 12, 0x1000).is_err());
        assert!(set_stream(&mut bytes, 28, 5, 1).is_err());
        assert!(set_stream(&mut bytes, 0, 65, 1).is_err());
        assert!(set_stream(&mut bytes, 0, 0, 0).is_err());
        assert_eq!(bytes, [0u8; 4]);
        assert_eq!(get_stream(&bytes, 28, 5), 0);
        assert_eq!(get_stream(&bytes, usize::MAX, 8), 0);
    }

    #[test]
    fn signed_values_round_trip_at_every_width() {
        for width in 1..=64u32 {
            let (lo, hi) = (-(1i128 << (width - 1)), (1i128 << (width - 1)) - 1);
            for v in [lo, hi, 0, -1, lo + 1, hi - 1] {
                let Ok(v) = i64::try_from(v) else { continue };
                if i128::from(v) < lo || i128::from(v) > hi {
                    continue;
                }
                let raw = signed_bits(v, width).unwrap();
                assert!(raw <= bit_mask(width));
                assert_eq!(sign_extend(raw, width), v, "{v} in {width} bits");
            }
            if width < 64 {
                assert!(signed_bits((hi + 1) as i64, width).is_err());
                assert!(signed_bits((lo - 1) as i64, width).is_err());
            }
        }
    }
}
