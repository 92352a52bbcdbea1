//! An [`Extra`] check of a key without a byte: [`Checksum::compute`] and
//! [`Checksum::compute_written`], which encoders call, give the CRC of the covered bytes alone;
//! [`Checksum::compute_prefix`], which decoders call, gives none; and [`Extra::compute`], none
//! either.

extern crate std;

use super::*;
use crate::layout::{ByteOrder, Pos, WordField};

static MCRF4XX: crc::Crc<u16, crc::Table<1>> =
    crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_MCRF4XX);

/// MAVLink v1's check: the message id is the fifth covered byte; id 0 (HEARTBEAT) folds in 50.
static MAVLINK1: Extra<'static> = Extra {
    crc: Checksum::Crc16(CrcImpl::Table1(&MCRF4XX)),
    key: WordField {
        at: Pos::Start(4),
        size: 1,
        order: ByteOrder::Little,
        shift: 0,
        width: 8,
    },
    direct: &[],
    bytes: &[(0, 50)],
};

/// The covered bytes of a HEARTBEAT (`FE 09 4E 01 01 00 .. 1C 7F`), id and all.
const HEARTBEAT: [u8; 14] = [
    0x09, 0x4E, 0x01, 0x01, 0x00, 0x00, 0x00, 0x00, 0x00, 0x02, 0x03, 0x51, 0x04, 0x03,
];

#[test]
fn a_key_without_a_byte_is_checked_by_the_crc_alone() {
    let check = Checksum::Extra(&MAVLINK1);
    let mut unknown = HEARTBEAT;
    unknown[4] = 7;
    let plain = u64::from(MCRF4XX.checksum(&unknown));
    assert_eq!(check.compute(&unknown), plain);
    assert_eq!(check.compute_written(&unknown), plain);
    assert_eq!(check.compute_prefix(&unknown, unknown.len()), None);
    // A key with a byte folds it in.
    assert_eq!(check.compute(&HEARTBEAT), 0x7F1C);
    assert_eq!(check.compute_written(&HEARTBEAT), 0x7F1C);
    assert_ne!(u64::from(MCRF4XX.checksum(&HEARTBEAT)), 0x7F1C);
}

#[test]
fn the_extra_value_is_there_for_a_key_with_a_byte_only() {
    assert_eq!(MAVLINK1.compute(&HEARTBEAT), Some(0x7F1C));
    assert_eq!(MAVLINK1.byte(&HEARTBEAT), Some(50));
    let mut unknown = HEARTBEAT;
    unknown[4] = 7;
    assert_eq!(MAVLINK1.compute(&unknown), None);
    assert_eq!(MAVLINK1.byte(&unknown), None);
}
