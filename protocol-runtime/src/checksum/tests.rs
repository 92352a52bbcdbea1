//! Every check against its definition: sums and xor against naive loops, every CRC of the
//! `crc` crate's catalogue against `crc::Crc<W, NoTable>`, custom CRCs against their check
//! values. Nothing is timed here (benchmarks live in `benches/`).

#![allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::panic
)]

extern crate std;

use std::format;
use std::vec::Vec;

use super::*;

const CHECK: &[u8] = b"123456789";

/// Overruns past the covered bytes a prefix computation is tested with.
const OVERRUNS: [usize; 5] = [0, 1, 15, 16, 40];

/// The step through the lengths `0..=300` the checks are compared at: every length, or under
/// Miri (which interprets every step, a thousand times slower or more) every 37th, which still
/// meets each 16-byte block's offsets.
const LENGTH_STEP: usize = if cfg!(miri) { 37 } else { 1 };

/// The size of the inputs that run past any 16-bit or 32-bit lane of a sum: eight MiB, or
/// under Miri 64 KiB, past the 16-bit lanes only.
const LONG: usize = if cfg!(miri) { 64 << 10 } else { 8 << 20 };

/// A xorshift64 generator: deterministic test data without dependencies.
fn fill(seed: &mut u64, buf: &mut [u8]) {
    for b in buf {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *b = (*seed >> 24) as u8;
    }
}

fn random(seed: u64, len: usize) -> Vec<u8> {
    let mut seed = seed;
    let mut buf = std::vec![0u8; len];
    fill(&mut seed, &mut buf);
    buf
}

// ---- sums and xor ----

fn naive_sum(data: &[u8]) -> u64 {
    data.iter().map(|&b| u64::from(b)).sum()
}

fn naive_xor(data: &[u8]) -> u64 {
    u64::from(data.iter().fold(0u8, |a, b| a ^ b))
}

/// Checks exact and prefix forms of the three byte checks for every `n` in `0..=300`, with
/// and without bytes past `n` (the window form applies from 128 bytes of input).
fn check_sums_over(buf: &[u8]) {
    for n in (0..=300).step_by(LENGTH_STEP) {
        let data = &buf[..n];
        let (sum, xor) = (naive_sum(data), naive_xor(data));
        assert_eq!(Checksum::Sum8.compute(data), sum % 256, "n {n}");
        assert_eq!(Checksum::SumMod255.compute(data), sum % 255, "n {n}");
        assert_eq!(Checksum::Xor8.compute(data), xor, "n {n}");
        for extra in OVERRUNS.into_iter().chain([100, 128, 200]) {
            let Some(input) = buf.get(..n + extra) else {
                continue;
            };
            let at = |c: Checksum<'_>| c.compute_prefix(input, n);
            assert_eq!(at(Checksum::Sum8), Some(sum % 256), "n {n} + {extra}");
            assert_eq!(at(Checksum::SumMod255), Some(sum % 255), "n {n} + {extra}");
            assert_eq!(at(Checksum::Xor8), Some(xor), "n {n} + {extra}");
        }
    }
}

#[test]
fn sums_match_naive_definitions_for_every_length_and_overrun() {
    for seed in [0x9E37_79B9_7F4A_7C15, 1, 0xDEAD_BEEF] {
        check_sums_over(&random(seed, 600));
    }
    check_sums_over(&[0xFF; 600]);
    check_sums_over(&[0; 600]);
}

#[test]
fn window_ignores_every_byte_past_n() {
    // Same covered bytes, different bytes after them: the same value.
    let mut a = random(7, 256);
    let b = a.clone();
    for n in 0..=128 {
        a[n..].fill(0xFF);
        for c in [Checksum::Sum8, Checksum::SumMod255, Checksum::Xor8] {
            assert_eq!(
                c.compute_prefix(&a, n),
                c.compute_prefix(&b, n),
                "{c:?} n {n}"
            );
        }
        a.copy_from_slice(&b);
    }
}

#[test]
fn sums_of_long_inputs_are_exact() {
    let buf = [0xFFu8; 5000];
    // Miri interprets every byte summed: there, fewer lengths, the edges kept.
    for len in (0..=5000)
        .step_by(if cfg!(miri) { 211 } else { 7 })
        .chain([1023, 1024, 1025, 2048, 4999, 5000])
    {
        let sum = 255 * len as u64;
        assert_eq!(sum::byte_sum(&buf[..len]), sum);
        assert_eq!(Checksum::Sum8.compute(&buf[..len]), sum % 256, "len {len}");
        assert_eq!(
            Checksum::SumMod255.compute(&buf[..len]),
            sum % 255,
            "len {len}"
        );
        assert_eq!(
            Checksum::SumMod255.compute_prefix(&buf, len),
            Some(sum % 255),
            "len {len}"
        );
        assert_eq!(Checksum::Xor8.compute(&buf[..len]), (len as u64 % 2) * 0xFF);
    }
    // `LONG` bytes of 0xFF and of random bytes: past the sums' lanes.
    for data in [std::vec![0xFFu8; LONG], random(3, LONG)] {
        let sum = naive_sum(&data);
        assert_eq!(Checksum::SumMod255.compute(&data), sum % 255);
        assert_eq!(Checksum::Sum8.compute(&data), sum % 256);
    }
}

#[test]
fn mod255_without_division_is_the_remainder() {
    let mut seed = 5;
    let mut words = [0u8; 8 * 1000];
    fill(&mut seed, &mut words);
    let randoms = words
        .chunks_exact(8)
        .map(|w| u64::from_le_bytes(w.try_into().unwrap()));
    let edges = [
        0,
        1,
        254,
        255,
        256,
        u64::from(u32::MAX),
        u64::from(u32::MAX) + 1,
        (1 << 33) - 2,
        u64::MAX - 1,
        u64::MAX,
        0xFFFF_FFFF_0000_0000,
        0x0000_0001_FFFF_FFFF,
    ];
    for x in edges.into_iter().chain(randoms) {
        assert_eq!(u64::from(sum::mod255(x)), x % 255, "{x:#x}");
    }
}

#[test]
fn rem255_is_the_remainder_for_every_u32_class() {
    // Every value a window or short sum takes in a decoder (up to 128 x 255), then the
    // neighbourhoods of every multiple of 255 near the top, where the add wraps.
    // (Under Miri, which interprets every step, a sample of each range.)
    let (step, near) = if cfg!(miri) { (37, 700) } else { (1, 70_000) };
    for x in (0..=(128 * 255 + 300)).step_by(step) {
        assert_eq!(u32::from(sum::rem255_u32(x)), x % 255, "{x}");
    }
    for q in (u32::MAX / 255 - near)..=(u32::MAX / 255) {
        for x in [0, 1, 254]
            .into_iter()
            .filter_map(|r| (q * 255).checked_add(r))
        {
            assert_eq!(u32::from(sum::rem255_u32(x)), x % 255, "{x}");
        }
    }
    for x in (u32::MAX - 1000)..=u32::MAX {
        assert_eq!(u32::from(sum::rem255_u32(x)), x % 255, "{x}");
    }
}

#[test]
fn sum_check_values() {
    assert_eq!(Checksum::SumMod255.compute(CHECK), 0xDE);
    assert_eq!(Checksum::Sum8.compute(CHECK), 0xDD);
    assert_eq!(Checksum::Xor8.compute(CHECK), 0x31);
}

#[test]
fn prefix_past_the_input_is_none() {
    static T16: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_UMTS);
    static T1: crc::Crc<u16, crc::Table<1>> =
        crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_UMTS);
    let data = [0u8; 200];
    for c in [
        Checksum::Sum8,
        Checksum::SumMod255,
        Checksum::Xor8,
        Checksum::Crc16(CrcImpl::Table16(&T16)),
        Checksum::Crc16(CrcImpl::Table1(&T1)),
    ] {
        for len in [0, 5, 128, 200] {
            assert_eq!(c.compute_prefix(&data[..len], len + 1), None, "{c:?}");
            assert!(c.compute_prefix(&data[..len], len).is_some(), "{c:?}");
        }
    }
    // Below `Checksum`, a prefix longer than the input is the whole input.
    assert_eq!(T16.checksum_prefix(CHECK, 100), 0xFEE8);
    assert_eq!(CrcImpl::Table1(&T1).checksum_prefix(CHECK, 100), 0xFEE8);
}

// ---- CRCs ----

/// Checks `Slicing16` (built at run time, the way the interpreter builds it) and `Bitwise`
/// against `crc::Crc<W, NoTable>` for every algorithm named: the check value, random data of every
/// length in `0..=300`, and prefixes with bytes past them (under Miri, a sample of the lengths
/// and of the algorithms). Returns the number of algorithms.
/// Each algorithm is checked in a function of its own: its stack frame (a `Slicing16` is built
/// on the stack) is reused by the next, not added to one frame of every algorithm.
macro_rules! check_catalogue {
    ($w:ty, $variant:ident: $($alg:ident),* $(,)?) => {{
        let buf = random(0x5EED, 300 + 40);
        let mut count = 0;
        $(
            {
            #[inline(never)]
            fn one(buf: &[u8]) {
            let alg: &'static crc::Algorithm<$w> = &crc::$alg;
            let reference = crc::Crc::<$w, crc::NoTable>::new(alg);
            let fast = std::boxed::Box::new(Slicing16::<$w>::new(alg));
            assert_eq!(fast.checksum(CHECK), alg.check, stringify!($alg));
            assert_eq!(reference.checksum(CHECK), alg.check, stringify!($alg));
            let check = Checksum::$variant(CrcImpl::Table16(&fast));
            let bitwise = super::Bitwise::<$w>::new(alg);
            for n in (0..=300).step_by(LENGTH_STEP) {
                let want = reference.checksum(&buf[..n]);
                assert_eq!(bitwise.checksum(&buf[..n]), want, "{} bitwise {n}", stringify!($alg));
                assert_eq!(fast.checksum(&buf[..n]), want, "{} n {n}", stringify!($alg));
                // The encoders' call, which never folds: the same value.
                assert_eq!(fast.checksum_written(&buf[..n]), want, "{} w {n}", stringify!($alg));
                assert_eq!(check.compute_written(&buf[..n]), u64::from(want));
                for extra in OVERRUNS {
                    assert_eq!(
                        fast.checksum_prefix(&buf[..n + extra], n),
                        want,
                        "{} n {n} + {extra}",
                        stringify!($alg)
                    );
                }
                assert_eq!(check.compute_prefix(&buf, n), Some(u64::from(want)));
            }
            }
            // (Under Miri, which interprets every table built, every seventh algorithm.)
            if !cfg!(miri) || count % 7 == 0 {
                one(&buf);
            }
            }
            count += 1;
        )*
        count
    }};
}

#[test]
fn catalogue_crc8_slicing_matches_the_crc_crate() {
    let count = check_catalogue!(u8, Crc8:
        CRC_3_GSM, CRC_3_ROHC, CRC_4_G_704, CRC_4_INTERLAKEN, CRC_5_EPC_C1G2, CRC_5_G_704,
        CRC_5_USB, CRC_6_CDMA2000_A, CRC_6_CDMA2000_B, CRC_6_DARC, CRC_6_G_704, CRC_6_GSM,
        CRC_7_MMC, CRC_7_ROHC, CRC_7_UMTS, CRC_8_AUTOSAR, CRC_8_BLUETOOTH, CRC_8_CDMA2000,
        CRC_8_DARC, CRC_8_DVB_S2, CRC_8_GSM_A, CRC_8_GSM_B, CRC_8_HITAG, CRC_8_I_432_1,
        CRC_8_I_CODE, CRC_8_LTE, CRC_8_MAXIM_DOW, CRC_8_MIFARE_MAD, CRC_8_NRSC_5,
        CRC_8_OPENSAFETY, CRC_8_ROHC, CRC_8_SAE_J1850, CRC_8_SMBUS, CRC_8_TECH_3250,
        CRC_8_WCDMA,
    );
    assert_eq!(count, 35);
}

#[test]
fn catalogue_crc16_slicing_matches_the_crc_crate() {
    let count = check_catalogue!(u16, Crc16:
        CRC_10_ATM, CRC_10_CDMA2000, CRC_10_GSM, CRC_11_FLEXRAY, CRC_11_UMTS, CRC_12_CDMA2000,
        CRC_12_DECT, CRC_12_GSM, CRC_12_UMTS, CRC_13_BBC, CRC_14_DARC, CRC_14_GSM, CRC_15_CAN,
        CRC_15_MPT1327, CRC_16_ARC, CRC_16_CDMA2000, CRC_16_CMS, CRC_16_DDS_110,
        CRC_16_DECT_R, CRC_16_DECT_X, CRC_16_DNP, CRC_16_EN_13757, CRC_16_GENIBUS,
        CRC_16_GSM, CRC_16_IBM_3740, CRC_16_IBM_SDLC, CRC_16_ISO_IEC_14443_3_A,
        CRC_16_KERMIT, CRC_16_LJ1200, CRC_16_M17, CRC_16_MAXIM_DOW, CRC_16_MCRF4XX,
        CRC_16_MODBUS, CRC_16_NRSC_5, CRC_16_OPENSAFETY_A, CRC_16_OPENSAFETY_B,
        CRC_16_PROFIBUS, CRC_16_RIELLO, CRC_16_SPI_FUJITSU, CRC_16_T10_DIF, CRC_16_TELEDISK,
        CRC_16_TMS37157, CRC_16_UMTS, CRC_16_USB, CRC_16_XMODEM,
    );
    assert_eq!(count, 45);
}

#[test]
fn catalogue_crc32_slicing_matches_the_crc_crate() {
    let count = check_catalogue!(u32, Crc32:
        CRC_17_CAN_FD, CRC_21_CAN_FD, CRC_24_BLE, CRC_24_FLEXRAY_A, CRC_24_FLEXRAY_B,
        CRC_24_INTERLAKEN, CRC_24_LTE_A, CRC_24_LTE_B, CRC_24_OPENPGP, CRC_24_OS_9,
        CRC_30_CDMA, CRC_31_PHILIPS, CRC_32_AIXM, CRC_32_AUTOSAR, CRC_32_BASE91_D,
        CRC_32_BZIP2, CRC_32_CD_ROM_EDC, CRC_32_CKSUM, CRC_32_ISCSI, CRC_32_ISO_HDLC,
        CRC_32_JAMCRC, CRC_32_MEF, CRC_32_MPEG_2, CRC_32_XFER,
    );
    assert_eq!(count, 24);
}

#[test]
fn catalogue_crc64_slicing_matches_the_crc_crate() {
    let count = check_catalogue!(u64, Crc64:
        CRC_40_GSM, CRC_64_ECMA_182, CRC_64_GO_ISO, CRC_64_MS, CRC_64_NVME, CRC_64_REDIS,
        CRC_64_WE, CRC_64_XZ,
    );
    assert_eq!(count, 8);
}

/// In a build with the `clmul` feature for a CPU with `pclmulqdq`, the catalogue tests above
/// run every reflected CRC of up to 32 bits through the carry-less folding (lengths 9 to 300);
/// this checks that they do, and that in any other build none does.
#[test]
fn reflected_crcs_fold_where_the_build_has_clmul() {
    let folds = cfg!(all(
        feature = "clmul",
        target_arch = "x86_64",
        target_feature = "pclmulqdq"
    ));
    static MCRF4XX: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_MCRF4XX);
    static ISO_HDLC: Slicing16<u32> = Slicing16::<u32>::new(&crc::CRC_32_ISO_HDLC);
    static USB5: Slicing16<u8> = Slicing16::<u8>::new(&crc::CRC_5_USB);
    static CAN_FD: Slicing16<u32> = Slicing16::<u32>::new(&crc::CRC_21_CAN_FD);
    static UMTS: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_UMTS);
    static XZ: Slicing16<u64> = Slicing16::<u64>::new(&crc::CRC_64_XZ);
    assert_eq!(MCRF4XX.uses_clmul(), folds);
    assert_eq!(ISO_HDLC.uses_clmul(), folds);
    assert_eq!(USB5.uses_clmul(), folds);
    // Not reflected, or wider than 32 bits: the tables.
    assert!(!CAN_FD.uses_clmul() && !crc::CRC_21_CAN_FD.refin);
    assert!(!UMTS.uses_clmul());
    assert!(!XZ.uses_clmul());
}

/// The crossed-endian catalogue entries (`refin != refout`) are covered above; this makes
/// sure there is at least one, so the reversal at the end is exercised.
#[test]
fn catalogue_has_crossed_endian_crcs() {
    let alg = &crc::CRC_12_UMTS;
    assert!(!alg.refin && alg.refout);
    static UMTS: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_12_UMTS);
    assert_eq!(UMTS.checksum(CHECK), 0xDAF);
}

/// Checks all three table variants of one algorithm against its check value, with the tables
/// built by the compiler (as generated code builds them).
macro_rules! check_all_tables {
    ($w:ty, $variant:ident, $alg:expr) => {{
        static NO: crc::Crc<$w, crc::NoTable> = crc::Crc::<$w, crc::NoTable>::new($alg);
        static T1: crc::Crc<$w, crc::Table<1>> = crc::Crc::<$w, crc::Table<1>>::new($alg);
        static T16: Slicing16<$w> = Slicing16::<$w>::new($alg);
        let expected = u64::from($alg.check);
        let buf = random(11, 300);
        for c in [
            Checksum::$variant(CrcImpl::NoTable(&NO)),
            Checksum::$variant(CrcImpl::Table1(&T1)),
            Checksum::$variant(CrcImpl::Table16(&T16)),
        ] {
            assert_eq!(c.compute(CHECK), expected, "{c:?}");
            assert_eq!(c.compute_prefix(b"123456789abcdefghijk", 9), Some(expected));
            // The fewest whole bytes that hold the width (a CRC-24 in three).
            assert_eq!(c.width(), usize::from($alg.width).div_ceil(8));
            for n in (0..=buf.len()).step_by(LENGTH_STEP) {
                assert_eq!(
                    c.compute_prefix(&buf, n),
                    Some(u64::from(NO.checksum(&buf[..n]))),
                    "{c:?} n {n}"
                );
                assert_eq!(c.compute(&buf[..n]), u64::from(NO.checksum(&buf[..n])));
            }
        }
        expected
    }};
}

#[test]
fn catalogue_crcs_match_their_check_values_with_every_table() {
    assert_eq!(check_all_tables!(u8, Crc8, &crc::CRC_8_MAXIM_DOW), 0xA1);
    assert_eq!(check_all_tables!(u8, Crc8, &crc::CRC_3_GSM), 0x4);
    assert_eq!(check_all_tables!(u16, Crc16, &crc::CRC_16_UMTS), 0xFEE8);
    assert_eq!(check_all_tables!(u16, Crc16, &crc::CRC_16_MCRF4XX), 0x6F91);
    assert_eq!(check_all_tables!(u16, Crc16, &crc::CRC_12_UMTS), 0xDAF);
    assert_eq!(
        check_all_tables!(u32, Crc32, &crc::CRC_32_ISO_HDLC),
        0xCBF4_3926
    );
    assert_eq!(check_all_tables!(u32, Crc32, &crc::CRC_24_BLE), 0xC2_5A56);
    assert_eq!(
        check_all_tables!(u64, Crc64, &crc::CRC_64_XZ),
        0x995D_C9BB_DF19_39FA
    );
    assert_eq!(
        check_all_tables!(u64, Crc64, &crc::CRC_64_ECMA_182),
        0x6C40_DF5F_0B49_7347
    );
    assert_eq!(
        check_all_tables!(u64, Crc64, &crc::CRC_40_GSM),
        0xD4_164F_C646
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
    // And its check value: 0x0B, where the catalogue's MAXIM-DOW with init 0 gives 0xA1 (the DJI
    // CRC-8 starts from 0xFF).
    assert_eq!(check_all_tables!(u8, Crc8, &DJI_CRC8), 0x0B);
    // The referee header A5 03 00 00 carries CRC-8 0x27 (a published frame), whatever the
    // table and however far the input runs past the header.
    static T1: crc::Crc<u8, crc::Table<1>> = crc::Crc::<u8, crc::Table<1>>::new(&DJI_CRC8);
    static T16: Slicing16<u8> = Slicing16::<u8>::new(&DJI_CRC8);
    let frame = [0xA5, 0x03, 0x00, 0x00, 0x27, 0x01, 0x02, 0x03, 0x04, 0x05];
    for c in [
        Checksum::Crc8(CrcImpl::Table1(&T1)),
        Checksum::Crc8(CrcImpl::Table16(&T16)),
    ] {
        assert_eq!(c.compute(&frame[..4]), 0x27);
        for end in 4..=frame.len() {
            assert_eq!(c.compute_prefix(&frame[..end], 4), Some(0x27));
        }
    }
}

#[test]
fn slicing_built_at_compile_time_equals_run_time() {
    static CONST: Slicing16<u32> = Slicing16::<u32>::new(&crc::CRC_32_ISCSI);
    let run = std::boxed::Box::new(Slicing16::<u32>::new(&crc::CRC_32_ISCSI));
    let buf = random(13, 300);
    for n in (0..=buf.len()).step_by(LENGTH_STEP) {
        assert_eq!(
            CONST.checksum_prefix(&buf, n),
            run.checksum_prefix(&buf, n),
            "n {n}"
        );
    }
}

#[test]
fn table_sizes() {
    use core::mem::size_of;
    assert_eq!(size_of::<[[u8; 256]; 16]>(), 4096);
    // The carry-less folding's constants, where the build has them (no bytes otherwise), and
    // the parameters, held by value.
    let folding = size_of::<Option<clmul::Folding>>();
    let params = |w: usize| w * 5 + 8;
    assert!(size_of::<Slicing16<u8>>() <= 4096 + 32 + folding + params(1));
    assert!(size_of::<Slicing16<u16>>() <= 8192 + 32 + folding + params(2));
    assert!(size_of::<Slicing16<u32>>() <= 16384 + 32 + folding + params(4));
    assert!(size_of::<Slicing16<u64>>() <= 32768 + 32 + folding + params(8));
    assert!(folding <= 64);
}

#[test]
fn debug_names_the_algorithm_and_table() {
    static T: Slicing16<u16> = Slicing16::<u16>::new(&crc::CRC_16_UMTS);
    let text = format!("{:?}", Checksum::Crc16(CrcImpl::Table16(&T)));
    assert!(text.starts_with("Crc16(Table16(Algorithm"), "{text}");
    assert!(format!("{T:?}").starts_with("Slicing16 { algorithm: Algorithm"));
    assert_eq!(format!("{:?}", Checksum::SumMod255), "SumMod255");
    assert_eq!(CrcImpl::Table16(&T).table_lanes(), 16);
    assert_eq!(*T.algorithm(), crc::CRC_16_UMTS);
}

// ---- complemented and wider sums, Fletcher ----

/// Fletcher-16 (two sums modulo 255) against the test vectors of Wikipedia's "Fletcher's
/// checksum" article ("abcde" 0xC8F0, "abcdef" 0x2057, "abcdefgh" 0x0627).
#[test]
fn fletcher16_matches_its_published_vectors() {
    assert_eq!(Checksum::Fletcher16.compute(b"abcde"), 0xC8F0);
    assert_eq!(Checksum::Fletcher16.compute(b"abcdef"), 0x2057);
    assert_eq!(Checksum::Fletcher16.compute(b"abcdefgh"), 0x0627);
    assert_eq!(Checksum::Fletcher16.width(), 2);
}

/// The modulo-256 Fletcher pair over UBX-CFG-RATE frames as u-blox u-center writes them
/// (class..payload of `B5 62 06 08 06 00 64 00 01 00 01 00 7A 12`, 100 ms, and of
/// `... C8 00 01 00 01 00 DE 6A`, 200 ms): `CK_A` in the low byte, `CK_B` in the high one.
#[test]
fn fletcher16_mod256_matches_ubx_frames() {
    let rate_100ms = [0x06, 0x08, 0x06, 0x00, 0x64, 0x00, 0x01, 0x00, 0x01, 0x00];
    assert_eq!(Checksum::Fletcher16Mod256.compute(&rate_100ms), 0x127A);
    let rate_200ms = [0x06, 0x08, 0x06, 0x00, 0xC8, 0x00, 0x01, 0x00, 0x01, 0x00];
    assert_eq!(Checksum::Fletcher16Mod256.compute(&rate_200ms), 0x6ADE);
}

fn naive_fletcher(data: &[u8], modulus: u64) -> u64 {
    let (mut a, mut b) = (0u64, 0u64);
    for &x in data {
        a = (a + u64::from(x)) % modulus;
        b = (b + a) % modulus;
    }
    (b << 8) | a
}

#[test]
fn fletcher_sums_match_naive_definitions_for_every_length_and_overrun() {
    for buf in [random(7, 1200), std::vec![0xFF; 1200]] {
        // Miri interprets every byte summed: there, fewer lengths.
        for n in (0..=1100).step_by(if cfg!(miri) { 97 } else { 7 }) {
            let data = &buf[..n];
            assert_eq!(
                Checksum::Fletcher16.compute(data),
                naive_fletcher(data, 255),
                "n {n}"
            );
            assert_eq!(
                Checksum::Fletcher16Mod256.compute(data),
                naive_fletcher(data, 256)
            );
            for extra in OVERRUNS {
                let input = &buf[..n + extra];
                let f = Checksum::Fletcher16.compute_prefix(input, n);
                assert_eq!(f, Some(naive_fletcher(data, 255)), "n {n} + {extra}");
            }
        }
    }
}

/// Complemented sums against the examples of their protocols' documents: ROBOTIS
/// Dynamixel Protocol 1.0 (`FF FF 01 04 02 2B 01 CC`, READ_DATA of the temperature; the check
/// `~(ID + LENGTH + INSTRUCTION + PARAMETERS) & 0xFF`) and the iBUS frame of ArduPilot's RC
/// protocol test (`ibus_bytes`: 30 bytes, then `0xFFFF - sum` little-endian `47 F3`).
#[test]
fn complemented_sums_match_protocol_examples() {
    let dynamixel = Checksum::Sum {
        width: 1,
        init: 0,
        xorout: 0xFF,
    };
    assert_eq!(dynamixel.width(), 1);
    assert_eq!(dynamixel.compute(&[0x01, 0x04, 0x02, 0x2B, 0x01]), 0xCC);
    assert_eq!(dynamixel.compute(&[0x01, 0x03, 0x00, 0x20]), 0xDB);
    let mut ibus = std::vec![0x20, 0x40];
    for ch in [
        1500u16, 1500, 1000, 1500, 1500, 1500, 1500, 1500, 1500, 1500, 1500, 1500, 1500, 1500,
    ] {
        ibus.extend_from_slice(&ch.to_le_bytes());
    }
    let complement16 = Checksum::Sum {
        width: 2,
        init: 0,
        xorout: 0xFFFF,
    };
    assert_eq!(complement16.width(), 2);
    assert_eq!(complement16.compute(&ibus), 0xF347);
    assert_eq!(
        complement16.compute(&ibus),
        0xFFFF - naive_sum(&ibus) % 65536
    );
}

#[test]
fn wide_sums_match_naive_definitions() {
    let buf = random(11, 700);
    for n in (0..=600).step_by(LENGTH_STEP) {
        let data = &buf[..n];
        let sum16 = Checksum::Sum {
            width: 2,
            init: 0,
            xorout: 0,
        };
        assert_eq!(sum16.compute(data), naive_sum(data) % 65536, "n {n}");
        let sum8 = Checksum::Sum {
            width: 1,
            init: 0,
            xorout: 0x5A,
        };
        assert_eq!(sum8.compute(data), (naive_sum(data) % 256) ^ 0x5A, "n {n}");
        assert_eq!(
            sum16.compute_prefix(&buf[..n + 40], n),
            Some(naive_sum(data) % 65536)
        );
    }
}

#[test]
fn algorithm_values_describe_their_checksums() {
    let crc = Algorithm::Crc16(CrcSpec {
        params: crc::CRC_16_MCRF4XX,
        table: CrcTable::Table1,
    });
    assert_eq!(crc.width(), 2);
    assert_eq!(crc.tableless().map(|c| c.width()), None);
    assert_eq!(crc.crc_table(), Some(CrcTable::Table1));
    assert_eq!(CrcTable::Table16.lanes(), 16);
    for a in [
        Algorithm::Sum8,
        Algorithm::SumMod255,
        Algorithm::Xor8,
        Algorithm::Sum {
            width: 2,
            init: 0,
            xorout: 0xFFFF,
        },
        Algorithm::Fletcher16,
        Algorithm::Fletcher16Mod256,
    ] {
        let c = a.tableless().unwrap();
        assert_eq!(c.width(), a.width(), "{a:?}");
        assert_eq!(a.crc_table(), None);
    }
}
