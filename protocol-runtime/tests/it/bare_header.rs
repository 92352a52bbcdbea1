//! A bare header longer than the bytes that decide the length (`LengthRule::FieldOrBare`
//! with header fields after the length field): it is a frame only once all its bytes have
//! come, at every chunk size.
#![allow(clippy::unwrap_used)]

use crate::common;

use common::{Seen, check};
use protocol_runtime::checksum::Checksum;
use protocol_runtime::decoder::Probe;
use protocol_runtime::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos, WordField};

/// `AD 29 len set cmd payload after sum8`, `len` counting the whole frame; the five-byte
/// header alone is a frame too. The length is known after three bytes, the bare header after
/// five.
static BARE: FrameLayout<'static> = FrameLayout {
    sync: &[0xAD, 0x29],
    sync_set: &[],
    header_len: 3,
    min_len: 7,
    max_len: 16,
    length: LengthRule::FieldOrBare {
        field: WordField {
            at: Pos::Start(2),
            size: 1,
            order: ByteOrder::Big,
            shift: 0,
            width: 8,
        },
        adjust: 0,
        bare: 5,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum8,
        from: Pos::Start(0),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Big,
    }],
    markers: &[],
    escape: None,
};

#[test]
fn a_bare_header_is_awaited_to_its_last_byte() {
    let bare = [0xAD, 0x29, 5, 0, 2];
    assert_eq!(BARE.probe(&bare[..3]), Probe::Need(5));
    assert_eq!(BARE.probe(&bare[..4]), Probe::Need(5));
    assert_eq!(BARE.probe(&bare), Probe::Frame(5));
    assert!(BARE.parse(&bare[..4]).is_err());
    assert_eq!(BARE.parse(&bare).unwrap(), &bare);
}

#[test]
fn a_bare_header_streams_whole_at_every_chunk_size() {
    let bare = vec![0xAD, 0x29, 5, 1, 5];
    let mut stream = bare.clone();
    stream.extend([0x00, 0x11]);
    stream.extend(&bare);
    for chunk in 1..=stream.len() {
        let seen = check::<16>(&BARE, &stream, &[chunk], true);
        let frames: Vec<&Seen> = seen
            .iter()
            .filter(|s| matches!(s, Seen::Frame { .. }))
            .collect();
        assert_eq!(
            frames,
            [
                &Seen::Frame {
                    offset: 0,
                    bytes: bare.clone()
                },
                &Seen::Frame {
                    offset: 7,
                    bytes: bare.clone()
                }
            ],
            "chunk {chunk}"
        );
    }
    // Cut short at the end: the three bytes that decide the length are no frame.
    let seen = check::<16>(&BARE, &bare[..3], &[1], true);
    assert!(
        !seen.iter().any(|s| matches!(s, Seen::Frame { .. })),
        "{seen:?}"
    );
}
