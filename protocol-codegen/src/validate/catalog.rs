//! The CRC catalogue of the `crc` crate (crc-catalog), by constant name: which names a spec
//! may use in `check = "..."`. Only byte-sized widths (8, 16, 32, 64) can be stored in a frame.
//! The parameters come from the crate's own constants, so they cannot drift from what the
//! generated code computes.

use crate::ir::CrcParams;

macro_rules! catalog {
    ($($name:ident),* $(,)?) => {
        /// Every byte-width catalogue CRC: (constant name, parameters).
        pub fn catalog() -> Vec<(&'static str, CrcParams)> {
            vec![$((stringify!($name), params(stringify!($name), &crc::$name))),*]
        }
    };
}

catalog!(
    CRC_8_AUTOSAR,
    CRC_8_BLUETOOTH,
    CRC_8_CDMA2000,
    CRC_8_DARC,
    CRC_8_DVB_S2,
    CRC_8_GSM_A,
    CRC_8_GSM_B,
    CRC_8_HITAG,
    CRC_8_I_432_1,
    CRC_8_I_CODE,
    CRC_8_LTE,
    CRC_8_MAXIM_DOW,
    CRC_8_MIFARE_MAD,
    CRC_8_NRSC_5,
    CRC_8_OPENSAFETY,
    CRC_8_ROHC,
    CRC_8_SAE_J1850,
    CRC_8_SMBUS,
    CRC_8_TECH_3250,
    CRC_8_WCDMA,
    CRC_16_ARC,
    CRC_16_CDMA2000,
    CRC_16_CMS,
    CRC_16_DDS_110,
    CRC_16_DECT_R,
    CRC_16_DECT_X,
    CRC_16_DNP,
    CRC_16_EN_13757,
    CRC_16_GENIBUS,
    CRC_16_GSM,
    CRC_16_IBM_3740,
    CRC_16_IBM_SDLC,
    CRC_16_ISO_IEC_14443_3_A,
    CRC_16_KERMIT,
    CRC_16_LJ1200,
    CRC_16_M17,
    CRC_16_MAXIM_DOW,
    CRC_16_MCRF4XX,
    CRC_16_MODBUS,
    CRC_16_NRSC_5,
    CRC_16_OPENSAFETY_A,
    CRC_16_OPENSAFETY_B,
    CRC_16_PROFIBUS,
    CRC_16_RIELLO,
    CRC_16_SPI_FUJITSU,
    CRC_16_T10_DIF,
    CRC_16_TELEDISK,
    CRC_16_TMS37157,
    CRC_16_UMTS,
    CRC_16_USB,
    CRC_16_XMODEM,
    CRC_32_AIXM,
    CRC_32_AUTOSAR,
    CRC_32_BASE91_D,
    CRC_32_BZIP2,
    CRC_32_CD_ROM_EDC,
    CRC_32_CKSUM,
    CRC_32_ISCSI,
    CRC_32_ISO_HDLC,
    CRC_32_JAMCRC,
    CRC_32_MEF,
    CRC_32_MPEG_2,
    CRC_32_XFER,
    CRC_64_ECMA_182,
    CRC_64_GO_ISO,
    CRC_64_MS,
    CRC_64_NVME,
    CRC_64_REDIS,
    CRC_64_WE,
    CRC_64_XZ,
);

fn params<W: crc::Width + Into<u64> + Copy>(name: &str, a: &crc::Algorithm<W>) -> CrcParams {
    CrcParams {
        catalog: Some(name.to_string()),
        display: display_name(name),
        width: a.width,
        poly: a.poly.into(),
        init: a.init.into(),
        refin: a.refin,
        refout: a.refout,
        xorout: a.xorout.into(),
        check: a.check.into(),
        residue: a.residue.into(),
        table: 16,
    }
}

/// `CRC_16_UMTS` -> `crc-16-umts`, the spelling specs use.
pub fn display_name(constant: &str) -> String {
    constant.to_ascii_lowercase().replace('_', "-")
}
