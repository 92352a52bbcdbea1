//! The machines against hand-written rules: `AA seq cmd sum8`, command 1 the handshake
//! (answered by itself), 2 a request with one retry, 3 fire-and-forget, 9 the NACK, 4 the
//! watchdog's command; and `AA seq cmd result sum8`, where command 3 answers command 2 with a
//! result value.

#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::panic)]

// The scheduler's test collects what it sends; the crate is `no_std` without its `std` feature.
extern crate std;

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
    refusals: &[],
    handshake: Some(1),
    watchdog: Some(Watchdog {
        key: 4,
        period: 100,
    }),
    modes: None,
    verdicts: &[],
    periodic: &[],
    fanouts: &[],
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
fn the_observer_pairs_the_nack_as_the_refusal_of_the_request_it_repeats() {
    let mut wire = Observer::<4>::new();
    let mut ask = frame(2);
    ask[1] = 7;
    LAYOUT.seal(&mut ask).unwrap();
    assert!(wire.request(&OPEN, 0, Some(10), &ask));
    let mut other = frame(9);
    other[1] = 8;
    LAYOUT.seal(&mut other).unwrap();
    assert_eq!(wire.answer(&OPEN, Some(11), &other), None);
    let mut nack = frame(9);
    nack[1] = 7;
    LAYOUT.seal(&mut nack).unwrap();
    assert_eq!(
        wire.answer(&OPEN, Some(12), &nack),
        Some(Paired {
            request: 0,
            round_trip: Some(2),
            open: false,
            refused: true,
        })
    );
    assert_eq!(wire.answer(&OPEN, Some(13), &nack), None);
    assert_eq!((wire.answered(), wire.finish()), (1, 0));
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

/// `AA seq cmd result sum8`: command 2 is answered by command 3, whose result byte says 0
/// accepted, 5 in progress, anything else refused.
static LAYOUT_RESULT: FrameLayout<'static> = FrameLayout {
    header_len: 3,
    min_len: 5,
    max_len: 5,
    length: LengthRule::Fixed(5),
    ..LAYOUT
};
static RULES_RESULT: PacketRules<'static> = PacketRules {
    layout: &LAYOUT_RESULT,
    max_payload: 1,
    ..RULES
};
static RESULT: SessionRules<'static> = SessionRules {
    packet: &RULES_RESULT,
    exchanges: &[
        exchange(1, Answer::Reply, 0),
        exchange(2, Answer::Command(3), 2),
    ],
    handshake: None,
    watchdog: None,
    verdicts: &[Verdict {
        request: 2,
        at: ValueAt::Payload(WordField::le(0, 1)),
        accept: &[0],
        progress: &[5],
    }],
    ..BASE
};

/// An answer of command 3 to sequence number `seq` with result `value`, sealed.
fn result(seq: u8, value: u8) -> [u8; 5] {
    let mut f = [0xAA, seq, 3, value, 0];
    LAYOUT_RESULT.seal(&mut f).unwrap();
    f
}

#[test]
fn a_result_value_accepts_or_rejects_with_the_value() {
    let mut req = Requester::<_, 2, 5>::new(&RESULT);
    let ok = req.send(0, &mut [0xAA, 0, 2, 0, 0]).unwrap().unwrap();
    let no = req.send(0, &mut [0xAA, 0, 2, 0, 0]).unwrap().unwrap();
    assert_eq!(
        req.on_frame(1, &result(1, 4)),
        Received::Outcome(Outcome {
            ticket: no,
            resolution: Resolution::Rejected(4)
        })
    );
    assert_eq!(
        req.on_frame(2, &result(0, 0)),
        Received::Outcome(Outcome {
            ticket: ok,
            resolution: Resolution::Answered
        })
    );
    assert_eq!(req.open(), 0);
    // A command without a result is answered by its answer whatever it holds.
    let mut reply = Requester::<_, 1, 5>::new(&RESULT);
    let t = reply.send(0, &mut [0xAA, 0, 1, 9, 0]).unwrap().unwrap();
    let mut back = [0xAA, 0, 1, 9, 0];
    LAYOUT_RESULT.seal(&mut back).unwrap();
    assert_eq!(
        reply.on_frame(1, &back),
        Received::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::Answered
        })
    );
}

#[test]
fn a_progress_value_keeps_the_request_waiting_without_retries() {
    let mut req = Requester::<_, 2, 5>::new(&RESULT);
    let t = req.send(0, &mut [0xAA, 0, 2, 0, 0]).unwrap().unwrap();
    assert_eq!(req.next_deadline(), Some(10));
    assert_eq!(
        req.on_frame(8, &result(0, 5)),
        Received::Progress {
            ticket: t,
            value: 5
        }
    );
    // The wait starts again at 8 and is not followed by a retry.
    assert_eq!((req.open(), req.next_deadline()), (1, Some(18)));
    assert_eq!(req.poll(17), None);
    assert_eq!(
        req.poll(18),
        Some(Due::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::TimedOut
        }))
    );
    // Progress, then the answer that ends it.
    let t = req.send(20, &mut [0xAA, 0, 2, 0, 0]).unwrap().unwrap();
    assert!(matches!(
        req.on_frame(21, &result(1, 5)),
        Received::Progress { .. }
    ));
    assert!(matches!(
        req.on_frame(25, &result(1, 5)),
        Received::Progress { .. }
    ));
    assert_eq!(
        req.on_frame(30, &result(1, 0)),
        Received::Outcome(Outcome {
            ticket: t,
            resolution: Resolution::Answered
        })
    );
    assert_eq!(req.on_frame(31, &result(1, 0)), Received::Unsolicited);
}

/// Command 4 every 100 ms from the requester, command 3 every 30 ms from both sides.
static PERIODIC: SessionRules<'static> = SessionRules {
    periodic: &[
        Periodic {
            key: 4,
            period: 100,
            sender: Sender::Requester,
        },
        Periodic {
            key: 3,
            period: 30,
            sender: Sender::Both,
        },
    ],
    ..BASE
};

/// The keys `poll` returns at each millisecond of `0..until`, with their instants.
fn sent<const N: usize>(
    s: &mut Scheduler<&'static SessionRules<'static>, N>,
    until: u64,
) -> std::vec::Vec<(u64, u64)> {
    let mut out = std::vec::Vec::new();
    for now in 0..until {
        while let Some(k) = s.poll(now) {
            out.push((now, k));
        }
    }
    out
}

#[test]
fn each_periodic_command_is_due_at_its_rate_on_its_side() {
    let mut host = Scheduler::<_, 2>::new(&PERIODIC, Sender::Requester, 0);
    let got = sent(&mut host, 201);
    let at =
        |key| -> std::vec::Vec<u64> { got.iter().filter(|g| g.1 == key).map(|g| g.0).collect() };
    assert_eq!(at(4), [0, 100, 200]);
    assert_eq!(at(3), [0, 30, 60, 90, 120, 150, 180]);
    let mut device = Scheduler::<_, 2>::new(&PERIODIC, Sender::Responder, 0);
    assert!(sent(&mut device, 201).iter().all(|g| g.1 == 3));
    // A table smaller than the spec's list schedules its first commands alone.
    let mut one = Scheduler::<_, 1>::new(&PERIODIC, Sender::Responder, 0);
    assert_eq!((one.poll(0), one.next_deadline()), (None, None));
}

#[test]
fn a_late_poll_keeps_the_rate_and_a_long_gap_sends_once() {
    let mut s = Scheduler::<_, 2>::new(&PERIODIC, Sender::Responder, 10);
    assert_eq!(s.poll(9), None);
    assert_eq!(s.poll(10), Some(3));
    // 5 ms late: the next is still due 30 ms after the last due instant.
    assert_eq!(s.poll(45), Some(3));
    assert_eq!(s.next_deadline(), Some(70));
    // Asleep for 200 ms: one frame, then the rate resumes from now.
    assert_eq!((s.poll(270), s.poll(270)), (Some(3), None));
    assert_eq!(s.next_deadline(), Some(300));
    // Sent by the application on its own: the next one a period later.
    s.sent(280, 3);
    assert_eq!(s.next_deadline(), Some(310));
}
