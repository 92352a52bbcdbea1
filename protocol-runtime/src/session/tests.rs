//! The machines against hand-written rules: `AA seq cmd sum8`, command 1 the handshake
//! (answered by itself), 2 a request with one retry, 3 fire-and-forget, 9 the NACK, 4 the
//! watchdog's command.

#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::panic)]

use super::*;
use crate::checksum::Checksum;
use crate::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos};

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
static RULES: PacketRules<'static> = PacketRules {
    layout: &LAYOUT,
    header_len: 3,
    trailer_len: 1,
    max_payload: 0,
    key: &[WordField::le(2, 1)],
    ack: None,
    directions: &[],
    stuffing: None,
    truncate_zeros: false,
};
const fn exchange(key: u64, answer: Answer, retries: u8) -> Exchange {
    Exchange {
        key,
        answer,
        timeout: 10,
        retries,
        backoff: 2,
    }
}
const BASE: SessionRules<'static> = SessionRules {
    packet: &RULES,
    default: exchange(0, Answer::None, 0),
    exchanges: &[exchange(1, Answer::Reply, 0), exchange(2, Answer::Reply, 1)],
    sequence: Some(WordField::le(1, 1)),
    echo: &[],
    swap: None,
    pairs: &[],
    nack: Some(9),
    handshake: Some(1),
    watchdog: Some(Watchdog {
        key: 4,
        period: 100,
    }),
    modes: None,
};
static SESSION: SessionRules<'static> = BASE;
/// The same rules without the handshake.
static OPEN: SessionRules<'static> = SessionRules {
    handshake: None,
    ..BASE
};

fn frame(cmd: u8) -> [u8; 4] {
    [0xAA, 0, cmd, 0]
}

#[test]
fn requests_wait_for_the_handshake_on_both_sides() {
    let mut req = Requester::<_, 2, 4>::new(&SESSION);
    let mut res = Responder::<_, 2, 4>::new(&SESSION);
    assert_eq!(req.send(0, &mut frame(2)), Err(SendError::Handshake));
    let mut early = frame(2);
    LAYOUT.seal(&mut early).unwrap();
    assert_eq!(res.on_frame(0, &early), Incoming::BeforeHandshake);

    let mut hello = frame(1);
    let t = req.send(0, &mut hello).unwrap().unwrap();
    assert_eq!(res.on_frame(1, &hello), Incoming::Deliver { answer: true });
    let mut reply = frame(1);
    res.answer(&hello, &mut reply).unwrap();
    assert_eq!(
        req.on_frame(2, &reply),
        Received::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::Answered
        })
    );
    assert!(req.handshaken() && res.handshaken());
    assert!(req.send(3, &mut frame(2)).unwrap().is_some());
}

#[test]
fn a_retry_is_answered_again_and_delivered_once() {
    let mut req = Requester::<_, 2, 4>::new(&OPEN);
    let mut res = Responder::<_, 2, 4>::new(&OPEN);
    let mut ask = frame(2);
    let t = req.send(0, &mut ask).unwrap().unwrap();
    assert_eq!(res.on_frame(1, &ask), Incoming::Deliver { answer: true });
    let mut reply = frame(2);
    res.answer(&ask, &mut reply).unwrap();
    // The reply is lost: after 10 ms the request goes again, and the responder resends.
    let Some(Due::Resend {
        ticket,
        frame: again,
    }) = req.poll(10)
    else {
        panic!("a retry")
    };
    assert_eq!((ticket, again), (t, &ask[..]));
    assert_eq!(
        res.on_frame(11, &ask),
        Incoming::Duplicate(Some(&reply[..]))
    );
    let Received::Outcome(o) = req.on_frame(12, &reply) else {
        panic!("an outcome")
    };
    assert_eq!((o.ticket, o.resolution), (t, Resolution::Answered));
    assert_eq!(req.poll(1000), None);
}

#[test]
fn a_request_times_out_after_its_retries_with_backoff() {
    let mut req = Requester::<_, 2, 4>::new(&OPEN);
    let t = req.send(0, &mut frame(2)).unwrap().unwrap();
    assert_eq!(req.poll(9), None);
    assert!(matches!(req.poll(10), Some(Due::Resend { .. })));
    assert_eq!(req.next_deadline(), Some(30));
    assert_eq!(req.poll(29), None);
    assert_eq!(
        req.poll(30),
        Some(Due::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::TimedOut
        }))
    );
    assert_eq!(req.open(), 0);
}

#[test]
fn a_nack_refuses_and_fire_and_forget_holds_no_slot() {
    let mut req = Requester::<_, 1, 4>::new(&OPEN);
    assert_eq!(req.send(0, &mut frame(3)), Ok(None));
    let mut ask = frame(2);
    let t = req.send(0, &mut ask).unwrap().unwrap();
    assert_eq!(req.send(0, &mut frame(2)), Err(SendError::Full));
    let mut nack = frame(9);
    nack[1] = ask[1];
    LAYOUT.seal(&mut nack).unwrap();
    assert_eq!(
        req.on_frame(1, &nack),
        Received::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::Refused
        })
    );
    assert_eq!(req.on_frame(2, &nack), Received::Unsolicited);
}

#[test]
fn the_watchdog_expires_once_per_lapse() {
    let mut res = Responder::<_, 1, 4>::new(&OPEN);
    assert_eq!(res.poll(1000), None);
    let mut feed = frame(4);
    LAYOUT.seal(&mut feed).unwrap();
    res.on_frame(0, &feed);
    assert_eq!(res.poll(99), None);
    assert_eq!(res.poll(100), Some(Alarm::WatchdogExpired));
    assert_eq!(res.poll(200), None);
    feed[1] = 1;
    LAYOUT.seal(&mut feed).unwrap();
    res.on_frame(250, &feed);
    assert_eq!(res.poll(350), Some(Alarm::WatchdogExpired));
}
