//! The packet rules on the header cases the formats of `tests` leave out: directions told by
//! address ranges (one, two overlapping, three), a key of three fields, acknowledgement data at
//! its largest and a header-only acknowledgement where the format has no bare form, and messages
//! encoded through [`PacketRules::encode_message`] as [`PacketRules::assemble`] encodes them.

#![allow(
    clippy::indexing_slicing,
    clippy::arithmetic_side_effects,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]

extern crate std;

use std::vec::Vec;

use super::*;
use crate::checksum::Checksum;
use crate::encoder::{CommandName, MessagePayload, PayloadVisitor, write_header};
use crate::error::{DecodeError, EncodeError};
use crate::layout::{ByteOrder, Check, LengthRule, Pos};

/// `AA len dst k0 k1 k2 payload.. sum`: `len` counts the whole frame, `dst` is an address
/// whose range tells the direction.
static FRAME: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 2,
    min_len: 4,
    max_len: 12,
    length: LengthRule::Field {
        field: WordField::le(1, 1),
        adjust: 0,
    },
    constants: &[],
    header_checks: &[],
    frame_checks: &[Check {
        checksum: Checksum::Sum8,
        from: Pos::Start(0),
        to: Pos::End(1),
        at: Pos::End(1),
        order: ByteOrder::Little,
    }],
    markers: &[],
    escape: None,
};

const DST: WordField = WordField::le(2, 1);

/// Three directions: addresses `00..=0F`, `10..=1F` and `20..=2F`.
static THREE: PacketRules<'static> = PacketRules {
    layout: &FRAME,
    header_len: 6,
    trailer_len: 1,
    max_payload: 5,
    key: &[
        WordField::le(3, 1),
        WordField::le(4, 1),
        WordField::le(5, 1),
    ],
    ack: None,
    directions: &[
        DirectionTest::in_range(DST, 0x00, 0x0F),
        DirectionTest::in_range(DST, 0x10, 0x1F),
        DirectionTest::in_range(DST, 0x20, 0x2F),
    ],
    stuffing: None,
    truncate_zeros: false,
};

/// A frame of `rules` carrying `key` and `payload` to address `dst`, checked by the engine.
fn frame_to(rules: &PacketRules<'_>, key: &[u64], dst: u64, payload: &[u8]) -> Vec<u8> {
    let body = Body::Command {
        key,
        carried: None,
        direction: None,
    };
    let len = rules.frame_len(&body, rules.wire_len(&body, payload), 0);
    let mut buf = [0u8; 32];
    let mut aside = [0u8; 32];
    let n = rules
        .assemble(
            &mut buf,
            &mut aside,
            &body,
            || len,
            0,
            |w| w.put_bytes(payload),
            |frame| write_header(frame, DST, dst),
        )
        .expect("assembles");
    let frame = buf[..n].to_vec();
    assert_eq!(rules.layout.parse(&frame), Ok(&frame[..]), "a valid frame");
    frame
}

/// The direction each of `dsts` tells under `rules`, with [`PacketRules::tells`] checked to
/// agree for directions 0 to 3.
fn directions(rules: &PacketRules<'_>, dsts: &[u64]) -> Vec<Result<usize, DecodeError>> {
    dsts.iter()
        .map(|&dst| {
            let frame = frame_to(rules, &[1, 2, 3], dst, &[]);
            let told = rules.direction(&frame);
            for d in 0..4 {
                assert_eq!(rules.tells(&frame, d), told == Ok(d), "{dst:#x} tells {d}?");
            }
            told
        })
        .collect()
}

#[test]
fn three_address_ranges_tell_three_directions_up_to_their_bounds() {
    let told = directions(&THREE, &[0x00, 0x0F, 0x10, 0x1F, 0x20, 0x2F, 0x30]);
    let unknown = Err(DecodeError::UnknownDirection);
    assert_eq!(told, [Ok(0), Ok(0), Ok(1), Ok(1), Ok(2), Ok(2), unknown]);
}

#[test]
fn one_address_range_tells_one_direction() {
    let rules = PacketRules {
        directions: &[DirectionTest::in_range(DST, 0x10, 0x1F)],
        ..THREE
    };
    let told = directions(&rules, &[0x0F, 0x10, 0x1F, 0x20]);
    let unknown = Err(DecodeError::UnknownDirection);
    assert_eq!(told, [unknown, Ok(0), Ok(0), unknown]);
}

#[test]
fn of_two_overlapping_ranges_the_first_that_holds_tells() {
    let rules = PacketRules {
        directions: &[
            DirectionTest::in_range(DST, 0x00, 0x1F),
            DirectionTest::equals(DST, 0x18),
        ],
        ..THREE
    };
    // 0x18 passes both tests: the first names it.
    let told = directions(&rules, &[0x05, 0x18, 0x20]);
    assert_eq!(told, [Ok(0), Ok(0), Err(DecodeError::UnknownDirection)]);
    let rules = PacketRules {
        directions: &[
            DirectionTest::in_range(DST, 0x00, 0x0F),
            DirectionTest::in_range(DST, 0x10, 0x1F),
        ],
        ..THREE
    };
    let told = directions(&rules, &[0x0F, 0x10, 0x20]);
    assert_eq!(told, [Ok(0), Ok(1), Err(DecodeError::UnknownDirection)]);
}

#[test]
fn a_message_is_refused_when_its_header_tells_another_direction() {
    let mut buf = [0u8; 32];
    for (dst, direction, ok) in [(0x05, 0, true), (0x15, 0, false), (0x25, 2, true)] {
        let body = Body::Command {
            key: &[1, 2, 3],
            carried: None,
            direction: Some(direction),
        };
        let len = THREE.frame_len(&body, 0, 0);
        let header = |frame: &mut [u8]| write_header(frame, DST, dst);
        let got = THREE.assemble(&mut buf, &mut [], &body, || len, 0, |_| Ok(()), header);
        let refused = Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE,
        });
        assert_eq!(
            got.is_ok(),
            ok,
            "{dst:#x} as direction {direction}: {got:?}"
        );
        if !ok {
            assert_eq!(got, refused);
        }
    }
}

#[test]
fn a_key_of_three_fields_is_written_and_read_whole() {
    let frame = frame_to(&THREE, &[0x0A, 0x0B, 0x0C], 0, &[9]);
    assert_eq!(&frame[3..6], &[0x0A, 0x0B, 0x0C]);
    assert_eq!(THREE.key(&frame), Ok(0x0A_0B0C));
    assert_eq!(THREE.key_value(&frame, 2), Ok(0x0C));
    assert_eq!(
        THREE.key_value(&frame, 3),
        Err(DecodeError::Truncated {
            needed: 6,
            available: frame.len()
        })
    );
    // Fewer values than key fields: refused, not written in part.
    let body = Body::Command {
        key: &[1, 2],
        carried: None,
        direction: None,
    };
    let mut buf = [0u8; 32];
    let len = THREE.frame_len(&body, 0, 0);
    let got = THREE.assemble(&mut buf, &mut [], &body, || len, 0, |_| Ok(()), |_| Ok(()));
    assert_eq!(
        got,
        Err(EncodeError::ValueOutOfRange {
            place: crate::error::Place::NONE
        })
    );
}

/// `AA len flags key payload.. sum`; bit 0 of `flags` marks an acknowledgement, whose data
/// follows `flags`; every frame has the trailer (no bare header).
static ACKS: PacketRules<'static> = PacketRules {
    layout: &FRAME,
    header_len: 4,
    trailer_len: 1,
    max_payload: 7,
    key: &[WordField::le(3, 1)],
    ack: Some(AckRule {
        flag: WordField::le(2, 1).bits(0, 1),
        equals: 1,
        header_len: 3,
        bare: false,
    }),
    directions: &[],
    stuffing: None,
    truncate_zeros: false,
};

/// An acknowledgement frame with `data`, its length and sum filled in (not limited to the
/// layout's largest frame).
fn ack_frame(data: &[u8]) -> Vec<u8> {
    let mut frame = Vec::from([0xAA, u8::try_from(data.len() + 4).unwrap(), 1]);
    frame.extend_from_slice(data);
    let sum = frame.iter().fold(0u8, |s, b| s.wrapping_add(*b));
    frame.push(sum);
    frame
}

#[test]
fn acknowledgement_data_may_fill_the_largest_frame_and_no_more() {
    // 12 bytes at most: 3 of header, 1 of trailer.
    assert_eq!(ACKS.ack_max(), 8);
    let full = ack_frame(&[7; 8]);
    assert_eq!(FRAME.parse(&full), Ok(&full[..]));
    assert_eq!(ACKS.ack_data(&full), Ok(Some(&[7u8; 8][..])));
    assert_eq!(
        ACKS.ack_data(&ack_frame(&[7; 9])),
        Err(DecodeError::PayloadLength {
            expected: 8,
            actual: 9
        })
    );
    // A command's header is longer: the largest acknowledgement data is not its payload's.
    let no_acks = PacketRules { ack: None, ..ACKS };
    assert_eq!(no_acks.ack_max(), 7);
}

#[test]
fn without_a_bare_form_a_header_alone_is_a_truncated_acknowledgement() {
    assert_eq!(ACKS.ack_data(&ack_frame(&[])), Ok(Some(&[][..])));
    assert_eq!(
        ACKS.ack_data(&[0xAA, 3, 1]),
        Err(DecodeError::Truncated {
            needed: 3,
            available: 3
        })
    );
}

/// A message of one command, `SET`, whose payload is three bytes.
struct Set([u8; 3]);

/// The command of [`Set`].
struct SetCommand;

impl CommandName for SetCommand {
    fn command_name(&self) -> &'static str {
        "SET"
    }
}

impl MessagePayload for Set {
    type Command = SetCommand;

    fn visit_payload<V: PayloadVisitor<SetCommand>>(&self, v: V) -> V::Output {
        v.visit(SetCommand, &self.0)
    }
}

/// The frame `encode_message` writes for `message` to address `dst`, with its length checked
/// against `message_len`.
fn encode_message(rules: &PacketRules<'_>, message: &Set, dst: u64) -> Vec<u8> {
    let body = Body::Command {
        key: &[4, 5, 6],
        carried: None,
        direction: None,
    };
    let mut buf = [0u8; 32];
    let mut aside = [0u8; 32];
    let header = |frame: &mut [u8]| write_header(frame, DST, dst);
    let n = rules
        .encode_message(&mut buf, &mut aside, &body, message, 0, header)
        .expect("encodes");
    let len = rules.message_len(&body, message, &mut [0u8; 32], 0);
    assert_eq!(n, len, "message_len agrees with what encode_message writes");
    buf[..n].to_vec()
}

#[test]
fn encode_message_writes_the_frame_assemble_writes() {
    let message = Set([1, 0, 0]);
    let frame = encode_message(&THREE, &message, 0x12);
    assert_eq!(frame, frame_to(&THREE, &[4, 5, 6], 0x12, &[1, 0, 0]));
    assert_eq!(frame.len(), 6 + 3 + 1);
    // Written aside and trimmed where the format drops trailing zeros.
    let trimmed = PacketRules {
        truncate_zeros: true,
        ..THREE
    };
    let frame = encode_message(&trimmed, &message, 0x12);
    assert_eq!(frame, frame_to(&trimmed, &[4, 5, 6], 0x12, &[1, 0, 0]));
    assert_eq!(frame.len(), 6 + 1 + 1);
}

#[test]
fn a_payload_the_wire_carries_as_written_needs_no_aside_buffer() {
    let body = Body::Command {
        key: &[4, 5, 6],
        carried: None,
        direction: None,
    };
    assert!(!THREE.writes_aside(&body));
    let mut buf = [0u8; 32];
    let len = THREE.frame_len(&body, 3, 0);
    let n = THREE.assemble(
        &mut buf,
        &mut [],
        &body,
        || len,
        0,
        |w| w.put_bytes(&[1, 0, 0]),
        |frame| write_header(frame, DST, 0x12),
    );
    assert_eq!(n, Ok(10));
    assert_eq!(
        buf[..10],
        frame_to(&THREE, &[4, 5, 6], 0x12, &[1, 0, 0])[..]
    );
    // Trimming trailing zeros writes aside, and an empty aside buffer has no room for them.
    let trimmed = PacketRules {
        truncate_zeros: true,
        ..THREE
    };
    assert!(trimmed.writes_aside(&body));
    let got = trimmed.assemble(
        &mut buf,
        &mut [],
        &body,
        || len,
        0,
        |w| w.put_bytes(&[1, 0, 0]),
        |_| Ok(()),
    );
    assert!(
        matches!(got, Err(EncodeError::BufferTooSmall { .. })),
        "{got:?}"
    );
}
