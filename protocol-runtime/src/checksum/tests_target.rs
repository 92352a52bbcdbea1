//! The CRC tables of a check whose spec names none ([`CrcTable::ByTarget`]): the run-time codec
//! builds the ones generated code's [`TargetCrc`] has on the same target, and a table size the
//! spec names stays as it is.

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
