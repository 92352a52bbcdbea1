//! Frame check algorithms: byte sums, xor, and CRCs from the [`crc`] crate.
//!
//! This module owns computing a check value over a byte range ([`Checksum::compute`]) and its
//! size on the wire ([`Checksum::width`]). Which bytes a check covers and where its value is
//! stored is the frame layout's business ([`crate::layout::Check`]).
//!
//! # CRC tables
//!
//! A CRC is a `&'static crc::Crc<W, I>` built in a `static` or `const`, wrapped in a [`CrcImpl`]
//! that names its table size, which trades memory for speed:
//!
//! | implementation | table | speed on 50-byte frames |
//! | --- | --- | --- |
//! | [`CrcImpl::NoTable`] (`crc::NoTable`) | none | slowest (bit by bit) |
//! | [`CrcImpl::Table1`] (`crc::Table<1>`) | 256 entries | about 3-5x slower than `Table<16>` |
//! | [`CrcImpl::Table16`] (`crc::Table<16>`) | 16 × 256 entries | fastest |
//!
//! Firmware short of flash picks `NoTable` or `Table1`; hosts pick `Table16`.
//!
//! ```
//! use protocol_runtime::checksum::{Checksum, CrcImpl};
//!
//! static CRC: crc::Crc<u16, crc::Table<16>> = crc::Crc::<u16, crc::Table<16>>::new(&crc::CRC_16_UMTS);
//! let check = Checksum::Crc16(CrcImpl::Table16(&CRC));
//! assert_eq!(check.width(), 2);
//! assert_eq!(check.compute(b"123456789"), 0xFEE8);
//! assert_eq!(Checksum::SumMod255.compute(b"123456789"), 0xDE);
//! ```

use core::fmt;

/// A check algorithm.
#[derive(Clone, Copy)]
pub enum Checksum<'a> {
    /// Sum of the bytes modulo 256.
    Sum8,
    /// Sum of the bytes modulo 255 (a value in `0..=254`).
    SumMod255,
    /// Xor of the bytes.
    Xor8,
    /// An 8-bit CRC.
    Crc8(CrcImpl<'a, u8>),
    /// A 16-bit CRC.
    Crc16(CrcImpl<'a, u16>),
    /// A 32-bit CRC.
    Crc32(CrcImpl<'a, u32>),
    /// A 64-bit CRC.
    Crc64(CrcImpl<'a, u64>),
}

/// A CRC of the [`crc`] crate, with its table size.
#[derive(Clone, Copy)]
pub enum CrcImpl<'a, W: crc::Width> {
    /// Bit by bit, no table.
    NoTable(&'a crc::Crc<W, crc::NoTable>),
    /// One 256-entry table.
    Table1(&'a crc::Crc<W, crc::Table<1>>),
    /// Slicing by 16: sixteen 256-entry tables.
    Table16(&'a crc::Crc<W, crc::Table<16>>),
}

macro_rules! crc_impl_width {
    ($($w:ty),*) => {$(
        impl CrcImpl<'_, $w> {
            #[doc = concat!("The CRC of `data` as a `", stringify!($w), "`.")]
            #[inline]
            pub fn checksum(&self, data: &[u8]) -> $w {
                match self {
                    CrcImpl::NoTable(c) => c.checksum(data),
                    CrcImpl::Table1(c) => c.checksum(data),
                    CrcImpl::Table16(c) => c.checksum(data),
                }
            }
        }
    )*};
}
crc_impl_width!(u8, u16, u32, u64);

impl<W: crc::Width> CrcImpl<'_, W> {
    /// The parameters of the CRC.
    #[inline]
    pub fn algorithm(&self) -> &'static crc::Algorithm<W> {
        match self {
            CrcImpl::NoTable(c) => c.algorithm,
            CrcImpl::Table1(c) => c.algorithm,
            CrcImpl::Table16(c) => c.algorithm,
        }
    }

    /// Number of 256-entry tables: 0, 1 or 16.
    #[inline]
    pub const fn table_lanes(&self) -> usize {
        match self {
            CrcImpl::NoTable(_) => 0,
            CrcImpl::Table1(_) => 1,
            CrcImpl::Table16(_) => 16,
        }
    }
}

impl<W: crc::Width + fmt::Debug> fmt::Debug for CrcImpl<'_, W> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let name = match self {
            CrcImpl::NoTable(_) => "NoTable",
            CrcImpl::Table1(_) => "Table1",
            CrcImpl::Table16(_) => "Table16",
        };
        f.debug_tuple(name).field(self.algorithm()).finish()
    }
}

impl fmt::Debug for Checksum<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Checksum::Sum8 => f.write_str("Sum8"),
            Checksum::SumMod255 => f.write_str("SumMod255"),
            Checksum::Xor8 => f.write_str("Xor8"),
            Checksum::Crc8(c) => f.debug_tuple("Crc8").field(c).finish(),
            Checksum::Crc16(c) => f.debug_tuple("Crc16").field(c).finish(),
            Checksum::Crc32(c) => f.debug_tuple("Crc32").field(c).finish(),
            Checksum::Crc64(c) => f.debug_tuple("Crc64").field(c).finish(),
        }
    }
}

impl Checksum<'_> {
    /// Bytes of the stored check value: 1 for the sums, xor and CRC-8, then 2, 4 or 8.
    #[inline]
    pub const fn width(&self) -> usize {
        match self {
            Checksum::Sum8 | Checksum::SumMod255 | Checksum::Xor8 | Checksum::Crc8(_) => 1,
            Checksum::Crc16(_) => 2,
            Checksum::Crc32(_) => 4,
            Checksum::Crc64(_) => 8,
        }
    }

    /// The check value of `data`, in the low [`width`](Self::width) bytes of the result.
    ///
    /// ```
    /// use protocol_runtime::Checksum;
    ///
    /// assert_eq!(Checksum::Sum8.compute(&[0xFF, 0x02]), 0x01);
    /// assert_eq!(Checksum::Xor8.compute(&[0x0F, 0xF0]), 0xFF);
    /// ```
    #[inline]
    pub fn compute(&self, data: &[u8]) -> u64 {
        match self {
            Checksum::Sum8 => byte_sum(data) & 0xFF,
            Checksum::SumMod255 => byte_sum(data).checked_rem(255).unwrap_or(0),
            Checksum::Xor8 => u64::from(xor8(data)),
            Checksum::Crc8(c) => u64::from(c.checksum(data)),
            Checksum::Crc16(c) => u64::from(c.checksum(data)),
            Checksum::Crc32(c) => u64::from(c.checksum(data)),
            Checksum::Crc64(c) => c.checksum(data),
        }
    }
}

/// Bytes summed or xored per step: one SSE2 register, which the compiler fills for a loop over
/// fixed-size arrays (`psadbw` for the sum).
const STEP: usize = 16;

/// `MASK[r..r + STEP]` keeps the last `r` bytes of a `STEP`-byte window.
#[rustfmt::skip]
const MASK: [u8; 2 * STEP] = [
    0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
    0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
];

/// The last `STEP` bytes of `data` (at least `STEP` long), masked to keep the last `rest`
/// (`< STEP`) of them: the bytes a whole-step loop from the start left over, read without a
/// byte loop. A frame's length varies from one frame to the next; a byte loop over its tail
/// would mispredict on every frame.
#[inline(always)]
fn masked_tail(data: &[u8], rest: usize) -> [u8; STEP] {
    let mut tail = data.last_chunk::<STEP>().copied().unwrap_or([0; STEP]);
    let mask = MASK
        .get(rest..)
        .and_then(<[u8]>::first_chunk::<STEP>)
        .unwrap_or(&[0; STEP]);
    for (b, m) in tail.iter_mut().zip(mask) {
        *b &= m;
    }
    tail
}

/// `data` (shorter than `STEP`), zero-extended.
#[inline(always)]
fn padded(data: &[u8]) -> [u8; STEP] {
    let mut block = [0u8; STEP];
    for (dst, src) in block.iter_mut().zip(data) {
        *dst = *src;
    }
    block
}

/// Splits `data` into whole steps and what is left, as one zero-filled step.
#[inline(always)]
fn steps(data: &[u8]) -> (core::slice::ChunksExact<'_, u8>, [u8; STEP]) {
    let whole = data.chunks_exact(STEP);
    let rest = whole.remainder().len();
    let last = if data.len() < STEP {
        padded(data)
    } else {
        masked_tail(data, rest)
    };
    (whole, last)
}

#[inline(always)]
fn sum_step(block: &[u8; STEP]) -> u64 {
    block
        .iter()
        .map(|&b| u64::from(b))
        .fold(0, u64::wrapping_add)
}

/// The exact sum of all bytes.
#[inline]
fn byte_sum(data: &[u8]) -> u64 {
    let (whole, last) = steps(data);
    let mut total = sum_step(&last);
    for block in whole {
        if let Ok(block) = <&[u8; STEP]>::try_from(block) {
            total = total.wrapping_add(sum_step(block));
        }
    }
    total
}

/// The xor of all bytes.
#[inline]
fn xor8(data: &[u8]) -> u8 {
    let (whole, last) = steps(data);
    let mut acc = u128::from_le_bytes(last);
    for block in whole {
        if let Ok(block) = <[u8; STEP]>::try_from(block) {
            acc ^= u128::from_le_bytes(block);
        }
    }
    acc.to_le_bytes().iter().fold(0, |x, b| x ^ b)
}

#[cfg(test)]
#[allow(clippy::indexing_slicing, clippy::arithmetic_side_effects)]
mod tests {
    use super::*;

    const CHECK: &[u8] = b"123456789";

    /// A xorshift64 generator: deterministic test data without dependencies.
    fn fill(seed: &mut u64, buf: &mut [u8]) {
        for b in buf {
            *seed ^= *seed << 13;
            *seed ^= *seed >> 7;
            *seed ^= *seed << 17;
            *b = (*seed >> 24) as u8;
        }
    }

    #[test]
    fn sums_match_naive_definitions_for_every_length() {
        let mut seed = 0x9E37_79B9_7F4A_7C15;
        let mut buf = [0u8; 300];
        for round in 0..4 {
            fill(&mut seed, &mut buf);
            if round == 3 {
                buf.fill(0xFF);
            }
            for len in 0..buf.len() {
                let data = &buf[..len];
                let sum: u64 = data.iter().map(|&b| u64::from(b)).sum();
                let xor = data.iter().fold(0u8, |a, b| a ^ b);
                assert_eq!(Checksum::Sum8.compute(data), sum % 256, "len {len}");
                assert_eq!(Checksum::SumMod255.compute(data), sum % 255, "len {len}");
                assert_eq!(Checksum::Xor8.compute(data), u64::from(xor), "len {len}");
            }
        }
    }

    #[test]
    fn sums_of_long_inputs_are_exact() {
        let buf = [0xFFu8; 5000];
        for len in [1023, 1024, 1025, 2048, 4999, 5000] {
            let sum = 255 * len as u64;
            assert_eq!(byte_sum(&buf[..len]), sum);
            assert_eq!(Checksum::SumMod255.compute(&buf[..len]), sum % 255);
        }
    }

    #[test]
    fn sum_mod_255_check_value() {
        assert_eq!(Checksum::SumMod255.compute(CHECK), 0xDE);
        assert_eq!(Checksum::Sum8.compute(CHECK), 0xDD);
        assert_eq!(Checksum::Xor8.compute(CHECK), 0x31);
    }

    /// Checks all three table variants of one algorithm against its catalogue check value.
    macro_rules! check_all_tables {
        ($w:ty, $variant:ident, $alg:expr) => {{
            static NO: crc::Crc<$w, crc::NoTable> = crc::Crc::<$w, crc::NoTable>::new($alg);
            static T1: crc::Crc<$w, crc::Table<1>> = crc::Crc::<$w, crc::Table<1>>::new($alg);
            static T16: crc::Crc<$w, crc::Table<16>> = crc::Crc::<$w, crc::Table<16>>::new($alg);
            let expected = u64::from($alg.check);
            for c in [
                Checksum::$variant(CrcImpl::NoTable(&NO)),
                Checksum::$variant(CrcImpl::Table1(&T1)),
                Checksum::$variant(CrcImpl::Table16(&T16)),
            ] {
                assert_eq!(c.compute(CHECK), expected, "{c:?}");
                assert_eq!(c.width(), core::mem::size_of::<$w>());
            }
            expected
        }};
    }

    #[test]
    fn catalogue_crcs_match_their_check_values() {
        assert_eq!(check_all_tables!(u8, Crc8, &crc::CRC_8_MAXIM_DOW), 0xA1);
        assert_eq!(check_all_tables!(u16, Crc16, &crc::CRC_16_UMTS), 0xFEE8);
        assert_eq!(check_all_tables!(u16, Crc16, &crc::CRC_16_MCRF4XX), 0x6F91);
        assert_eq!(
            check_all_tables!(u32, Crc32, &crc::CRC_32_ISO_HDLC),
            0xCBF4_3926
        );
        assert_eq!(
            check_all_tables!(u64, Crc64, &crc::CRC_64_XZ),
            0x995D_C9BB_DF19_39FA
        );
        assert_eq!(
            check_all_tables!(u64, Crc64, &crc::CRC_64_ECMA_182),
            0x6C40_DF5F_0B49_7347
        );
    }

    static DJI_CRC8: crc::Algorithm<u8> = crc::Algorithm {
        width: 8,
        poly: 0x31,
        init: 0xFF,
        refin: true,
        refout: true,
        xorout: 0,
        check: 0x0B,
        residue: 0,
    };
    static DJI_CRC16: crc::Algorithm<u16> = crc::Algorithm {
        width: 16,
        poly: 0x8005,
        init: 0xC55C,
        refin: true,
        refout: true,
        xorout: 0,
        check: 0x2752,
        residue: 0,
    };
    static DJI_CRC32: crc::Algorithm<u32> = crc::Algorithm {
        width: 32,
        poly: 0x04C1_1DB7,
        init: 0xC55C_0000,
        refin: true,
        refout: true,
        xorout: 0,
        check: 0xE4D9_DC14,
        residue: 0,
    };

    #[test]
    fn dji_custom_crcs_match_their_check_values() {
        assert_eq!(check_all_tables!(u16, Crc16, &DJI_CRC16), 0x2752);
        assert_eq!(check_all_tables!(u32, Crc32, &DJI_CRC32), 0xE4D9_DC14);
        static T: crc::Crc<u8, crc::Table<1>> = crc::Crc::<u8, crc::Table<1>>::new(&DJI_CRC8);
        // The referee header A5 03 00 00 carries CRC-8 0x27 (a published frame).
        assert_eq!(
            Checksum::Crc8(CrcImpl::Table1(&T)).compute(&[0xA5, 0x03, 0x00, 0x00]),
            0x27
        );
        // And its check value (protocols.md: 0x0B; the catalogue's MAXIM-DOW with init 0 is 0xA1).
        assert_eq!(check_all_tables!(u8, Crc8, &DJI_CRC8), 0x0B);
    }

    #[test]
    fn debug_names_the_algorithm_and_table() {
        extern crate std;
        use std::format;
        static T: crc::Crc<u16, crc::Table<16>> =
            crc::Crc::<u16, crc::Table<16>>::new(&crc::CRC_16_UMTS);
        let text = format!("{:?}", Checksum::Crc16(CrcImpl::Table16(&T)));
        assert!(text.starts_with("Crc16(Table16(Algorithm"), "{text}");
        assert_eq!(format!("{:?}", Checksum::SumMod255), "SumMod255");
        assert_eq!(CrcImpl::Table16(&T).table_lanes(), 16);
    }
}
