//! Checks that are not a whole register of bytes or start from a constant: every CRC of the
//! `crc` crate's catalogue whose width is not 8, 16, 32 or 64 (stored in the fewest whole
//! bytes, checked against the catalogue's `check` value with every table size), and the sums
//! and xors seeded with a constant, against naive loops.

#![allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::panic
)]

use super::*;
use crate::layout::{ByteOrder, Check, Pos};

const CHECK: &[u8] = b"123456789";

/// Each narrow catalogue CRC, with all three table sizes: its `check` value over
/// "123456789", the same with bytes past the covered ones, and its stored size.
#[test]
fn narrow_catalogue_crcs_give_their_check_values() {
    macro_rules! narrow {
        ($w:ty, $ctor:ident, $($alg:ident),*) => {$({
            // A function per algorithm: its frame (a `Slicing16` on the stack) is reused by
            // the next, not added to one frame of every algorithm.
            #[inline(never)]
            fn one() {
            let alg = &crc::$alg;
            let none = crc::Crc::<$w, crc::NoTable>::new(alg);
            let one = crc::Crc::<$w, crc::Table<1>>::new(alg);
            let sixteen = Slicing16::<$w>::new(alg);
            for check in [
                Checksum::$ctor(CrcImpl::NoTable(&none)),
                Checksum::$ctor(CrcImpl::Table1(&one)),
                Checksum::$ctor(CrcImpl::Table16(&sixteen)),
            ] {
                let name = stringify!($alg);
                assert_eq!(check.compute(CHECK), u64::from(alg.check), "{name}");
                assert_eq!(check.compute_prefix(b"123456789abcdefgh", 9), Some(u64::from(alg.check)), "{name}");
                assert_eq!(check.width(), usize::from(alg.width).div_ceil(8), "{name}");
            }
            }
            one();
        })*};
    }
    narrow!(
        u8,
        Crc8,
        CRC_3_GSM,
        CRC_3_ROHC,
        CRC_4_G_704,
        CRC_4_INTERLAKEN,
        CRC_5_EPC_C1G2,
        CRC_5_G_704,
        CRC_5_USB,
        CRC_6_CDMA2000_A,
        CRC_6_CDMA2000_B,
        CRC_6_DARC,
        CRC_6_G_704,
        CRC_6_GSM,
        CRC_7_MMC,
        CRC_7_ROHC,
        CRC_7_UMTS
    );
    narrow!(
        u16,
        Crc16,
        CRC_10_ATM,
        CRC_10_CDMA2000,
        CRC_10_GSM,
        CRC_11_FLEXRAY,
        CRC_11_UMTS,
        CRC_12_CDMA2000,
        CRC_12_DECT,
        CRC_12_GSM,
        CRC_12_UMTS,
        CRC_13_BBC,
        CRC_14_DARC,
        CRC_14_GSM,
        CRC_15_CAN,
        CRC_15_MPT1327
    );
    narrow!(
        u32,
        Crc32,
        CRC_17_CAN_FD,
        CRC_21_CAN_FD,
        CRC_24_BLE,
        CRC_24_FLEXRAY_A,
        CRC_24_FLEXRAY_B,
        CRC_24_INTERLAKEN,
        CRC_24_LTE_A,
        CRC_24_LTE_B,
        CRC_24_OPENPGP,
        CRC_24_OS_9,
        CRC_30_CDMA,
        CRC_31_PHILIPS
    );
    narrow!(u64, Crc64, CRC_40_GSM);
}

/// A CRC-24 check stored big-endian in three bytes after the bytes it covers: the value the
/// layout stores is the catalogue's, in three bytes, and a changed byte fails it.
#[test]
fn a_crc24_is_stored_in_three_bytes() {
    static CRC: Slicing16<u32> = Slicing16::<u32>::new(&crc::CRC_24_LTE_A);
    let check = Check {
        checksum: Checksum::Crc32(CrcImpl::Table16(&CRC)),
        from: Pos::Start(0),
        to: Pos::End(3),
        at: Pos::End(3),
        order: ByteOrder::Big,
    };
    let mut frame = *b"123456789\0\0\0";
    check.store(&mut frame).unwrap();
    let want = crc::CRC_24_LTE_A.check.to_be_bytes();
    assert_eq!(&frame[9..], &want[1..]);
    assert!(check.verify(&frame));
    frame[4] ^= 1;
    assert!(!check.verify(&frame));
}

/// A sum seeded with a constant is the sum of the seed and the bytes, modulo its width, then
/// xored; a seeded XOR is the XOR of the seed and the bytes. Every length up to 300 bytes,
/// whole and as a prefix of a longer input (the window paths).
#[test]
fn seeded_sums_and_xors_match_naive_loops() {
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut buf = [0u8; 340];
    for b in &mut buf {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        *b = (seed >> 24) as u8;
    }
    let sum8 = Checksum::Sum {
        width: 1,
        init: 0xA5,
        xorout: 0x0F,
    };
    let sum16 = Checksum::Sum {
        width: 2,
        init: 0xFFF0,
        xorout: 0,
    };
    let xor = Checksum::Xor { init: 0x5A };
    assert_eq!((sum8.width(), sum16.width(), xor.width()), (1, 2, 1));
    // (Under Miri, which interprets every step, every 37th length.)
    for n in (0..=300).step_by(if cfg!(miri) { 37 } else { 1 }) {
        let data = &buf[..n];
        let total: u64 = data.iter().map(|&b| u64::from(b)).sum();
        let x = data.iter().fold(0x5Au8, |x, &b| x ^ b);
        let want = [
            ((total + 0xA5) % 256) ^ 0x0F,
            (total + 0xFFF0) % 65536,
            u64::from(x),
        ];
        for (check, want) in [sum8, sum16, xor].iter().zip(want) {
            assert_eq!(check.compute(data), want, "{check:?} n {n}");
            assert_eq!(check.compute_prefix(&buf, n), Some(want), "{check:?} n {n}");
        }
    }
}

/// A seeded algorithm without a table is its own [`Checksum`], of the same width.
#[test]
fn seeded_algorithms_need_no_table() {
    let sum = Algorithm::Sum {
        width: 1,
        init: 3,
        xorout: 0,
    };
    assert_eq!(sum.tableless().unwrap().compute(&[1, 2]), 6);
    let xor = Algorithm::Xor { init: 0xF0 };
    assert_eq!(xor.tableless().unwrap().compute(&[0x0F]), 0xFF);
    assert_eq!(xor.width(), 1);
}
