//! The packet rules on small formats, each through the engine's own parsing and sealing: what
//! [`PacketRules::assemble`] writes, the decoding functions take apart again.

#![allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

extern crate std;

use std::vec;
use std::vec::Vec;

use super::*;
use crate::checksum::Checksum;
use crate::encoder::write_header;
use crate::error::{DecodeError, EncodeError};
use crate::layout::{Check, LengthExtension, LengthRule, Pos};

/// `AA len flags key0 key1 payload.. sum`: `len` counts the whole frame; bit 0 of `flags` marks
/// an acknowledgement, whose data follows `flags` (no key); bit 1 tells the direction; an
/// acknowledgement without data is the 3-byte header alone.
static ACKED: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 2,
    min_len: 4,
    max_len: 20,
    length: LengthRule::FieldOrBare {
        field: WordField::le(1, 1),
        adjust: 0,
        bare: 3,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum8,
        from: Pos::Start(0),
        to: Pos::End(1),
        at: Pos::End(1),
        order: crate::layout::ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

static ACKED_RULES: PacketRules<'static> = PacketRules {
    layout: &ACKED,
    header_len: 5,
    trailer_len: 1,
    max_payload: 14,
    key: &[WordField::le(3, 1), WordField::le(4, 1)],
    ack: Some(AckRule {
        flag: WordField::le(2, 1).bits(0, 1),
        equals: 1,
        header_len: 3,
        bare: true,
    }),
    directions: &[
        DirectionTest::Equals {
            field: WordField::le(2, 1).bits(1, 1),
            value: 0,
        },
        DirectionTest::Equals {
            field: WordField::le(2, 1).bits(1, 1),
            value: 1,
        },
    ],
    stuffing: None,
    truncate_zeros: false,
};

/// Encodes `body` with `payload` and the direction bit `dir`; the frame, checked by the engine.
fn encode(rules: &PacketRules<'_>, body: &Body<'_>, payload: &[u8], dir: u64) -> Vec<u8> {
    let mut aside = [0u8; 512];
    let len = rules.frame_len(body, rules.wire_len(body, payload), 0);
    let mut buf = [0u8; 512];
    let n = rules
        .assemble(
            &mut buf,
            &mut aside,
            body,
            || len,
            0,
            |w| w.put_bytes(payload),
            |frame| write_header(frame, WordField::le(2, 1).bits(1, 1), dir),
        )
        .expect("assembles");
    assert_eq!(n, len, "frame_len agrees with what assemble writes");
    let frame = buf[..n].to_vec();
    assert_eq!(
        rules.layout.parse(&frame),
        Ok(&frame[..]),
        "the engine accepts it"
    );
    frame
}

#[test]
fn a_command_frame_comes_apart_into_key_direction_and_payload() {
    let body = Body::Command {
        key: &[0x12, 0x34],
        carried: None,
        direction: Some(1),
    };
    let frame = encode(&ACKED_RULES, &body, &[7, 8, 9], 1);
    assert_eq!(&frame[..5], &[0xAA, 9, 0b10, 0x12, 0x34]);
    assert_eq!(ACKED_RULES.ack_data(&frame), Ok(None));
    assert_eq!(ACKED_RULES.key(&frame), Ok(0x1234));
    assert_eq!(ACKED_RULES.key_value(&frame, 1), Ok(0x34));
    assert_eq!(ACKED_RULES.direction(&frame), Ok(1));
    let mut scratch = [0u8; 16];
    assert_eq!(
        ACKED_RULES.payload(&frame, &mut scratch),
        Ok(&[7, 8, 9][..])
    );
}

#[test]
fn a_header_that_does_not_tell_the_message_direction_is_refused() {
    let body = Body::Command {
        key: &[1, 2],
        carried: None,
        direction: Some(0),
    };
    let mut buf = [0u8; 32];
    let header = |frame: &mut [u8]| write_header(frame, WordField::le(2, 1).bits(1, 1), 1);
    let len = ACKED_RULES.frame_len(&body, 0, 0);
    let got = ACKED_RULES.assemble(&mut buf, &mut [], &body, || len, 0, |_| Ok(()), header);
    assert_eq!(
        got,
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE
        })
    );
}

#[test]
fn an_acknowledgement_carries_data_and_an_empty_one_is_a_bare_header() {
    let frame = encode(&ACKED_RULES, &Body::Ack, &[5, 6], 0);
    assert_eq!(frame, [0xAA, 6, 1, 5, 6, 0xAA + 6 + 1 + 5 + 6]);
    assert_eq!(ACKED_RULES.ack_data(&frame), Ok(Some(&[5, 6][..])));
    let bare = encode(&ACKED_RULES, &Body::Ack, &[], 0);
    assert_eq!(bare, [0xAA, 3, 1]);
    // Into a buffer of exactly its length, though a trailer would not fit after the header.
    let mut exact = [0u8; 3];
    let len = ACKED_RULES.frame_len(&Body::Ack, 0, 0);
    let got = ACKED_RULES.assemble(
        &mut exact,
        &mut [],
        &Body::Ack,
        || len,
        0,
        |_| Ok(()),
        |_| Ok(()),
    );
    assert_eq!((got, exact), (Ok(3), [0xAA, 3, 1]));
    assert_eq!(ACKED_RULES.ack_data(&bare), Ok(Some(&[][..])));
    // Ack data longer than the largest frame holds.
    let mut long = [0u8; 24];
    long[2] = 1;
    assert_eq!(
        ACKED_RULES.ack_data(&long),
        Err(DecodeError::PayloadLength {
            expected: ACKED_RULES.ack_max(),
            actual: 20
        })
    );
}

#[test]
fn a_key_value_that_does_not_fit_its_field_is_out_of_range() {
    let body = Body::Command {
        key: &[0x100, 0],
        carried: None,
        direction: None,
    };
    let mut buf = [0u8; 32];
    let len = ACKED_RULES.frame_len(&body, 0, 0);
    let got = ACKED_RULES.assemble(&mut buf, &mut [], &body, || len, 0, |_| Ok(()), |_| Ok(()));
    assert_eq!(
        got,
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE
        })
    );
}

#[test]
fn short_frames_are_truncated_errors_not_panics() {
    let mut scratch = [0u8; 4];
    for len in 0..5 {
        let frame = [0xAAu8, 0, 0, 0, 0];
        let frame = &frame[..len];
        let _ = ACKED_RULES.ack_data(frame);
        assert!(ACKED_RULES.key(frame).is_err() || len >= 5);
        let _ = ACKED_RULES.direction(frame);
        let _ = ACKED_RULES.payload(frame, &mut scratch);
    }
}

/// `24 M len cmd payload.. xor` with MSP v1's jumbo form: a `len` of 255 announces a `u16le`
/// count after `cmd`; trailing zeros of command payloads are dropped, stuffing inserts `00`
/// after `24 4D`.
static WIDE: FrameLayout<'static> = FrameLayout {
    sync: &[0x24, 0x4D],
    sync_set: &[],
    header_len: 4,
    min_len: 5,
    max_len: 400,
    length: LengthRule::Conditional {
        field: WordField::le(2, 1),
        adjust: 5,
        extension: Some(LengthExtension {
            marker: 255,
            wide: WordField::le(4, 2),
            len: 2,
        }),
        trailer: None,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Xor8,
        from: Pos::Start(2),
        to: Pos::End(1),
        at: Pos::End(1),
        order: crate::layout::ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

static WIDE_RULES: PacketRules<'static> = PacketRules {
    layout: &WIDE,
    header_len: 4,
    trailer_len: 1,
    max_payload: 395,
    key: &[WordField::le(3, 1)],
    ack: None,
    directions: &[],
    stuffing: Some(Stuffing {
        after: &[0x24, 0x4D],
        insert: 0,
    }),
    truncate_zeros: true,
};

fn command(key: &[u64]) -> Body<'_> {
    Body::Command {
        key,
        carried: None,
        direction: None,
    }
}

#[test]
fn trailing_zeros_are_trimmed_on_the_wire_and_refilled_for_the_struct() {
    let frame = encode(&WIDE_RULES, &command(&[7]), &[1, 0, 2, 0, 0], 0);
    assert_eq!(frame[2], 3, "three bytes sent");
    let mut scratch = [0u8; 400];
    let sent = WIDE_RULES.payload(&frame, &mut scratch).map(<[u8]>::to_vec);
    assert_eq!(sent, Ok(vec![1, 0, 2]));
    let mut filled = [0xFFu8; 8];
    let sent = sent.unwrap_or_default();
    assert_eq!(
        WIDE_RULES.filled(&sent, 5, None, &mut filled),
        Ok(&[1, 0, 2, 0, 0][..])
    );
    // An all-zero payload keeps its first byte.
    let frame = encode(&WIDE_RULES, &command(&[7]), &[0, 0], 0);
    assert_eq!(frame[2], 1);
}

#[test]
fn stuffed_bytes_are_inserted_on_encode_and_removed_on_decode() {
    let payload = [0x24, 0x4D, 0x10];
    let frame = encode(&WIDE_RULES, &command(&[1]), &payload, 0);
    assert_eq!(&frame[4..8], &[0x24, 0x4D, 0x00, 0x10]);
    let mut scratch = [0u8; 400];
    assert_eq!(WIDE_RULES.payload(&frame, &mut scratch), Ok(&payload[..]));
}

#[test]
fn a_payload_past_the_marker_moves_behind_the_wider_length() {
    let payload: Vec<u8> = (0..300u32).map(|i| (i % 200) as u8 + 1).collect();
    let frame = encode(&WIDE_RULES, &command(&[9]), &payload, 0);
    assert_eq!(frame[2], 255);
    assert_eq!(frame.len(), 4 + 2 + 300 + 1);
    let mut scratch = [0u8; 400];
    assert_eq!(WIDE_RULES.payload(&frame, &mut scratch), Ok(&payload[..]));
}

#[test]
fn a_format_without_extension_fields_carries_exactly_the_fields_before_them() {
    let body = Body::Command {
        key: &[3],
        carried: Some(2),
        direction: None,
    };
    let rules = PacketRules {
        truncate_zeros: false,
        stuffing: None,
        ..WIDE_RULES
    };
    let frame = encode(&rules, &body, &[4, 5, 6, 7], 0);
    let mut scratch = [0u8; 400];
    let sent = rules.payload(&frame, &mut scratch).map(<[u8]>::to_vec);
    assert_eq!(sent, Ok(vec![4, 5]));
    let mut filled = [0xFFu8; 8];
    assert_eq!(
        rules.filled(&[4, 5], 4, Some(2), &mut filled),
        Ok(&[4, 5, 0, 0][..])
    );
    assert_eq!(
        rules.filled(&[4, 5, 6], 4, Some(2), &mut filled),
        Err(DecodeError::PayloadLength {
            expected: 2,
            actual: 3
        })
    );
}

#[test]
fn a_buffer_too_small_for_the_frame_is_an_error() {
    let body = command(&[1]);
    let payload = [1u8, 2, 3];
    let len = WIDE_RULES.frame_len(&body, WIDE_RULES.wire_len(&body, &payload), 0);
    for size in 0..len {
        let mut buf = vec![0u8; size];
        let mut aside = [0u8; 16];
        let got = WIDE_RULES.assemble(
            &mut buf,
            &mut aside,
            &body,
            || len,
            0,
            |w| w.put_bytes(&payload),
            |_| Ok(()),
        );
        assert!(
            matches!(got, Err(EncodeError::BufferTooSmall { .. })),
            "{size}: {got:?}"
        );
    }
}

#[test]
fn acknowledgement_data_is_not_stuffed() {
    let rules = PacketRules {
        stuffing: Some(Stuffing {
            after: &[5],
            insert: 0,
        }),
        ..ACKED_RULES
    };
    let frame = encode(&rules, &Body::Ack, &[5, 6], 0);
    assert_eq!(rules.ack_data(&frame), Ok(Some(&[5, 6][..])));
    let body = Body::Command {
        key: &[1, 2],
        carried: None,
        direction: Some(0),
    };
    let frame = encode(&rules, &body, &[5, 6], 0);
    assert_eq!(&frame[5..8], &[5, 0, 6], "a command's payload is");
}
