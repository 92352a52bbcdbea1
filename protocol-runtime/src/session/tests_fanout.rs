//! The requester and responder on requests answered once by each id they list, against
//! hand-written rules shaped as Dynamixel 2.0's: `AA id cmd len payload sum8`, where 0x55 (a
//! status) answers every request from the id it was sent to, 0xFE is the broadcast id that
//! expects no answer, 0x82 lists the ids that answer it (one byte each, after a two-byte
//! address) and 0x92 lists them in elements of three bytes (`id address length`).

#![allow(clippy::indexing_slicing, clippy::unwrap_used, clippy::panic)]

extern crate std;
use std::vec::Vec;

use super::*;
use crate::checksum::Checksum;
use crate::layout::{ByteOrder, Check, FrameLayout, LengthRule, Pos};

static LAYOUT: FrameLayout<'static> = FrameLayout {
    sync: &[0xAA],
    sync_set: &[],
    header_len: 4,
    min_len: 5,
    max_len: 32,
    length: LengthRule::Field {
        field: WordField::le(3, 1),
        adjust: 5,
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
static RULES: PacketRules<'static> = PacketRules {
    layout: &LAYOUT,
    header_len: 4,
    trailer_len: 1,
    max_payload: 27,
    key: &[WordField::le(2, 1)],
    ack: None,
    directions: &[],
    stuffing: None,
    truncate_zeros: false,
};
const ID: WordField = WordField::le(1, 1);
const STATUS: u64 = 0x55;
const fn expects_status(key: u64, retries: u8) -> Exchange {
    Exchange {
        key,
        answer: Answer::Command(STATUS),
        timeout: 10,
        retries,
        backoff: 1,
    }
}
static SESSION: SessionRules<'static> = SessionRules {
    packet: &RULES,
    default: expects_status(0, 0),
    exchanges: &[
        expects_status(0x82, 1),
        Exchange {
            answer: Answer::None,
            ..expects_status(STATUS, 0)
        },
    ],
    sequence: None,
    echo: &[ID],
    swap: None,
    pairs: &[],
    nack: None,
    refusals: &[],
    handshake: None,
    watchdog: None,
    modes: Some(Modes {
        field: ID,
        none: Some((0xFE, 0xFE)),
        once: None,
    }),
    verdicts: &[],
    periodic: &[],
    fanouts: &[
        Fanout {
            request: 0x82,
            first: 2,
            stride: 1,
            id: ID,
        },
        Fanout {
            request: 0x92,
            first: 0,
            stride: 3,
            id: ID,
        },
    ],
};

/// A sealed frame of `cmd` to or from `id`.
fn frame(id: u8, cmd: u8, payload: &[u8]) -> Vec<u8> {
    let mut f = std::vec![0xAA, id, cmd, u8::try_from(payload.len()).unwrap()];
    f.extend_from_slice(payload);
    f.push(0);
    LAYOUT.seal(&mut f).unwrap();
    f
}

/// A sync read of address 0x84 to the broadcast id, listing `ids`.
fn sync_read(ids: &[u8]) -> Vec<u8> {
    let mut payload = std::vec![0x84, 0x00];
    payload.extend_from_slice(ids);
    frame(0xFE, 0x82, &payload)
}

fn status(id: u8) -> Vec<u8> {
    frame(id, 0x55, &[0x00, 0x10, 0x20])
}

fn outcome(ticket: Ticket, resolution: Resolution) -> Received {
    Received::Outcome(Outcome { ticket, resolution })
}

#[test]
fn a_sync_read_resolves_when_every_listed_id_answered() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    let mut request = sync_read(&[3, 5, 7]);
    // Sent to the broadcast id, which otherwise expects nothing: the list says who answers.
    let t = req.send(0, &mut request).unwrap().unwrap();
    assert!(req.several(t));
    let partial = |id, waiting| Received::Partial {
        ticket: t,
        id,
        waiting,
    };
    assert_eq!(req.on_frame(1, &status(5)), partial(5, 2));
    assert_eq!(req.on_frame(2, &status(9)), Received::Unsolicited);
    assert_eq!(req.on_frame(3, &status(5)), Received::Unsolicited);
    assert_eq!(req.on_frame(4, &status(3)), partial(3, 1));
    // Each answer waits the wait anew: 4 + 10 ms.
    assert_eq!(req.next_deadline(), Some(14));
    assert_eq!(
        req.on_frame(13, &status(7)),
        outcome(t, Resolution::Answered)
    );
    assert_eq!(req.open(), 0);
    assert_eq!(req.on_frame(14, &status(7)), Received::Unsolicited);
}

#[test]
fn a_sync_read_sent_again_times_out_listing_the_ids_that_did_not_answer() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    let mut request = sync_read(&[1, 2, 200]);
    let t = req.send(0, &mut request).unwrap().unwrap();
    assert!(matches!(
        req.on_frame(1, &status(1)),
        Received::Partial { .. }
    ));
    // The whole request again: the requester does not rewrite its payload.
    let Some(Due::Resend { ticket, frame }) = req.poll(11) else {
        panic!("a retry is due")
    };
    assert_eq!((ticket, frame), (t, &request[..]));
    assert_eq!(req.on_frame(12, &status(1)), Received::Unsolicited);
    assert!(matches!(
        req.on_frame(13, &status(200)),
        Received::Partial { .. }
    ));
    let Some(Due::Outcome(o)) = req.poll(23) else {
        panic!("the request times out")
    };
    let mut missing = IdSet::EMPTY;
    missing.insert(2);
    assert_eq!(o.resolution, Resolution::Incomplete(missing));
    assert_eq!(missing.iter().collect::<Vec<_>>(), [2]);
    assert_eq!(req.open(), 0);
}

#[test]
fn a_sync_read_that_nobody_answers_times_out() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    let t = req.send(0, &mut sync_read(&[4])).unwrap().unwrap();
    assert!(matches!(req.poll(10), Some(Due::Resend { .. })));
    let Some(Due::Outcome(o)) = req.poll(20) else {
        panic!("the request times out")
    };
    assert_eq!((o.ticket, o.resolution), (t, Resolution::TimedOut));
}

#[test]
fn a_list_of_no_id_expects_nothing_and_a_single_id_resolves_at_once() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    assert_eq!(req.send(0, &mut sync_read(&[])), Ok(None));
    let t = req.send(0, &mut sync_read(&[9])).unwrap().unwrap();
    assert_eq!(
        req.on_frame(1, &status(9)),
        outcome(t, Resolution::Answered)
    );
}

#[test]
fn a_bulk_read_lists_its_ids_in_elements() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    // Servo 1: 2 bytes at 0x84; servo 0x0A: 4 bytes at 0x80 (an address byte equal to an id
    // that is not listed, 0x84, is not read as one).
    let payload = [0x01, 0x84, 0x02, 0x0A, 0x80, 0x04];
    let mut request = frame(0xFE, 0x92, &payload);
    let listed = SESSION.fanouts[1].listed(&RULES, &request).unwrap();
    assert_eq!(listed.iter().collect::<Vec<_>>(), [0x01, 0x0A]);
    let t = req.send(0, &mut request).unwrap().unwrap();
    assert_eq!(req.on_frame(1, &status(0x84)), Received::Unsolicited);
    assert!(matches!(
        req.on_frame(1, &status(0x0A)),
        Received::Partial { .. }
    ));
    assert_eq!(
        req.on_frame(2, &status(1)),
        outcome(t, Resolution::Answered)
    );
}

#[test]
fn a_read_of_one_servo_still_expects_one_status_and_a_broadcast_none() {
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    let t = req
        .send(0, &mut frame(3, 0x02, &[0x84, 0, 4, 0]))
        .unwrap()
        .unwrap();
    assert!(!req.several(t));
    assert_eq!(req.on_frame(1, &status(4)), Received::Unsolicited);
    assert_eq!(
        req.on_frame(2, &status(3)),
        outcome(t, Resolution::Answered)
    );
    assert_eq!(req.send(3, &mut frame(0xFE, 0x03, &[0x41, 0, 1])), Ok(None));
}

#[test]
fn each_responder_answers_a_sync_read_with_its_own_id() {
    let request = sync_read(&[3, 5]);
    let mut req = Requester::<_, 2, 32>::new(&SESSION);
    let t = req.send(0, &mut request.clone()).unwrap().unwrap();
    for (id, heard) in [(3u8, false), (5, true)] {
        let mut servo = Responder::<_, 2, 32>::new(&SESSION);
        assert_eq!(
            servo.on_frame(0, &request),
            Incoming::Deliver { answer: true }
        );
        let mut answer = status(id);
        servo.answer(&request, &mut answer).unwrap();
        // The answer keeps the servo's id, not the request's broadcast id.
        assert_eq!(answer, status(id));
        let got = req.on_frame(1, &answer);
        assert_eq!(got == outcome(t, Resolution::Answered), heard);
    }
}

#[test]
fn an_id_set_holds_every_byte() {
    let mut set = IdSet::EMPTY;
    for id in [0u8, 63, 64, 127, 128, 255] {
        set.insert(id);
    }
    assert_eq!(set.len(), 6);
    assert!(set.contains(255) && !set.contains(1));
    assert!(set.remove(64) && !set.remove(64));
    assert_eq!(set.iter().collect::<Vec<_>>(), [0, 63, 127, 128, 255]);
    assert!(!set.is_empty() && IdSet::EMPTY.is_empty());
}

/// These rules as generated code hands them out, sized for rules that list no command of
/// several answers: wrongly, since these do.
#[derive(Clone, Copy)]
struct Unlisted;

impl SessionRef for Unlisted {
    type Awaiting = NoFanout;
    fn session(&self) -> &SessionRules<'_> {
        &SESSION
    }
}

#[test]
fn a_requester_without_id_sets_keeps_none_in_its_slots() {
    use core::mem::size_of;
    assert_eq!(size_of::<Option<NoFanout>>(), 0);
    let with = size_of::<Requester<&SessionRules<'static>, 4, 32>>();
    let without = size_of::<Requester<Unlisted, 4, 32>>();
    // Each slot saves at least the 32-byte id set.
    assert!(with >= without + 4 * size_of::<IdSet>(), "{with} {without}");
}

#[test]
fn a_requester_without_id_sets_refuses_a_request_of_several_answers() {
    let mut req = Requester::<_, 2, 32>::new(Unlisted);
    let mut request = sync_read(&[3, 5]);
    let before = request.clone();
    assert_eq!(req.send(0, &mut request), Err(SendError::Several));
    assert_eq!((request, req.open()), (before, 0));
    // Its requests of one answer are as any requester's.
    let t = req
        .send(1, &mut frame(3, 0x02, &[0x84, 0, 4, 0]))
        .unwrap()
        .unwrap();
    assert_eq!(
        req.on_frame(2, &status(3)),
        outcome(t, Resolution::Answered)
    );
}

#[test]
fn an_observer_of_rules_without_id_sets_keeps_none_and_pairs_as_any_observer() {
    use core::mem::size_of;
    let with = size_of::<Observer<4>>();
    let without = size_of::<Observer<4, NoFanout>>();
    // Each open request saves at least the 32-byte id set.
    assert!(with >= without + 4 * size_of::<IdSet>(), "{with} {without}");
    // A READ and its status, a READ left unanswered: as the observer with id sets has them.
    let read = frame(3, 0x02, &[0x84, 0, 4, 0]);
    let mut lean = Observer::<4, NoFanout>::new();
    let mut full = Observer::<4>::new();
    assert!(lean.request(Unlisted, 0, Some(0), &read));
    assert!(full.request(&SESSION, 0, Some(0), &read));
    let paired = Some(Paired {
        request: 0,
        round_trip: Some(3),
        open: false,
        refused: false,
    });
    assert_eq!(lean.answer(Unlisted, Some(3), &status(3)), paired);
    assert_eq!(full.answer(&SESSION, Some(3), &status(3)), paired);
    assert!(lean.request(Unlisted, 2, Some(10), &read));
    assert!(full.request(&SESSION, 2, Some(10), &read));
    assert_eq!((lean.answered(), lean.finish()), (1, 1));
    assert_eq!((full.answered(), full.finish()), (1, 1));
}

#[test]
fn a_status_that_could_answer_two_open_requests_is_refused_at_send() {
    let mut req = Requester::<_, 4, 32>::new(&SESSION);
    let read3 = req
        .send(0, &mut frame(3, 0x02, &[0x84, 0, 4, 0]))
        .unwrap()
        .unwrap();
    // A status from 3 could answer the READ or a SYNC_READ listing 3: the second waits.
    let mut listing3 = sync_read(&[5, 3]);
    let before = listing3.clone();
    assert_eq!(req.send(1, &mut listing3), Err(SendError::Ambiguous));
    assert_eq!((listing3, req.open()), (before, 1));
    // So could a PING of 3 (its answer is a status too), and a BULK_READ listing 3.
    assert_eq!(
        req.send(1, &mut frame(3, 0x01, &[])),
        Err(SendError::Ambiguous)
    );
    let bulk3 = [0x07, 0x84, 0x02, 0x03, 0x80, 0x04];
    assert_eq!(
        req.send(1, &mut frame(0xFE, 0x92, &bulk3)),
        Err(SendError::Ambiguous)
    );
    // Servos 4 and 5 are not 3: a SYNC_READ of them is told apart by the sender's id.
    let sync = req.send(2, &mut sync_read(&[4, 5])).unwrap().unwrap();
    // Now a READ of 5, and a BULK_READ listing 4, could share a status with the SYNC_READ.
    assert_eq!(
        req.send(3, &mut frame(5, 0x02, &[0x84, 0, 4, 0])),
        Err(SendError::Ambiguous)
    );
    let bulk4 = [0x04, 0x84, 0x02, 0x09, 0x80, 0x04];
    assert_eq!(
        req.send(3, &mut frame(0xFE, 0x92, &bulk4)),
        Err(SendError::Ambiguous)
    );
    // Once 5 has answered, the SYNC_READ waits for 4 alone: a READ of 5 is told apart.
    assert!(matches!(
        req.on_frame(4, &status(5)),
        Received::Partial { id: 5, .. }
    ));
    let read5 = req
        .send(5, &mut frame(5, 0x02, &[0x84, 0, 4, 0]))
        .unwrap()
        .unwrap();
    // Each status resolves the one request it can answer.
    assert_eq!(
        req.on_frame(6, &status(5)),
        outcome(read5, Resolution::Answered)
    );
    assert_eq!(
        req.on_frame(6, &status(3)),
        outcome(read3, Resolution::Answered)
    );
    assert_eq!(
        req.on_frame(7, &status(4)),
        outcome(sync, Resolution::Answered)
    );
    // With the READ of 3 resolved, the SYNC_READ listing 3 goes out.
    assert!(req.send(8, &mut sync_read(&[5, 3])).unwrap().is_some());
}

#[test]
fn id_sets_meet_when_they_share_an_id() {
    let (mut a, mut b) = (IdSet::EMPTY, IdSet::EMPTY);
    a.insert(3);
    a.insert(200);
    b.insert(4);
    assert!(!a.meets(&b) && !IdSet::EMPTY.meets(&a));
    b.insert(200);
    assert!(a.meets(&b) && b.meets(&a));
}
