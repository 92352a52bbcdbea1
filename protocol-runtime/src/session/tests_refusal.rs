//! Refusals by a direction of their own: `AA dir cmd sum8`, where `dir` is `<` (0x3C) for a
//! request, `>` (0x3E) for its reply and `!` (0x21) for an error reply (MSP's three
//! directions); every request expects the same command back, once, within 10 ms.

#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::panic)]

use super::*;
use crate::checksum::Checksum;
use crate::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos};
use crate::rules::DirectionTest;

const REQUEST: u8 = 0x3C;
const REPLY: u8 = 0x3E;
const ERROR: u8 = 0x21;

static LAYOUT: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 3,
    min_len: 4,
    max_len: 4,
    length: LengthRule::Fixed(4),
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
const DIR: WordField = WordField::le(1, 1);
static RULES: PacketRules<'static> = PacketRules {
    layout: &LAYOUT,
    header_len: 3,
    trailer_len: 1,
    max_payload: 0,
    key: &[WordField::le(2, 1)],
    ack: None,
    directions: &[
        DirectionTest::Equals {
            field: DIR,
            value: REQUEST as u64,
        },
        DirectionTest::Equals {
            field: DIR,
            value: REPLY as u64,
        },
        DirectionTest::Equals {
            field: DIR,
            value: ERROR as u64,
        },
    ],
    stuffing: None,
    truncate_zeros: false,
};
/// Direction 2, the error replies, refuses.
static SESSION: SessionRules<'static> = SessionRules {
    packet: &RULES,
    default: Exchange {
        key: 0,
        answer: Answer::Reply,
        timeout: 10,
        retries: 0,
        backoff: 1,
    },
    exchanges: &[],
    sequence: None,
    echo: &[],
    swap: None,
    pairs: &[],
    nack: None,
    refusals: &[2],
    handshake: None,
    watchdog: None,
    modes: None,
    verdicts: &[],
    periodic: &[],
    fanouts: &[],
};
/// The same rules without refusals: the error reply is just another frame of its command.
static BLIND: SessionRules<'static> = SessionRules {
    refusals: &[],
    ..SESSION
};

/// A sealed frame of direction `dir` and command `cmd`.
fn frame(dir: u8, cmd: u8) -> [u8; 4] {
    let mut f = [0xAA, dir, cmd, 0];
    LAYOUT.seal(&mut f).unwrap();
    f
}

#[test]
fn an_error_reply_refuses_the_request_of_its_command() {
    let mut req = Requester::<_, 4, 4>::new(&SESSION);
    let status = req.send(0, &mut frame(REQUEST, 101)).unwrap().unwrap();
    let attitude = req.send(0, &mut frame(REQUEST, 108)).unwrap().unwrap();
    // A refusal of a command nothing asked for refuses nothing.
    assert_eq!(req.on_frame(1, &frame(ERROR, 7)), Received::Unsolicited);
    assert_eq!(
        req.on_frame(2, &frame(ERROR, 108)),
        Received::Outcome(Outcome {
            ticket: attitude,
            resolution: Resolution::Refused,
        })
    );
    assert_eq!(
        req.on_frame(3, &frame(REPLY, 101)),
        Received::Outcome(Outcome {
            ticket: status,
            resolution: Resolution::Answered,
        })
    );
    assert_eq!(req.open(), 0);
    // The refused request has its one outcome: its late reply is unsolicited.
    assert_eq!(req.on_frame(4, &frame(REPLY, 108)), Received::Unsolicited);
    assert_eq!(req.poll(100), None);
}

#[test]
fn without_refusals_the_error_reply_is_taken_for_the_answer() {
    let mut req = Requester::<_, 4, 4>::new(&BLIND);
    let ticket = req.send(0, &mut frame(REQUEST, 101)).unwrap().unwrap();
    assert_eq!(
        req.on_frame(1, &frame(ERROR, 101)),
        Received::Outcome(Outcome {
            ticket,
            resolution: Resolution::Answered,
        })
    );
}

#[test]
fn an_error_reply_is_not_a_request() {
    let mut req = Requester::<_, 4, 4>::new(&SESSION);
    assert_eq!(
        req.send(0, &mut frame(ERROR, 101)),
        Err(SendError::NotARequest(DecodeError::UnknownDirection))
    );
    assert_eq!(req.open(), 0);
    assert!(SESSION.refuses(&frame(ERROR, 101)));
    assert!(!SESSION.refuses(&frame(REPLY, 101)));
    assert!(!BLIND.refuses(&frame(ERROR, 101)));
}

#[test]
fn the_observer_pairs_an_error_reply_as_a_refusal() {
    let mut wire = Observer::<4>::new();
    assert!(wire.request(&SESSION, 0, Some(100), &frame(REQUEST, 101)));
    assert!(!wire.request(&SESSION, 1, Some(101), &frame(ERROR, 5)));
    assert_eq!(wire.answer(&SESSION, Some(102), &frame(ERROR, 7)), None);
    assert_eq!(
        wire.answer(&SESSION, Some(104), &frame(ERROR, 101)),
        Some(Paired {
            request: 0,
            round_trip: Some(4),
            open: false,
            refused: true,
        })
    );
    assert!(wire.request(&SESSION, 3, Some(110), &frame(REQUEST, 108)));
    assert_eq!(
        wire.answer(&SESSION, Some(111), &frame(REPLY, 108)),
        Some(Paired {
            request: 3,
            round_trip: Some(1),
            open: false,
            refused: false,
        })
    );
    assert_eq!((wire.answered(), wire.finish()), (2, 0));
}
