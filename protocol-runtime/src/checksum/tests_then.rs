//! A CRC then one more byte (MAVLink's CRC_EXTRA): [`Slicing16::then`] and the [`Extra`]
//! check against `crc::Crc<W, NoTable>` over the bytes and the byte, for CRCs of every kind
//! (reflected or not, `refin != refout`, widths below their word), at every length that
//! takes a different path (the short checks, the leading block, whole blocks).

#![allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::cast_possible_truncation
)]

extern crate std;

use std::vec::Vec;

use super::*;
use crate::layout::{ByteOrder, Pos, WordField};

/// Deterministic test data (a xorshift64 generator).
fn random(len: usize) -> Vec<u8> {
    let mut seed = 0x0DD_BA11_u64;
    (0..len)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 24) as u8
        })
        .collect()
}

/// For each algorithm named: the CRC of `data[..n]` then a byte, by `Slicing16` (as the prefix
/// of a longer input, and as bytes just written) and by both `CrcImpl`s with a table, equals
/// the table-free CRC of the bytes and the byte.
macro_rules! check_then {
    ($w:ty: $($alg:ident),* $(,)?) => {$(
        {
            #[inline(never)]
            fn one(buf: &[u8]) {
                let alg: &'static crc::Algorithm<$w> = &crc::$alg;
                let reference = crc::Crc::<$w, crc::NoTable>::new(alg);
                let fast = std::boxed::Box::new(Slicing16::<$w>::new(alg));
                let one = crc::Crc::<$w, crc::Table<1>>::new(alg);
                // (Under Miri, which interprets every step, every 37th length.)
                for n in (0..=200).step_by(if cfg!(miri) { 37 } else { 1 }) {
                    let byte = buf[n + 7];
                    let mut digest = reference.digest();
                    digest.update(&buf[..n]);
                    digest.update(&[byte]);
                    let want = digest.finalize();
                    let name = stringify!($alg);
                    assert_eq!(fast.checksum_prefix_then(buf, n, byte), want, "{name} n {n}");
                    assert_eq!(fast.checksum_written_then(&buf[..n], byte), want, "{name} w {n}");
                    assert_eq!(fast.then(fast.checksum(&buf[..n]), byte), want, "{name} {n}");
                    let t16 = CrcImpl::Table16(&fast);
                    assert_eq!(t16.checksum_prefix_then(buf, n, byte), want, "{name} {n}");
                    assert_eq!(CrcImpl::Table1(&one).checksum_then(&buf[..n], byte), want);
                }
            }
            one(&random(300));
        }
    )*};
}

#[test]
fn a_byte_appended_to_a_crc_is_the_crc_of_the_bytes_and_the_byte() {
    check_then!(u8: CRC_3_GSM, CRC_3_ROHC, CRC_4_G_704, CRC_7_MMC, CRC_8_SMBUS, CRC_8_ROHC);
    check_then!(u16: CRC_12_UMTS, CRC_11_FLEXRAY, CRC_16_MCRF4XX, CRC_16_UMTS, CRC_16_KERMIT);
    check_then!(u32: CRC_24_OPENPGP, CRC_32_ISO_HDLC, CRC_32_BZIP2, CRC_32_ISCSI);
    check_then!(u64: CRC_40_GSM, CRC_64_XZ, CRC_64_ECMA_182);
}

static MCRF4XX_16: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);
static MCRF4XX_1: crc::Crc<u16, crc::Table<1>> =
    crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_MCRF4XX);

/// The pairs of [`mavlink_extra`]: three ids below 256 and one above.
const PAIRS: [(u32, u8); 4] = [(0, 50), (30, 39), (33, 104), (70_000, 7)];
/// The bytes of the ids below 34, as a table indexed by id.
static DIRECT: [u16; 34] = direct_table(&PAIRS);

/// MAVLink 2's check: the key is the 24-bit message id at the sixth covered byte; with
/// `direct`, the ids below 34 are read from [`DIRECT`] and the pairs hold the others.
fn mavlink_extra(crc: Checksum<'static>, direct: bool) -> Extra<'static> {
    let (direct, bytes): (&[u16], &[(u32, u8)]) = if direct {
        (&DIRECT, &PAIRS[3..])
    } else {
        (&[], &PAIRS)
    };
    Extra {
        crc,
        key: WordField {
            at: Pos::Start(6),
            size: 3,
            order: ByteOrder::Little,
            shift: 0,
            width: 24,
        },
        direct,
        bytes,
    }
}

#[test]
fn an_extra_check_has_one_value_whatever_its_table() {
    for direct in [false, true] {
        let sixteen = mavlink_extra(Checksum::Crc16(CrcImpl::Table16(&MCRF4XX_16)), direct);
        let one = mavlink_extra(Checksum::Crc16(CrcImpl::Table1(&MCRF4XX_1)), false);
        one_value_whatever_the_table(Checksum::Extra(&sixteen), Checksum::Extra(&one));
    }
}

/// `sixteen` and `one` (the same check, built with other tables or lookups) give the same
/// values for every id and length.
fn one_value_whatever_the_table(sixteen: Checksum<'_>, one: Checksum<'_>) {
    let mut buf = random(400);
    // Id 5 has no byte, and neither has id 34, the first past the direct table.
    for (round, id) in [0u32, 30, 33, 70_000, 5, 34].into_iter().enumerate() {
        buf[6..9].copy_from_slice(&id.to_le_bytes()[..3]);
        for n in 9..=300 {
            let want = one.compute_prefix(&buf, n);
            assert_eq!(want.is_some(), round < 4, "id {id}");
            assert_eq!(sixteen.compute_prefix(&buf, n), want, "id {id} n {n}");
            assert_eq!(sixteen.compute_prefix(&buf[..n], n), want, "id {id} n {n}");
            let plain = want.unwrap_or_else(|| one.compute(&buf[..n]));
            assert_eq!(sixteen.compute(&buf[..n]), plain, "id {id} n {n}");
            assert_eq!(sixteen.compute_written(&buf[..n]), plain, "id {id} n {n}");
        }
        assert_eq!(sixteen.compute_prefix(&buf[..20], 21), None);
    }
}
