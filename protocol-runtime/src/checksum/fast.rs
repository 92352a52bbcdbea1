//! The `crc-fast` host feature: the CRCs that the `crc-fast` crate catalogues are computed by
//! it (carry-less folding with SIMD, behind its own run-time CPU dispatch) from [`FAST_FROM`]
//! bytes on; shorter ones, and the CRCs it does not catalogue, by
//! [`Slicing16`](super::Slicing16)'s tables.
//!
//! This module owns when the crate is used: the match between a `crc` crate
//! [`Algorithm`](crc::Algorithm) and the `crc-fast` catalogue, made once when a
//! [`Slicing16`](super::Slicing16) is built, and the length from which a CRC goes to it. The
//! carry-less multiply intrinsics are `#[target_feature]` functions, which safe code cannot
//! call from a function without that attribute: the `crc-fast` crate owns those calls, and this
//! crate stays `#![forbid(unsafe_code)]`. (The crate's switches are listed in one place:
//! [`decoder`](crate::decoder#target-and-build-switches).)

pub use crc_fast::CrcAlgorithm;

/// CRCs of at least this many bytes are the crate's; shorter ones stay with the tables: under
/// 128 bytes the crate's path is no faster than them (0.67x - 1.11x their speed at 16 to 112
/// bytes in two runs), from 128 bytes on its folding is (1.2x - 1.9x at 128 bytes, 16x - 20x at
/// 4 KiB). The `crc16-mcrf4xx` group of `cargo bench -p protocol-benches`, in both builds;
/// `BENCHMARKS.md`.
pub(super) const FAST_FROM: usize = 128;

/// `$name(alg)`: the `crc-fast` algorithm computing the same CRC as `alg`, if one does.
macro_rules! catalogue {
    ($name:ident, $w:ty, [$(($alg:ident, $fast:ident)),* $(,)?]) => {
        #[doc = concat!("The `crc-fast` algorithm that computes `alg` (", stringify!($w), "), if any.")]
        pub(super) const fn $name(alg: &crc::Algorithm<$w>) -> Option<CrcAlgorithm> {
            $(
                let c = &crc::$alg;
                if alg.width == c.width
                    && alg.poly == c.poly
                    && alg.init == c.init
                    && alg.refin == c.refin
                    && alg.refout == c.refout
                    && alg.xorout == c.xorout
                {
                    return Some(CrcAlgorithm::$fast);
                }
            )*
            None
        }
    };
}

/// No CRC-8 in the `crc-fast` catalogue.
pub(super) const fn crc8(_: &crc::Algorithm<u8>) -> Option<CrcAlgorithm> {
    None
}

catalogue!(
    crc16,
    u16,
    [
        (CRC_16_ARC, Crc16Arc),
        (CRC_16_CDMA2000, Crc16Cdma2000),
        (CRC_16_CMS, Crc16Cms),
        (CRC_16_DDS_110, Crc16Dds110),
        (CRC_16_DECT_R, Crc16DectR),
        (CRC_16_DECT_X, Crc16DectX),
        (CRC_16_DNP, Crc16Dnp),
        (CRC_16_EN_13757, Crc16En13757),
        (CRC_16_GENIBUS, Crc16Genibus),
        (CRC_16_GSM, Crc16Gsm),
        (CRC_16_IBM_3740, Crc16Ibm3740),
        (CRC_16_IBM_SDLC, Crc16IbmSdlc),
        (CRC_16_ISO_IEC_14443_3_A, Crc16IsoIec144433A),
        (CRC_16_KERMIT, Crc16Kermit),
        (CRC_16_LJ1200, Crc16Lj1200),
        (CRC_16_M17, Crc16M17),
        (CRC_16_MAXIM_DOW, Crc16MaximDow),
        (CRC_16_MCRF4XX, Crc16Mcrf4xx),
        (CRC_16_MODBUS, Crc16Modbus),
        (CRC_16_NRSC_5, Crc16Nrsc5),
        (CRC_16_OPENSAFETY_A, Crc16OpensafetyA),
        (CRC_16_OPENSAFETY_B, Crc16OpensafetyB),
        (CRC_16_PROFIBUS, Crc16Profibus),
        (CRC_16_RIELLO, Crc16Riello),
        (CRC_16_SPI_FUJITSU, Crc16SpiFujitsu),
        (CRC_16_T10_DIF, Crc16T10Dif),
        (CRC_16_TELEDISK, Crc16Teledisk),
        (CRC_16_TMS37157, Crc16Tms37157),
        (CRC_16_UMTS, Crc16Umts),
        (CRC_16_USB, Crc16Usb),
        (CRC_16_XMODEM, Crc16Xmodem),
    ]
);

catalogue!(
    crc32,
    u32,
    [
        (CRC_32_AIXM, Crc32Aixm),
        (CRC_32_AUTOSAR, Crc32Autosar),
        (CRC_32_BASE91_D, Crc32Base91D),
        (CRC_32_BZIP2, Crc32Bzip2),
        (CRC_32_CD_ROM_EDC, Crc32CdRomEdc),
        (CRC_32_CKSUM, Crc32Cksum),
        (CRC_32_ISCSI, Crc32Iscsi),
        (CRC_32_ISO_HDLC, Crc32IsoHdlc),
        (CRC_32_JAMCRC, Crc32Jamcrc),
        (CRC_32_MEF, Crc32Mef),
        (CRC_32_MPEG_2, Crc32Mpeg2),
        (CRC_32_XFER, Crc32Xfer),
    ]
);

catalogue!(
    crc64,
    u64,
    [
        (CRC_64_ECMA_182, Crc64Ecma182),
        (CRC_64_GO_ISO, Crc64GoIso),
        (CRC_64_MS, Crc64Ms),
        (CRC_64_NVME, Crc64Nvme),
        (CRC_64_REDIS, Crc64Redis),
        (CRC_64_WE, Crc64We),
        (CRC_64_XZ, Crc64Xz),
    ]
);

#[cfg(test)]
// Test code: an index out of bounds is a failed test.
#[allow(clippy::indexing_slicing)]
mod tests {
    use crate::checksum::Slicing16;

    /// Every catalogued CRC through `crc-fast` against the `crc` crate's bitwise reference,
    /// every length up to 200 bytes and with bytes past the covered ones.
    #[test]
    fn catalogued_crcs_match_the_crc_crate() {
        let data: [u8; 256] = core::array::from_fn(|i| (i as u8).wrapping_mul(73).wrapping_add(11));
        macro_rules! check {
            ($w:ty, $($alg:ident),*) => {$(
                let table = Slicing16::<$w>::new(&crc::$alg);
                assert!(table.uses_crc_fast(), stringify!($alg));
                let reference = crc::Crc::<$w, crc::NoTable>::new(&crc::$alg);
                // (Under Miri, which interprets every step, every 23rd length.)
                for n in (0..200).step_by(if cfg!(miri) { 23 } else { 1 }) {
                    let want = reference.checksum(&data[..n]);
                    assert_eq!(table.checksum(&data[..n]), want, "{} n {n}", stringify!($alg));
                    assert_eq!(table.checksum_prefix(&data, n), want, "{} +", stringify!($alg));
                }
            )*};
        }
        check!(
            u16,
            CRC_16_MCRF4XX,
            CRC_16_KERMIT,
            CRC_16_MODBUS,
            CRC_16_IBM_3740,
            CRC_16_XMODEM
        );
        check!(u32, CRC_32_ISO_HDLC, CRC_32_ISCSI, CRC_32_BZIP2);
        check!(u64, CRC_64_XZ, CRC_64_ECMA_182);
        assert!(!Slicing16::<u8>::new(&crc::CRC_8_SMBUS).uses_crc_fast());
    }
}
