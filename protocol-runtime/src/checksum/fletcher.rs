//! Fletcher's checksums: two running sums, `A` of the bytes and `B` of the successive `A`s,
//! stored as the value `B << 8 | A`.
//!
//! This module owns computing them; which one a check uses is the parent module's business.

/// Bytes added before the modulo 255 sums are reduced: from `A, B < 255`, after 256 bytes
/// `A < 255 + 256 × 255 < 2^16` and `B < 255 + 256 × 2^16 < 2^25`, far inside a `u32`.
const BLOCK: usize = 256;

/// Fletcher-16: both sums modulo 255.
#[inline]
pub(super) fn fletcher16(data: &[u8]) -> u16 {
    let (mut a, mut b) = (0u32, 0u32);
    for block in data.chunks(BLOCK) {
        for &byte in block {
            a = a.wrapping_add(u32::from(byte));
            b = b.wrapping_add(a);
        }
        a = a.checked_rem(255).unwrap_or(0);
        b = b.checked_rem(255).unwrap_or(0);
    }
    ((b as u16) << 8) | a as u16
}

/// Fletcher's sums modulo 256 (u-blox UBX's `CK_A`, `CK_B`).
#[inline]
pub(super) fn fletcher16_mod256(data: &[u8]) -> u16 {
    let (mut a, mut b) = (0u8, 0u8);
    for &byte in data {
        a = a.wrapping_add(byte);
        b = b.wrapping_add(a);
    }
    (u16::from(b) << 8) | u16::from(a)
}
