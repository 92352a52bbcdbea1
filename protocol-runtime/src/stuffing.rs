//! Byte stuffing: a frame format may forbid a byte pattern inside its payload (Dynamixel 2.0
//! forbids its header `FF FF FD`) by inserting a byte after every occurrence of it. The length
//! field counts the stuffed bytes and the checks cover the stuffed frame, so the stream engine
//! sees stuffed frames only; payload code unstuffs before reading and stuffs after writing.

use crate::error::{DecodeError, EncodeError};

/// The rule: after every occurrence of `after`, the sender inserts `insert`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Stuffing<'a> {
    /// The pattern that must not appear as is (its last byte is the one inserted).
    pub after: &'a [u8],
    /// The byte inserted after each occurrence.
    pub insert: u8,
}

impl Stuffing<'_> {
    /// Number of occurrences of the pattern in `data` (non-overlapping, left to right).
    pub fn count(&self, data: &[u8]) -> usize {
        let n = self.after.len();
        if n == 0 {
            return 0;
        }
        let mut count = 0usize;
        let mut i = 0usize;
        while let Some(window) = data.get(i..i.saturating_add(n)) {
            if window == self.after {
                count = count.saturating_add(1);
                i = i.saturating_add(n);
            } else {
                i = i.saturating_add(1);
            }
        }
        count
    }

    /// Stuffs `buf[..len]` in place: inserts `insert` after every occurrence of the pattern,
    /// moving the bytes after it towards the end. Returns the stuffed length.
    ///
    /// Each insertion moves the rest of the data by one byte: quadratic in the worst case, but
    /// payloads are short and occurrences rare, and it needs no second buffer.
    ///
    /// # Errors
    ///
    /// [`EncodeError::BufferTooSmall`] if `buf` has no room for the inserted bytes.
    pub fn stuff_in_place(&self, buf: &mut [u8], len: usize) -> Result<usize, EncodeError> {
        let data = buf.get(..len).ok_or(EncodeError::BufferTooSmall {
            needed: len,
            available: buf.len(),
        })?;
        let total = len.saturating_add(self.count(data));
        if total > buf.len() {
            return Err(EncodeError::BufferTooSmall {
                needed: total,
                available: buf.len(),
            });
        }
        let n = self.after.len();
        if n == 0 {
            return Ok(len);
        }
        let mut cur = len;
        let mut i = 0usize;
        while i.saturating_add(n) <= cur {
            if buf.get(i..i.saturating_add(n)) == Some(self.after) {
                let end = i.saturating_add(n);
                buf.copy_within(end..cur, end.saturating_add(1));
                if let Some(b) = buf.get_mut(end) {
                    *b = self.insert;
                }
                cur = cur.saturating_add(1);
                // Skip the pattern and the inserted byte.
                i = end.saturating_add(1);
            } else {
                i = i.saturating_add(1);
            }
        }
        Ok(cur)
    }

    /// Removes the inserted bytes: copies `stuffed` into `out` without the byte that follows
    /// each occurrence of the pattern. Returns the unstuffed bytes.
    ///
    /// # Errors
    ///
    /// [`DecodeError::PayloadLength`] if `out` is too short; [`DecodeError::InvalidStuffing`]
    /// if a pattern is not followed by the inserted byte.
    pub fn unstuff<'o>(&self, stuffed: &[u8], out: &'o mut [u8]) -> Result<&'o [u8], DecodeError> {
        let n = self.after.len();
        let mut i = 0usize;
        let mut o = 0usize;
        while let Some(&b) = stuffed.get(i) {
            let slot = out.get_mut(o).ok_or(DecodeError::PayloadLength {
                expected: o,
                actual: stuffed.len(),
            })?;
            *slot = b;
            o = o.saturating_add(1);
            i = i.saturating_add(1);
            let ends_pattern =
                n > 0 && o >= n && out.get(o.saturating_sub(n)..o) == Some(self.after);
            if ends_pattern {
                match stuffed.get(i) {
                    Some(&x) if x == self.insert => i = i.saturating_add(1),
                    _ => return Err(DecodeError::InvalidStuffing),
                }
            }
        }
        Ok(out.get(..o).unwrap_or(&[]))
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

    const DXL: Stuffing<'static> = Stuffing {
        after: &[0xFF, 0xFF, 0xFD],
        insert: 0xFD,
    };

    #[test]
    fn stuffs_and_unstuffs_like_the_dynamixel_sdk() {
        // int32 -131073 = FF FF FD FF (LE) in a sync write: one FD inserted after FF FF FD.
        let cases: [(&[u8], &[u8]); 4] = [
            (
                &[0x01, 0xFF, 0xFF, 0xFD, 0xFF, 0x02],
                &[0x01, 0xFF, 0xFF, 0xFD, 0xFD, 0xFF, 0x02],
            ),
            (
                &[0x00, 0xFF, 0xFF, 0xFD, 0x00],
                &[0x00, 0xFF, 0xFF, 0xFD, 0xFD, 0x00],
            ),
            (&[0xFF, 0xFF, 0xFD], &[0xFF, 0xFF, 0xFD, 0xFD]),
            (
                &[0xFF, 0xFF, 0xFD, 0xFD, 0xFF, 0xFF, 0xFD],
                &[0xFF, 0xFF, 0xFD, 0xFD, 0xFD, 0xFF, 0xFF, 0xFD, 0xFD],
            ),
        ];
        for (plain, stuffed) in cases {
            let mut buf = [0u8; 16];
            buf[..plain.len()].copy_from_slice(plain);
            let n = DXL.stuff_in_place(&mut buf, plain.len()).expect("room");
            assert_eq!(&buf[..n], stuffed);
            let mut out = [0u8; 16];
            assert_eq!(DXL.unstuff(stuffed, &mut out), Ok(plain));
        }
        let mut small = [0xFF, 0xFF, 0xFD];
        assert!(DXL.stuff_in_place(&mut small, 3).is_err());
        let mut out = [0u8; 8];
        assert_eq!(
            DXL.unstuff(&[0xFF, 0xFF, 0xFD, 0x00], &mut out),
            Err(DecodeError::InvalidStuffing)
        );
    }
}
