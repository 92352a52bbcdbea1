//! The checks as a layout type declares them (`declared.rs`): where it declares no CRC, every
//! sum, xor and Fletcher check gives what it gives undeclared, and a CRC gives nothing (so a
//! frame it checks neither verifies nor is written), where it declares every kind, a CRC too.

#![allow(clippy::indexing_slicing, clippy::unwrap_used)]

use super::*;
use crate::layout::{EveryKind, FrameLayout, LayoutRef, LengthRule};

static LAYOUT: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 1,
    min_len: 2,
    max_len: 2,
    length: LengthRule::Fixed(2),
    constants: &[],
    header_checks: &[],
    frame_checks: &[],
    markers: &[],
    escape: None,
};

/// A layout type that declares no CRC.
#[derive(Clone, Copy)]
struct SumsOnly;

impl LayoutRef for SumsOnly {
    const CRC_CHECKED: bool = false;
    fn layout(&self) -> &FrameLayout<'_> {
        &LAYOUT
    }
}

static T1: crc::Crc<u16, crc::Table<1>> = crc::Crc::<u16, crc::Table<1>>::new(&crc::CRC_16_UMTS);

#[test]
fn a_layout_without_crcs_computes_every_sum_as_any_layout_does() {
    let data: [u8; 200] = core::array::from_fn(|i| (i as u8).wrapping_mul(37) ^ 0x5A);
    let sums = [
        Checksum::Sum8,
        Checksum::SumMod255,
        Checksum::Xor8,
        Checksum::Xor { init: 0x21 },
        Checksum::Sum {
            width: 2,
            init: 0x1234,
            xorout: 0xFFFF,
        },
        Checksum::Fletcher16,
        Checksum::Fletcher16Mod256,
    ];
    for c in sums {
        for n in [0, 1, 7, 128, 129, 200, 201] {
            let input = &data[..n.min(200)];
            assert_eq!(
                c.compute_prefix_of::<SumsOnly>(&data, n),
                c.compute_prefix(&data, n),
                "{c:?} {n}"
            );
            assert_eq!(
                c.compute_written_of::<SumsOnly>(input),
                Some(c.compute_written(input)),
                "{c:?} {n}"
            );
        }
    }
}

#[test]
fn a_crc_is_computed_only_where_the_layout_declares_one() {
    let crc = Checksum::Crc16(CrcImpl::Table1(&T1));
    let check = b"123456789";
    assert_eq!(crc.compute_prefix_of::<SumsOnly>(check, 9), None);
    assert_eq!(crc.compute_written_of::<SumsOnly>(check), None);
    assert_eq!(crc.compute_prefix_of::<EveryKind>(check, 9), Some(0xFEE8));
    assert_eq!(crc.compute_written_of::<EveryKind>(check), Some(0xFEE8));
}
