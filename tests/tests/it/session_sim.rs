//! The session machines under faults: a host and a device hold the conversation their spec
//! declares (RoboRTS: acknowledgements, session modes, sequence numbers; HFLink: a handshake,
//! replies matched by command and addresses) over a simulated link that drops, duplicates,
//! corrupts, delays and reorders frames, on a simulated clock. Property tests draw the fault
//! schedules; every run must resolve each request to exactly one outcome, never deliver a
//! numbered request twice, never send a request more than 1 + its retries times, hold at most
//! its slots open, deliver nothing before the handshake, and allocate nothing in the machines.
//!
//! Dynamixel's SYNC_READ and BULK_READ are answered by each servo they list: every answer but
//! the last leaves the request open (`Partial`), a request some servos missed resolves to
//! `Incomplete`, no servo's answer reaches the application twice, none from a servo the
//! request does not list, and a request one status could answer as well as an open one waits
//! (`SendError::Ambiguous`).
//!
//! MSP's flight controller refuses the requests it does not serve with the error reply of
//! their command (`!`, a frame of the spec's empty direction): each such request resolves once,
//! as refused, and a clean link refuses exactly those.
//!
//! `cargo test -p protocol-tests --test it -- --nocapture session_sim::fault_matrix` prints the
//! counts of a fixed matrix of schedules, MAVLink's commands among them (answered, refused by
//! their ACK's `result`, or kept waiting by an ACK that says they are in progress),
//! Dynamixel's reads of several servos and MSP's error replies (the `nack` column).

#[path = "session_sim/dynamixel.rs"]
pub(crate) mod dynamixel;
#[path = "session_sim/link.rs"]
pub(crate) mod link;
#[path = "session_sim/msp.rs"]
pub(crate) mod msp;
#[path = "session_sim/sim.rs"]
pub(crate) mod sim;

use crate::session_mavlink::MavlinkResults;
use dynamixel::Dynamixel;
use link::Fault;
use msp::Msp;
use proptest::prelude::*;
use sim::{Peer, SLOTS, Tally, run};

protocol_kit::protocol!("../specs/roborts.toml");
protocol_kit::protocol!("../specs/hflink.toml");

fn encode(
    n: usize,
    encode: impl FnOnce(&mut [u8]) -> Result<usize, protocol_kit::EncodeError>,
) -> Vec<u8> {
    let mut buf = vec![0u8; n];
    let len = encode(&mut buf).expect("encodes");
    buf.truncate(len);
    buf
}

/// The RoboRTS manifold (requester, address 0) and chassis (responder, address 1).
struct Roborts;

impl Peer for Roborts {
    type Session = roborts::Session;
    fn session() -> roborts::Session {
        roborts::Session
    }

    fn request(kind: u8, mode: u8) -> Vec<u8> {
        use roborts::*;
        let message = match kind % 2 {
            0 => Message::Heartbeat(Heartbeat { heartbeat: 7 }),
            _ => Message::SetChassisSpeed(ChassisSpeed {
                vx: 100,
                vy: -5,
                vw: 3,
                rotate_x_offset: 0,
                rotate_y_offset: 0,
            }),
        };
        let packet = Packet {
            header: Header {
                session_id: mode % 32,
                sender: 0,
                receiver: 1,
                seq_num: 0,
            },
            message,
        };
        encode(MAX_FRAME_LEN, |b| packet.encode(b))
    }

    fn handshake() -> Option<Vec<u8>> {
        None
    }

    fn answer(_request: &[u8]) -> Vec<u8> {
        use roborts::*;
        let ack = Packet {
            header: Header {
                session_id: 0,
                sender: 1,
                receiver: 0,
                seq_num: 0,
            },
            message: Message::Ack(protocol_kit::Bytes::from_slice(&[]).expect("empty")),
        };
        encode(MAX_FRAME_LEN, |b| ack.encode(b))
    }

    fn decodes(frame: &[u8]) -> bool {
        roborts::LAYOUT
            .parse(frame)
            .is_ok_and(|f| f.len() == frame.len())
            && roborts::Packet::from_frame(frame).is_ok()
    }
}

/// The HFLink master (requester, 0x01) and slave (responder, 0x11).
struct Hflink;

impl Peer for Hflink {
    type Session = hflink::Session;
    fn session() -> hflink::Session {
        hflink::Session
    }

    fn request(kind: u8, _mode: u8) -> Vec<u8> {
        use hflink::*;
        let coord = ChassisCoord {
            x: 0.5,
            y: 0.0,
            z: 0.1,
        };
        let request = match kind % 3 {
            0 => Request::ReadRobotSpeed,
            1 => Request::SetRobotSpeed(coord),
            _ => Request::ClearCoordinateData,
        };
        let packet = Packet {
            header: Header {
                sender: 0x01,
                receiver: 0x11,
            },
            message: Message::Request(request),
        };
        encode(MAX_FRAME_LEN, |b| packet.encode(b))
    }

    fn handshake() -> Option<Vec<u8>> {
        use hflink::*;
        let packet = Packet {
            header: Header {
                sender: 0x01,
                receiver: 0x11,
            },
            message: Message::Request(Request::ShakingHands(ChassisCoord {
                x: 0.0,
                y: 0.0,
                z: 0.0,
            })),
        };
        Some(encode(MAX_FRAME_LEN, |b| packet.encode(b)))
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        use hflink::*;
        let Ok(Packet {
            message: Message::Request(r),
            ..
        }) = Packet::from_frame(request)
        else {
            panic!("the responder delivers requests");
        };
        let response = match r {
            Request::ShakingHands(_) => Response::ShakingHands,
            Request::ReadRobotSpeed => Response::ReadRobotSpeed(ChassisCoord {
                x: 1.0,
                y: 2.0,
                z: 3.0,
            }),
            Request::SetRobotSpeed(_) => Response::SetRobotSpeed,
            Request::ClearCoordinateData => Response::ClearCoordinateData,
            other => panic!("not a request of the plan: {other:?}"),
        };
        let packet = Packet {
            header: Header {
                sender: 0x11,
                receiver: 0x01,
            },
            message: Message::Response(response),
        };
        encode(MAX_FRAME_LEN, |b| packet.encode(b))
    }

    fn decodes(frame: &[u8]) -> bool {
        hflink::LAYOUT
            .parse(frame)
            .is_ok_and(|f| f.len() == frame.len())
            && hflink::Packet::from_frame(frame).is_ok()
    }
}

/// The invariants every run holds, whatever the faults.
fn check(name: &str, t: &Tally) {
    assert_eq!(
        t.outcome_errors, 0,
        "{name}: a request without exactly one outcome: {t:?}"
    );
    assert_eq!(
        t.requests,
        t.answered + t.refused + t.rejected_by_value + t.timed_out + t.incomplete,
        "{name}: {t:?}"
    );
    assert_eq!(
        (t.answers_twice, t.unlisted),
        (0, 0),
        "{name}: an answer of several handed over twice, or from a device not listed: {t:?}"
    );
    assert_eq!(
        t.resent_after_progress, 0,
        "{name}: a request sent again after it was in progress: {t:?}"
    );
    assert_eq!(
        t.mismatched, 0,
        "{name}: an answer matched to another request: {t:?}"
    );
    assert_eq!(
        t.over_retried, 0,
        "{name}: a request sent beyond its retries: {t:?}"
    );
    assert_eq!(
        t.before_handshake, 0,
        "{name}: a request delivered before the handshake: {t:?}"
    );
    assert_eq!(t.allocations, 0, "{name}: the machines allocated: {t:?}");
    assert!(t.max_open <= SLOTS, "{name}: {t:?}");
}

fn fault() -> impl Strategy<Value = Fault> {
    prop_oneof![
        6 => (1u64..30).prop_map(Fault::Pass),
        2 => Just(Fault::Drop),
        1 => (1u64..30, 1u64..60).prop_map(|(a, b)| Fault::Twice(a, b)),
        1 => (1u64..30, 0usize..64, 1u8..0xFF).prop_map(|(d, at, m)| Fault::Corrupt(d, at, m)),
    ]
}

fn plan() -> impl Strategy<Value = Vec<(u64, u8, u8)>> {
    prop::collection::vec((0u64..40, any::<u8>(), any::<u8>()), 1..24)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn roborts_holds_its_sessions_under_faults(
        plan in plan(),
        schedule in prop::collection::vec(fault(), 0..200),
    ) {
        let t = run::<Roborts>(&plan, schedule);
        check("roborts", &t);
        // RoboRTS numbers its frames: no request reaches the chassis twice.
        prop_assert_eq!(t.duplicates_delivered, 0, "{:?}", t);
    }

    #[test]
    fn dynamixel_reads_of_several_servos_resolve_once_under_faults(
        plan in plan(),
        schedule in prop::collection::vec(fault(), 0..200),
    ) {
        let t = run::<Dynamixel>(&plan, schedule);
        check("dynamixel", &t);
    }

    #[test]
    fn hflink_holds_its_handshake_and_replies_under_faults(
        plan in plan(),
        schedule in prop::collection::vec(fault(), 0..200),
    ) {
        let t = run::<Hflink>(&plan, schedule);
        check("hflink", &t);
    }
}

/// A clean link answers everything: the machines are not merely surviving faults.
#[test]
fn a_clean_link_answers_every_request() {
    let plan: Vec<(u64, u8, u8)> = (0..20).map(|i| (3, i, 2 + i % 30)).collect();
    for (name, t) in [
        ("roborts", run::<Roborts>(&plan, Vec::new())),
        ("hflink", run::<Hflink>(&plan, Vec::new())),
        ("dynamixel", run::<Dynamixel>(&plan, Vec::new())),
    ] {
        check(name, &t);
        assert_eq!(
            (t.timed_out, t.resends, t.refused),
            (0, 0, 0),
            "{name}: {t:?}"
        );
        assert!(
            t.requests >= 20 && t.answered == t.requests,
            "{name}: {t:?}"
        );
    }
    // RoboRTS session 0 expects no acknowledgement: such a request holds no ticket.
    let t = run::<Roborts>(&[(1, 0, 0), (1, 1, 0), (1, 0, 5)], Vec::new());
    assert_eq!(
        (t.fire_and_forget, t.requests, t.answered),
        (2, 1, 1),
        "{t:?}"
    );
}

/// MSP on a clean link: the flight controller answers API_VERSION and ATTITUDE and refuses
/// STATUS and UID with their error replies; every request resolves once, as the one or the
/// other, and none is sent again.
#[test]
fn a_clean_msp_link_refuses_exactly_the_requests_its_controller_refuses() {
    let plan: Vec<(u64, u8, u8)> = (0..20).map(|i| (3, i, 0)).collect();
    let t = run::<Msp>(&plan, Vec::new());
    check("msp", &t);
    assert_eq!(
        (t.requests, t.answered, t.refused, t.timed_out, t.resends),
        (20, 10, 10, 0, 0),
        "{t:?}"
    );
}

/// A link that loses everything: each request times out once, after exactly its retries.
#[test]
fn a_dead_link_times_every_request_out_after_its_retries() {
    let plan: Vec<(u64, u8, u8)> = (0..6).map(|i| (1, i, 5)).collect();
    let t = run::<Roborts>(&plan, vec![Fault::Drop; 1000]);
    check("roborts", &t);
    let retries = u64::from(roborts::SESSION.default.retries);
    assert_eq!((t.timed_out, t.resends), (6, 6 * retries), "{t:?}");
}

/// A small deterministic generator for the matrix (the property tests draw their own).
struct Mix(u64);

impl Mix {
    fn next(&mut self, n: u64) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        (z ^ (z >> 31)) % n
    }

    fn schedule(&mut self, loss: u64) -> Vec<Fault> {
        (0..400)
            .map(|_| match self.next(100) {
                r if r < loss => Fault::Drop,
                r if r < loss + 5 => Fault::Twice(1 + self.next(20), 1 + self.next(60)),
                r if r < loss + 10 => Fault::Corrupt(
                    1 + self.next(20),
                    self.next(64) as usize,
                    1 + self.next(0xFE) as u8,
                ),
                _ => Fault::Pass(1 + self.next(30)),
            })
            .collect()
    }

    fn plan(&mut self) -> Vec<(u64, u8, u8)> {
        (0..20)
            .map(|_| (self.next(40), self.next(256) as u8, self.next(256) as u8))
            .collect()
    }
}

/// The fault matrix: 100 schedules per loss rate and spec, the invariants checked on each and
/// the totals printed, with the machines' fixed sizes.
#[test]
fn fault_matrix() {
    use protocol_kit::session::{Requester, Responder};
    println!(
        "machines ({SLOTS} slots of {} bytes): requester {} bytes, responder {} bytes",
        sim::FRAME,
        std::mem::size_of::<Requester<roborts::Session, SLOTS, { sim::FRAME }>>(),
        std::mem::size_of::<Responder<roborts::Session, SLOTS, { sim::FRAME }>>()
    );
    println!(
        "{:<9} {:>5} {:>7} {:>6} {:>6} {:>9} {:>6} {:>8} {:>7} {:>10} {:>6} {:>6} {:>6} {:>7} {:>6} {:>7} {:>7} {:>6}",
        "spec",
        "loss%",
        "frames",
        "drop",
        "dup",
        "corrupt",
        "reqs",
        "answered",
        "partial",
        "incomplete",
        "nack",
        "result",
        "inprog",
        "timeout",
        "resend",
        "deliv",
        "dupdel",
        "alloc"
    );
    for loss in [0u64, 10, 30] {
        for name in ["roborts", "hflink", "mavlink", "dynamixel", "msp"] {
            let mut mix = Mix(loss * 1000 + name.len() as u64);
            let mut total = Tally::default();
            for _ in 0..100 {
                let (plan, schedule) = (mix.plan(), mix.schedule(loss));
                let t = match name {
                    "roborts" => run::<Roborts>(&plan, schedule),
                    "hflink" => run::<Hflink>(&plan, schedule),
                    "dynamixel" => run::<Dynamixel>(&plan, schedule),
                    "msp" => run::<Msp>(&plan, schedule),
                    _ => run::<MavlinkResults>(&plan, schedule),
                };
                check(name, &t);
                if name == "roborts" {
                    assert_eq!(t.duplicates_delivered, 0, "{t:?}");
                }
                add(&mut total, &t);
            }
            let f = total.faults;
            println!(
                "{:<9} {:>5} {:>7} {:>6} {:>6} {:>9} {:>6} {:>8} {:>7} {:>10} {:>6} {:>6} {:>6} {:>7} {:>6} {:>7} {:>7} {:>6}",
                name,
                loss,
                f.frames,
                f.dropped,
                f.duplicated,
                f.corrupted,
                total.requests,
                total.answered,
                total.partial,
                total.incomplete,
                total.refused,
                total.rejected_by_value,
                total.progress,
                total.timed_out,
                total.resends,
                total.delivered,
                // HFLink, MAVLink and Dynamixel number nothing: a duplicate request cannot be
                // told from a new one. Dynamixel's column counts the servos' answers handed
                // to the host twice instead.
                match name {
                    "roborts" => total.duplicates_delivered.to_string(),
                    "dynamixel" => total.answers_twice.to_string(),
                    _ => "-".to_string(),
                },
                total.allocations
            );
        }
    }
}

fn add(total: &mut Tally, t: &Tally) {
    total.requests += t.requests;
    total.answered += t.answered;
    total.partial += t.partial;
    total.incomplete += t.incomplete;
    total.answers_twice += t.answers_twice;
    total.refused += t.refused;
    total.rejected_by_value += t.rejected_by_value;
    total.progress += t.progress;
    total.timed_out += t.timed_out;
    total.resends += t.resends;
    total.delivered += t.delivered;
    total.duplicates_delivered += t.duplicates_delivered;
    total.allocations += t.allocations;
    total.faults.frames += t.faults.frames;
    total.faults.dropped += t.faults.dropped;
    total.faults.duplicated += t.faults.duplicated;
    total.faults.corrupted += t.faults.corrupted;
}
