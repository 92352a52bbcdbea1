//! Which payloads lose their trailing zeros on the wire: a command's, and only in a format that
//! truncates them. A payload written aside for another reason (stuffed) and a struct's payload
//! keep theirs, whatever [`PacketRules::wire_len`] and [`PacketRules::assemble`] are given.

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
use crate::layout::{ByteOrder, Check, LengthRule, Pos};

/// `AA len key payload.. sum`: `len` counts the whole frame.
static FRAME: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 2,
    min_len: 4,
    max_len: 32,
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

/// Payloads stuffed (a `00` after each `AA`), their trailing zeros kept.
static STUFFED: PacketRules<'static> = PacketRules {
    layout: &FRAME,
    header_len: 3,
    trailer_len: 1,
    max_payload: 28,
    key: &[WordField::le(2, 1)],
    ack: None,
    directions: &[],
    stuffing: Some(Stuffing {
        after: &[0xAA],
        insert: 0,
    }),
    truncate_zeros: false,
};

const COMMAND: Body<'static> = Body::Command {
    key: &[7],
    carried: None,
    direction: None,
};

/// The frame `rules` assemble of `body` and `payload`, its length as
/// [`PacketRules::frame_len`] of [`PacketRules::wire_len`] says, checked by the engine.
fn assembled(rules: &PacketRules<'_>, body: &Body<'_>, payload: &[u8]) -> Vec<u8> {
    let len = rules.frame_len(body, rules.wire_len(body, payload), 0);
    let mut buf = [0u8; 32];
    let mut aside = [0u8; 32];
    let n = rules
        .assemble(
            &mut buf,
            &mut aside,
            body,
            || len,
            0,
            |w| w.put_bytes(payload),
            |_| Ok(()),
        )
        .expect("assembles");
    assert_eq!(n, len, "frame_len agrees with what assemble writes");
    let frame = buf[..n].to_vec();
    assert_eq!(rules.layout.parse(&frame), Ok(&frame[..]), "a valid frame");
    frame
}

#[test]
fn a_stuffed_command_payload_keeps_its_trailing_zeros_where_the_format_keeps_them() {
    assert!(STUFFED.writes_aside(&COMMAND), "stuffed: written aside");
    assert_eq!(STUFFED.wire_len(&COMMAND, &[1, 0, 0]), 3);
    let frame = assembled(&STUFFED, &COMMAND, &[1, 0, 0]);
    assert_eq!(&frame[..7], &[0xAA, 7, 7, 1, 0, 0, 0xB9]);
    let mut scratch = [0u8; 32];
    assert_eq!(STUFFED.payload(&frame, &mut scratch), Ok(&[1, 0, 0][..]));
}

#[test]
fn a_struct_payload_keeps_its_trailing_zeros_where_a_command_payload_loses_them() {
    let rules = PacketRules {
        truncate_zeros: true,
        ..STUFFED
    };
    let body = Body::Struct { start: 2 };
    assert_eq!(rules.wire_len(&body, &[1, 0, 0]), 3);
    let frame = assembled(&rules, &body, &[1, 0, 0]);
    let mut scratch = [0u8; 32];
    assert_eq!(
        rules.payload_from(&frame, 2, &mut scratch),
        Ok(&[1, 0, 0][..])
    );
    // A command of the same format sends the byte before its zeros only.
    assert_eq!(rules.wire_len(&COMMAND, &[1, 0, 0]), 1);
    let frame = assembled(&rules, &COMMAND, &[1, 0, 0]);
    assert_eq!(rules.payload(&frame, &mut scratch), Ok(&[1][..]));
}
