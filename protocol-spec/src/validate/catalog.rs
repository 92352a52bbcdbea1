//! The CRC catalogue of the `crc` crate (crc-catalog), by constant name, and the other names
//! users know its entries by: which names a spec may use in `check = "..."`. Every entry of up
//! to 64 bits is offered (one of 82 bits is not); a CRC whose width is not a whole number of
//! bytes is stored in the fewest bytes that hold it (a CRC-24 in three). The parameters come
//! from the crate's own constants, so they cannot drift from what the generated code
//! computes.

use crate::ir::{Algorithm, CrcSpec, CrcTable};

/// A catalogue CRC: the `crc` crate's constant name and the algorithm (with the fastest table).
pub struct Entry {
    /// The constant (`CRC_16_UMTS`).
    pub constant: &'static str,
    /// The algorithm.
    pub algorithm: Algorithm,
}

macro_rules! catalog {
    ($($name:ident),* $(,)?) => {
        /// Every catalogue CRC of up to 64 bits.
        pub fn catalog() -> Vec<Entry> {
            vec![$(Entry { constant: stringify!($name), algorithm: crc::$name.into_algorithm() }),*]
        }
    };
}

catalog!(
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
    CRC_7_UMTS,
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
    CRC_15_MPT1327,
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
    CRC_31_PHILIPS,
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
    CRC_40_GSM,
);

/// A catalogue constant as an algorithm computed with sixteen tables.
trait IntoAlgorithm {
    fn into_algorithm(self) -> Algorithm;
}

macro_rules! into_algorithm {
    ($($w:ty => $variant:ident),*) => {$(
        impl IntoAlgorithm for crc::Algorithm<$w> {
            fn into_algorithm(self) -> Algorithm {
                Algorithm::$variant(CrcSpec { params: self, table: CrcTable::ByTarget })
            }
        }
    )*};
}
into_algorithm!(u8 => Crc8, u16 => Crc16, u32 => Crc32, u64 => Crc64);

/// Names users know catalogue CRCs by, each with the catalogue constant it names: the aliases
/// of Greg Cook's "Catalogue of parametrised CRC algorithms" (reveng), on which crc-catalog is
/// built, for the entries links use. In the order a did-you-mean prefers them: a name users
/// write first (`CRC-32` before `CRC-32/MEF`). One more is not reveng's: `CRC-24Q`, the CRC
/// of RTCM 3 (and of Qualcomm's documents it is named after), whose parameters (poly
/// `0x864CFB`, init 0, not reflected, xorout 0) are exactly CRC-24/LTE-A's.
pub const ALIASES: &[(&str, &str)] = &[
    ("CRC_32", "CRC_32_ISO_HDLC"),
    ("CRC_32_ADCCP", "CRC_32_ISO_HDLC"),
    ("CRC_32_V_42", "CRC_32_ISO_HDLC"),
    ("CRC_32_XZ", "CRC_32_ISO_HDLC"),
    ("PKZIP", "CRC_32_ISO_HDLC"),
    ("CRC_32C", "CRC_32_ISCSI"),
    ("CRC_32_CASTAGNOLI", "CRC_32_ISCSI"),
    ("CRC_32_NVME", "CRC_32_ISCSI"),
    ("CRC_32_AAL5", "CRC_32_BZIP2"),
    ("CRC_32_POSIX", "CRC_32_CKSUM"),
    ("CRC_16_CCITT_FALSE", "CRC_16_IBM_3740"),
    ("CRC_16_AUTOSAR", "CRC_16_IBM_3740"),
    ("CRC_16_CCITT", "CRC_16_KERMIT"),
    ("CRC_16_CCITT_TRUE", "CRC_16_KERMIT"),
    ("CRC_CCITT", "CRC_16_KERMIT"),
    ("CRC_16_BLUETOOTH", "CRC_16_KERMIT"),
    ("CRC_16_V_41_LSB", "CRC_16_KERMIT"),
    ("KERMIT", "CRC_16_KERMIT"),
    ("CRC_16_V_41_MSB", "CRC_16_XMODEM"),
    ("CRC_16_ACORN", "CRC_16_XMODEM"),
    ("CRC_16_LTE", "CRC_16_XMODEM"),
    ("XMODEM", "CRC_16_XMODEM"),
    ("ZMODEM", "CRC_16_XMODEM"),
    ("MODBUS", "CRC_16_MODBUS"),
    ("CRC_16", "CRC_16_ARC"),
    ("CRC_16_LHA", "CRC_16_ARC"),
    ("CRC_IBM", "CRC_16_ARC"),
    ("ARC", "CRC_16_ARC"),
    ("CRC_16_X_25", "CRC_16_IBM_SDLC"),
    ("X_25", "CRC_16_IBM_SDLC"),
    ("CRC_16_ISO_HDLC", "CRC_16_IBM_SDLC"),
    ("CRC_16_BUYPASS", "CRC_16_UMTS"),
    ("CRC_16_VERIFONE", "CRC_16_UMTS"),
    ("CRC_16_MAXIM", "CRC_16_MAXIM_DOW"),
    ("CRC_8", "CRC_8_SMBUS"),
    ("CRC_8_MAXIM", "CRC_8_MAXIM_DOW"),
    ("DOW_CRC", "CRC_8_MAXIM_DOW"),
    ("CRC_8_ITU", "CRC_8_I_432_1"),
    ("CRC_64", "CRC_64_ECMA_182"),
    ("CRC_24", "CRC_24_OPENPGP"),
    ("CRC_24Q", "CRC_24_LTE_A"),
    ("CRC_64_GO_ECMA", "CRC_64_XZ"),
];

/// `CRC_16_UMTS` -> `crc-16-umts`, the spelling specs use.
pub fn display_name(constant: &str) -> String {
    constant.to_ascii_lowercase().replace('_', "-")
}
