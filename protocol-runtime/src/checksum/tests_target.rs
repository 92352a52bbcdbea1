//! The CRC tables of a check: the ones a spec names, whatever the CRC's width; for a check whose
//! spec names none ([`CrcTable::ByTarget`]), the ones generated code's [`TargetCrc`] has on the
//! same target, which the run-time codec builds too; and a CRC without tables, as `Debug` shows
//! it.

extern crate std;

use std::format;

use super::*;

static TARGET: TargetCrc<u16> = TargetCrc::<u16>::new(&crc::CRC_16_MCRF4XX);

#[test]
fn a_crc_without_a_table_gets_the_tables_generated_code_gets() {
    let generated = CrcImpl::by_target(&TARGET).table_lanes();
    assert_eq!(CrcTable::ByTarget.lanes(), generated);
    let resolved = CrcTable::ByTarget.on_this_target();
    assert_ne!(resolved, CrcTable::ByTarget, "resolved to a table size");
    assert_eq!(resolved.lanes(), generated);
    for (named, lanes) in [
        (CrcTable::NoTable, 0),
        (CrcTable::Table1, 1),
        (CrcTable::Table16, 16),
    ] {
        assert_eq!(named.on_this_target(), named);
        assert_eq!(named.lanes(), lanes);
    }
}

#[test]
fn a_crc_of_every_width_names_its_table() {
    let table = CrcTable::Table16;
    let crcs = [
        Algorithm::Crc8(CrcSpec {
            params: crc::CRC_8_MAXIM_DOW,
            table,
        }),
        Algorithm::Crc16(CrcSpec {
            params: crc::CRC_16_MCRF4XX,
            table,
        }),
        Algorithm::Crc32(CrcSpec {
            params: crc::CRC_32_ISO_HDLC,
            table,
        }),
        Algorithm::Crc64(CrcSpec {
            params: crc::CRC_64_XZ,
            table,
        }),
    ];
    for crc in crcs {
        assert_eq!(crc.crc_table(), Some(table), "{crc:?}");
    }
}

#[test]
fn a_crc_without_tables_shows_its_parameters() {
    let bitwise = Bitwise::<u16>::new(&crc::CRC_16_MCRF4XX);
    let text = format!("{bitwise:?}");
    assert!(text.starts_with("Bitwise(Algorithm {"), "{text}");
    assert!(text.contains("poly: 4129"), "{text}");
}
