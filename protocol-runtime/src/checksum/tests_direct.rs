//! The direct table of an [`Extra`] check at its edges: [`fill_direct`] at run time (as the
//! run-time codec fills it) with a key at the table's length and past it, and a key whose
//! byte is 0, which the table must tell from a key without a byte.

use super::*;
use crate::layout::{ByteOrder, Pos, WordField};

static MCRF4XX: crc::Crc<u16, crc::Table<1>> =
    crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_MCRF4XX);

/// Keys 0 and 3 with a byte (3's is 0); key 4 is the table's length and 9 is past it.
const PAIRS: [(u32, u8); 4] = [(0, 50), (3, 0), (4, 7), (9, 8)];

#[test]
fn fill_direct_writes_the_keys_below_the_table_length_only() {
    let mut table = [0u16; 4];
    fill_direct(&mut table, &PAIRS);
    assert_eq!(table, [0x100 | 50, 0, 0, 0x100]);
    // The same pairs through the `const` builder, evaluated here at run time.
    assert_eq!(direct_table::<4>(&PAIRS), table);
    // A table one longer takes key 4 as well.
    assert_eq!(
        direct_table::<5>(&PAIRS),
        [0x100 | 50, 0, 0, 0x100, 0x100 | 7]
    );
}

/// A check whose one-byte key is the first covered byte, keys below 4 in `direct`.
fn check(direct: &'static [u16]) -> Extra<'static> {
    Extra {
        crc: Checksum::Crc16(CrcImpl::Table1(&MCRF4XX)),
        key: WordField {
            at: Pos::Start(0),
            size: 1,
            order: ByteOrder::Little,
            shift: 0,
            width: 8,
        },
        direct,
        bytes: &[(4, 7), (9, 8)],
    }
}

/// The table [`fill_direct_writes_the_keys_below_the_table_length_only`] builds, written out:
/// evaluated in a `const`, a builder that indexes past the table stops the build instead of
/// failing a test.
static DIRECT: [u16; 4] = [0x100 | 50, 0, 0, 0x100];

#[test]
fn a_key_whose_byte_is_zero_has_a_byte() {
    let extra = check(&DIRECT);
    assert_eq!(extra.byte(&[3, 0xAA]), Some(0));
    assert_eq!(extra.byte(&[0, 0xAA]), Some(50));
    // Keys 1 and 2 lie in the table without a byte; 4 and 9 are in the pairs, 5 nowhere.
    assert_eq!(extra.byte(&[1, 0xAA]), None);
    assert_eq!(extra.byte(&[2, 0xAA]), None);
    assert_eq!(extra.byte(&[4, 0xAA]), Some(7));
    assert_eq!(extra.byte(&[9, 0xAA]), Some(8));
    assert_eq!(extra.byte(&[5, 0xAA]), None);
    // Folding 0 in is not the plain CRC: the check of key 3 differs from one without a byte.
    let data = [3, 0xAA];
    let folded = extra.compute(&data);
    assert_eq!(folded, Some(extra.fold(&data, 0)));
    assert_ne!(folded, Some(u64::from(MCRF4XX.checksum(&data))));
}
