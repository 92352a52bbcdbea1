//! MAVLink's command protocol as its spec declares it: a COMMAND_LONG expects the COMMAND_ACK
//! of the same `command`, from the system and component it targets, addressed back to its
//! sender (a `match` of request fields against answer fields of other names, in the header and
//! the payload), sent again up to three times. The requester resolves each COMMAND_LONG to its
//! COMMAND_ACK alone, and over a lossy link (the session simulation's) to exactly one outcome
//! within its retries. The ACK's `result` decides that outcome: 0 (ACCEPTED) answers the
//! command, 5 (IN_PROGRESS) makes it wait again without being sent again, any other value
//! refuses it with the value.

use crate::session_sim::{link, sim};
use link::Fault;
use proptest::prelude::*;
use protocol_kit::session::{Outcome, Received, Resolution};
use sim::{Peer, Tally, run};

protocol_kit::protocol!("../specs/mavlink.toml");

use mavlink::{CommandAck, CommandLong, Header, Message, Packet};

/// The ground station.
const GCS: (u8, u8) = (255, 190);
/// The autopilot.
const AUTOPILOT: (u8, u8) = (1, 1);

fn encode(packet: &Packet) -> Vec<u8> {
    let mut buf = vec![0u8; mavlink::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

fn header((sysid, compid): (u8, u8)) -> Header {
    Header {
        sysid,
        compid,
        ..Header::default()
    }
}

fn command_long(command: u16) -> Vec<u8> {
    encode(&Packet {
        header: header(GCS),
        message: Message::CommandLong(CommandLong {
            param1: 1.0,
            param2: 0.0,
            param3: 0.0,
            param4: 0.0,
            param5: 0.0,
            param6: 0.0,
            param7: 0.0,
            command,
            target_system: AUTOPILOT.0,
            target_component: AUTOPILOT.1,
            confirmation: 0,
        }),
    })
}

/// A COMMAND_ACK of `command` from `from` to `to`, accepted.
fn command_ack(command: u16, from: (u8, u8), to: (u8, u8)) -> Vec<u8> {
    command_result(command, 0, from, to)
}

/// A COMMAND_ACK of `command` from `from` to `to` with `result` (MAV_RESULT).
fn command_result(command: u16, result: u8, from: (u8, u8), to: (u8, u8)) -> Vec<u8> {
    encode(&Packet {
        header: header(from),
        message: Message::CommandAck(CommandAck {
            command,
            result,
            progress: 0,
            result_param2: 0,
            target_system: to.0,
            target_component: to.1,
        }),
    })
}

/// Two commands open at once: each ACK resolves its own, and an ACK that differs from the
/// request in any matched value resolves none.
#[test]
fn command_long_resolves_to_its_command_ack() {
    let mut requester = mavlink::Requester::<4, 64>::new(mavlink::Session);
    let arm = requester
        .send(0, &mut command_long(400))
        .expect("sent")
        .expect("expects an ACK");
    let takeoff = requester
        .send(0, &mut command_long(22))
        .expect("sent")
        .expect("expects an ACK");
    // A second open request of the same command to the same target could not be told apart.
    assert!(requester.send(0, &mut command_long(22)).is_err());
    let unsolicited = [
        command_ack(21, AUTOPILOT, GCS),        // another command
        command_ack(22, (2, 1), GCS),           // from another system
        command_ack(22, (1, 2), GCS),           // from another component
        command_ack(22, AUTOPILOT, (255, 1)),   // to another component
        command_ack(22, AUTOPILOT, (254, 190)), // to another system
    ];
    for ack in &unsolicited {
        assert_eq!(
            requester.on_frame(1, ack),
            Received::Unsolicited,
            "{ack:02x?}"
        );
    }
    assert_eq!(
        requester.on_frame(2, &command_ack(22, AUTOPILOT, GCS)),
        Received::Outcome(Outcome {
            ticket: takeoff,
            resolution: Resolution::Answered
        })
    );
    assert_eq!(
        requester.on_frame(3, &command_ack(400, AUTOPILOT, GCS)),
        Received::Outcome(Outcome {
            ticket: arm,
            resolution: Resolution::Answered
        })
    );
    // A heartbeat expects nothing.
    let mut heartbeat = encode(&Packet {
        header: header(GCS),
        message: Message::Heartbeat(mavlink::Heartbeat::default()),
    });
    assert_eq!(requester.send(4, &mut heartbeat), Ok(None));
}

/// The ground station (requester) and the autopilot (responder).
struct Mavlink;

impl Peer for Mavlink {
    type Session = mavlink::Session;
    fn session() -> mavlink::Session {
        mavlink::Session
    }

    fn request(kind: u8, _mode: u8) -> Vec<u8> {
        // Three commands (arm, take off, land) and a heartbeat, which expects nothing.
        match kind % 4 {
            0 => command_long(400),
            1 => command_long(22),
            2 => command_long(21),
            _ => encode(&Packet {
                header: header(GCS),
                message: Message::Heartbeat(mavlink::Heartbeat::default()),
            }),
        }
    }

    fn handshake() -> Option<Vec<u8>> {
        None
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        let Ok(Packet {
            header,
            message: Message::CommandLong(c),
        }) = Packet::from_frame(request)
        else {
            panic!("only COMMAND_LONG expects an answer");
        };
        command_ack(
            c.command,
            (c.target_system, c.target_component),
            (header.sysid, header.compid),
        )
    }

    fn decodes(frame: &[u8]) -> bool {
        mavlink::LAYOUT
            .parse(frame)
            .is_ok_and(|f| f.len() == frame.len())
            && Packet::from_frame(frame).is_ok()
    }
}

fn check(t: &Tally) {
    assert_eq!(
        t.outcome_errors, 0,
        "a request without exactly one outcome: {t:?}"
    );
    assert_eq!(
        t.requests,
        t.answered + t.refused + t.rejected_by_value + t.timed_out,
        "{t:?}"
    );
    assert_eq!(
        t.over_retried, 0,
        "a request sent beyond its retries: {t:?}"
    );
    assert_eq!(
        t.resent_after_progress, 0,
        "a command sent again after it was in progress: {t:?}"
    );
    assert_eq!(t.refused, 0, "MAVLink's session has no NACK command: {t:?}");
    assert_eq!(t.allocations, 0, "the machines allocated: {t:?}");
    assert!(t.max_open <= sim::SLOTS, "{t:?}");
}

#[test]
fn a_clean_link_acknowledges_every_command() {
    let plan: Vec<(u64, u8, u8)> = (0..24).map(|i| (400, i, 0)).collect();
    let t = run::<Mavlink>(&plan, Vec::new());
    check(&t);
    assert_eq!((t.requests, t.fire_and_forget), (18, 6), "{t:?}");
    assert_eq!((t.answered, t.resends, t.timed_out), (18, 0, 0), "{t:?}");
}

#[test]
fn a_lossy_link_is_retried_until_each_command_is_acknowledged() {
    // One frame in three lost, starting with the first: each command's first send is lost,
    // its retry and the ACK get through.
    let schedule: Vec<Fault> = (0..400)
        .map(|i| {
            if i % 3 == 0 {
                Fault::Drop
            } else {
                Fault::Pass(5)
            }
        })
        .collect();
    let plan: Vec<(u64, u8, u8)> = (0..12).map(|i| (3000, i % 3, 0)).collect();
    let t = run::<Mavlink>(&plan, schedule);
    check(&t);
    assert_eq!(t.requests, 12, "{t:?}");
    assert_eq!(t.answered, 12, "{t:?}");
    assert_eq!(t.resends, 12, "each command needed one retry: {t:?}");
}

#[test]
fn a_dead_link_times_every_command_out_after_three_retries() {
    let plan: Vec<(u64, u8, u8)> = (0..3).map(|i| (1, i, 0)).collect();
    let t = run::<Mavlink>(&plan, vec![Fault::Drop; 1000]);
    check(&t);
    assert_eq!((t.timed_out, t.resends), (3, 9), "{t:?}");
}

fn fault() -> impl Strategy<Value = Fault> {
    prop_oneof![
        6 => (1u64..300).prop_map(Fault::Pass),
        2 => Just(Fault::Drop),
        1 => (1u64..300, 1u64..600).prop_map(|(a, b)| Fault::Twice(a, b)),
        1 => (1u64..30, 0usize..48, 1u8..0xFF).prop_map(|(d, at, m)| Fault::Corrupt(d, at, m)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn commands_resolve_once_under_faults(
        plan in prop::collection::vec((0u64..1500, any::<u8>(), any::<u8>()), 1..16),
        schedule in prop::collection::vec(fault(), 0..120),
    ) {
        let t = run::<Mavlink>(&plan, schedule);
        check(&t);
    }
}

/// MAV_RESULT values the autopilot answers with.
const ACCEPTED: u8 = 0;
const FAILED: u8 = 4;
const IN_PROGRESS: u8 = 5;

/// The ACK's result decides: accepted answers, a refusal carries its value (even one the spec
/// does not name), in progress keeps the command open.
#[test]
fn the_ack_result_answers_refuses_or_extends_the_wait() {
    let mut requester = mavlink::Requester::<4, 64>::new(mavlink::Session);
    let arm = requester
        .send(0, &mut command_long(400))
        .expect("sent")
        .expect("expects an ACK");
    let land = requester
        .send(0, &mut command_long(21))
        .expect("sent")
        .expect("expects an ACK");
    let takeoff = requester
        .send(0, &mut command_long(22))
        .expect("sent")
        .expect("expects an ACK");
    let ack = |command, result| command_result(command, result, AUTOPILOT, GCS);
    assert_eq!(
        requester.on_frame(10, &ack(21, FAILED)),
        Received::Outcome(Outcome {
            ticket: land,
            resolution: Resolution::Rejected(u64::from(FAILED))
        })
    );
    // A value newer than the spec's list is a refusal, never a success.
    assert_eq!(
        requester.on_frame(11, &ack(400, 200)),
        Received::Outcome(Outcome {
            ticket: arm,
            resolution: Resolution::Rejected(200)
        })
    );
    // In progress at 900 ms: no retry at 1000 ms, the wait runs to 1900 ms.
    assert_eq!(
        requester.on_frame(900, &ack(22, IN_PROGRESS)),
        Received::Progress {
            ticket: takeoff,
            value: u64::from(IN_PROGRESS)
        }
    );
    assert_eq!(requester.next_deadline(), Some(1900));
    assert_eq!(requester.poll(1000), None);
    assert_eq!(
        requester.on_frame(1500, &ack(22, ACCEPTED)),
        Received::Outcome(Outcome {
            ticket: takeoff,
            resolution: Resolution::Answered
        })
    );
    assert_eq!(requester.open(), 0);
}

/// The autopilot answering as a real one does: arm accepted, take off in progress then
/// accepted, land failed.
pub(crate) struct MavlinkResults;

impl Peer for MavlinkResults {
    type Session = mavlink::Session;
    fn session() -> mavlink::Session {
        mavlink::Session
    }

    fn request(kind: u8, mode: u8) -> Vec<u8> {
        Mavlink::request(kind, mode)
    }

    fn handshake() -> Option<Vec<u8>> {
        None
    }

    fn progress(request: &[u8]) -> Option<Vec<u8>> {
        let (header, c) = command_of(request);
        (c.command == 22).then(|| {
            command_result(
                c.command,
                IN_PROGRESS,
                (c.target_system, c.target_component),
                (header.sysid, header.compid),
            )
        })
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        let (header, c) = command_of(request);
        let result = if c.command == 21 { FAILED } else { ACCEPTED };
        command_result(
            c.command,
            result,
            (c.target_system, c.target_component),
            (header.sysid, header.compid),
        )
    }

    fn decodes(frame: &[u8]) -> bool {
        Mavlink::decodes(frame)
    }
}

fn command_of(request: &[u8]) -> (Header, CommandLong) {
    match Packet::from_frame(request) {
        Ok(Packet {
            header,
            message: Message::CommandLong(c),
        }) => (header, c),
        other => panic!("only COMMAND_LONG expects an answer: {other:?}"),
    }
}

#[test]
fn a_clean_link_resolves_each_command_by_its_result() {
    let plan: Vec<(u64, u8, u8)> = (0..24).map(|i| (400, i, 0)).collect();
    let t = run::<MavlinkResults>(&plan, Vec::new());
    check(&t);
    // Six each of arm, take off, land and heartbeat.
    assert_eq!((t.requests, t.fire_and_forget), (18, 6), "{t:?}");
    assert_eq!(
        (t.answered, t.rejected_by_value, t.progress, t.timed_out),
        (12, 6, 6, 0),
        "{t:?}"
    );
}

#[test]
fn a_command_in_progress_whose_final_ack_is_lost_times_out_unsent() {
    // The command reaches the autopilot, the IN_PROGRESS gets back, the final ACK is lost.
    let schedule = vec![Fault::Pass(5), Fault::Pass(5), Fault::Drop];
    let t = run::<MavlinkResults>(&[(1, 1, 0)], schedule);
    check(&t);
    assert_eq!(
        (t.requests, t.progress, t.timed_out, t.resends),
        (1, 1, 1, 0),
        "{t:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn results_resolve_once_under_faults(
        plan in prop::collection::vec((0u64..1500, any::<u8>(), any::<u8>()), 1..16),
        schedule in prop::collection::vec(fault(), 0..120),
    ) {
        let t = run::<MavlinkResults>(&plan, schedule);
        check(&t);
    }
}
