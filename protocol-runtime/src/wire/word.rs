//! Unsigned words at fixed positions of a frame: [`read_uint`], [`write_uint`] and the bit
//! fields of a [`WordField`] (a length, a version, a flag sharing a word with others).
//!
//! This module owns how a header or trailer value is found in a frame; which values a layout
//! holds, and what they mean, is [`crate::layout`]'s and the engine's business.

use crate::layout::{ByteOrder, WordField};

/// The `N` bytes at `offset`, if they exist.
#[cfg_attr(not(protocol_opt0), inline(always))]
fn chunk_at<const N: usize>(bytes: &[u8], offset: usize) -> Option<[u8; N]> {
    bytes.get(offset..)?.first_chunk::<N>().copied()
}

/// Writes `bytes` over `word` (of the same length).
#[cfg_attr(not(protocol_opt0), inline(always))]
fn put<const N: usize>(word: &mut [u8], bytes: [u8; N]) -> Option<()> {
    word.first_chunk_mut::<N>()?.copy_from_slice(&bytes);
    Some(())
}

/// Reads an unsigned word of `size` bytes (1 to 8) at `offset`.
///
/// Returns `None` if the word does not lie inside `bytes` or `size` is not in `1..=8`.
///
/// ```
/// use protocol_runtime::layout::ByteOrder;
/// use protocol_runtime::wire::read_uint;
///
/// let bytes = [0x00, 0x12, 0x34, 0x56];
/// assert_eq!(read_uint(&bytes, 1, 2, ByteOrder::Big), Some(0x1234));
/// assert_eq!(read_uint(&bytes, 1, 3, ByteOrder::Little), Some(0x56_3412));
/// assert_eq!(read_uint(&bytes, 3, 2, ByteOrder::Big), None);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn read_uint(bytes: &[u8], offset: usize, size: u8, order: ByteOrder) -> Option<u64> {
    // One fixed-size load per common size: no byte loop, no call to memcpy.
    match (size, order) {
        (1, _) => bytes.get(offset).map(|&b| u64::from(b)),
        (2, ByteOrder::Little) => chunk_at(bytes, offset).map(|w| u64::from(u16::from_le_bytes(w))),
        (2, ByteOrder::Big) => chunk_at(bytes, offset).map(|w| u64::from(u16::from_be_bytes(w))),
        (4, ByteOrder::Little) => chunk_at(bytes, offset).map(|w| u64::from(u32::from_le_bytes(w))),
        (4, ByteOrder::Big) => chunk_at(bytes, offset).map(|w| u64::from(u32::from_be_bytes(w))),
        (8, ByteOrder::Little) => chunk_at(bytes, offset).map(u64::from_le_bytes),
        (8, ByteOrder::Big) => chunk_at(bytes, offset).map(u64::from_be_bytes),
        (3 | 5 | 6 | 7, _) => {
            let word = bytes.get(offset..offset.checked_add(usize::from(size))?)?;
            let push = |acc: u64, b: &u8| (acc << 8) | u64::from(*b);
            Some(match order {
                ByteOrder::Little => word.iter().rev().fold(0, push),
                ByteOrder::Big => word.iter().fold(0, push),
            })
        }
        _ => None,
    }
}

/// Writes `value` as an unsigned word of `size` bytes (1 to 8) at `offset`.
///
/// Returns `None`, writing nothing, if the word does not lie inside `bytes`, `size` is not in
/// `1..=8` or `value` does not fit in `size` bytes.
///
/// ```
/// use protocol_runtime::layout::ByteOrder;
/// use protocol_runtime::wire::write_uint;
///
/// let mut bytes = [0u8; 3];
/// assert_eq!(write_uint(&mut bytes, 1, 2, ByteOrder::Little, 0x1234), Some(()));
/// assert_eq!(bytes, [0x00, 0x34, 0x12]);
/// assert_eq!(write_uint(&mut bytes, 0, 1, ByteOrder::Big, 0x100), None);
/// ```
#[cfg_attr(not(protocol_opt0), inline(always))]
pub fn write_uint(
    bytes: &mut [u8],
    offset: usize,
    size: u8,
    order: ByteOrder,
    value: u64,
) -> Option<()> {
    if size == 0 || size > 8 {
        return None;
    }
    // A shift by 64 (an 8-byte word) is `None`: every value fits.
    if value
        .checked_shr(u32::from(size).wrapping_mul(8))
        .unwrap_or(0)
        != 0
    {
        return None;
    }
    let word = bytes.get_mut(offset..offset.checked_add(usize::from(size))?)?;
    // One fixed-size store per common size: no byte loop through a copy on the stack.
    match (size, order) {
        (1, _) => {
            if let Some(b) = word.first_mut() {
                *b = value as u8;
            }
            return Some(());
        }
        (2, ByteOrder::Little) => return put(word, (value as u16).to_le_bytes()),
        (2, ByteOrder::Big) => return put(word, (value as u16).to_be_bytes()),
        (4, ByteOrder::Little) => return put(word, (value as u32).to_le_bytes()),
        (4, ByteOrder::Big) => return put(word, (value as u32).to_be_bytes()),
        (8, ByteOrder::Little) => return put(word, value.to_le_bytes()),
        (8, ByteOrder::Big) => return put(word, value.to_be_bytes()),
        _ => {}
    }
    match order {
        ByteOrder::Little => word
            .iter_mut()
            .zip(value.to_le_bytes())
            .for_each(|(d, s)| *d = s),
        ByteOrder::Big => {
            word.iter_mut()
                .rev()
                .zip(value.to_be_bytes().into_iter().rev())
                .for_each(|(d, s)| *d = s);
        }
    }
    Some(())
}

impl WordField {
    /// Whether the field is well formed: `size` in `1..=8`, `width >= 1` and the bits
    /// `shift..shift + width` inside the word. Reads and writes of a malformed field return
    /// `None`.
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn is_valid(&self) -> bool {
        let bits = (self.size as u32).wrapping_mul(8);
        let top = (self.shift as u32).wrapping_add(self.width as u32);
        self.size >= 1 && self.size <= 8 && self.width >= 1 && top <= bits
    }

    /// The largest value the field holds: `2^width - 1`.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// let len = WordField { at: Pos::Start(1), size: 2, order: ByteOrder::Little, shift: 0, width: 10 };
    /// assert_eq!(len.max_value(), 1023);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub const fn max_value(&self) -> u64 {
        if self.width == 0 {
            0
        } else if self.width >= 64 {
            u64::MAX
        } else {
            u64::MAX.wrapping_shr(64u32.wrapping_sub(self.width as u32))
        }
    }

    /// Reads the field from `frame`: resolves `at` against `frame.len()`, reads the word and
    /// extracts bits `shift..shift + width`.
    ///
    /// Returns `None` if the word lies outside `frame` or the field is malformed.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// // A 10-bit length and a 6-bit version sharing a little-endian u16.
    /// let len = WordField { at: Pos::Start(1), size: 2, order: ByteOrder::Little, shift: 0, width: 10 };
    /// let ver = WordField { shift: 10, width: 6, ..len };
    /// let frame = [0xAA, 0x2C, 0x0C];
    /// assert_eq!(len.read(&frame), Some(0x02C));
    /// assert_eq!(ver.read(&frame), Some(3));
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn read(&self, frame: &[u8]) -> Option<u64> {
        if !self.is_valid() {
            return None;
        }
        let offset = self.at.resolve(frame.len())?;
        let word = read_uint(frame, offset, self.size, self.order)?;
        Some(word.checked_shr(u32::from(self.shift))? & self.max_value())
    }

    /// Writes `value` into the field's bits of `frame`, keeping the word's other bits.
    ///
    /// Returns `None`, writing nothing, if the word lies outside `frame`, the field is malformed
    /// or `value` does not fit in `width` bits.
    ///
    /// ```
    /// use protocol_runtime::layout::{ByteOrder, Pos, WordField};
    ///
    /// let ver = WordField { at: Pos::Start(0), size: 2, order: ByteOrder::Little, shift: 10, width: 6 };
    /// let mut frame = [0xFF, 0x03];
    /// assert_eq!(ver.write(&mut frame, 5), Some(()));
    /// assert_eq!(frame, [0xFF, 0x17]);
    /// assert_eq!(ver.write(&mut frame, 64), None);
    /// ```
    #[cfg_attr(not(protocol_opt0), inline(always))]
    pub fn write(&self, frame: &mut [u8], value: u64) -> Option<()> {
        if !self.is_valid() || value > self.max_value() {
            return None;
        }
        let offset = self.at.resolve(frame.len())?;
        if self.shift == 0 && u32::from(self.width) == u32::from(self.size).wrapping_mul(8) {
            // The whole word: nothing of it to keep, no read back.
            return write_uint(frame, offset, self.size, self.order, value);
        }
        let word = read_uint(frame, offset, self.size, self.order)?;
        let shift = u32::from(self.shift);
        let mask = self.max_value().checked_shl(shift)?;
        let word = (word & !mask) | value.checked_shl(shift)?;
        write_uint(frame, offset, self.size, self.order, word)
    }
}

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::layout::Pos;

    #[test]
    fn uints_of_every_size() {
        let bytes = [1, 2, 3, 4, 5, 6, 7, 8, 9];
        assert_eq!(
            read_uint(&bytes, 0, 8, ByteOrder::Big),
            Some(0x0102_0304_0506_0708)
        );
        assert_eq!(
            read_uint(&bytes, 1, 8, ByteOrder::Little),
            Some(0x0908_0706_0504_0302)
        );
        assert_eq!(read_uint(&bytes, 2, 0, ByteOrder::Little), None);
        assert_eq!(read_uint(&bytes, 0, 9, ByteOrder::Little), None);
        assert_eq!(read_uint(&bytes, usize::MAX, 1, ByteOrder::Little), None);
        let mut out = [0u8; 9];
        for size in 1..=8u8 {
            let max = u64::MAX >> (64 - 8 * u32::from(size));
            for order in [ByteOrder::Little, ByteOrder::Big] {
                write_uint(&mut out, 1, size, order, max - 1).unwrap();
                assert_eq!(read_uint(&out, 1, size, order), Some(max - 1));
                if size < 8 {
                    assert_eq!(write_uint(&mut out, 1, size, order, max + 1), None);
                }
            }
        }
        assert_eq!(write_uint(&mut out, 8, 2, ByteOrder::Big, 0), None);
    }

    #[test]
    fn word_fields_narrow_to_their_bits() {
        let field = WordField {
            at: Pos::End(3),
            size: 2,
            order: ByteOrder::Big,
            shift: 4,
            width: 8,
        };
        let mut frame = [0u8, 0xA0, 0x0B, 0xFF];
        assert_eq!(field.read(&frame), Some(0x00));
        field.write(&mut frame, 0xCD).unwrap();
        assert_eq!(frame, [0, 0xAC, 0xDB, 0xFF]);
        assert_eq!(field.read(&frame), Some(0xCD));
        assert_eq!(field.write(&mut frame, 0x100), None);
        assert_eq!(field.read(&frame[..1]), None);
        let bad = WordField { shift: 9, ..field };
        assert!(!bad.is_valid());
        assert_eq!(bad.read(&frame), None);
        let full = WordField {
            at: Pos::Start(0),
            size: 8,
            order: ByteOrder::Little,
            shift: 0,
            width: 64,
        };
        assert_eq!(full.max_value(), u64::MAX);
        let mut eight = [0u8; 8];
        full.write(&mut eight, u64::MAX).unwrap();
        assert_eq!(full.read(&eight), Some(u64::MAX));
        assert_eq!(WordField { width: 0, ..full }.max_value(), 0);
    }
}
