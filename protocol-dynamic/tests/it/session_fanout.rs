//! Dynamixel 2.0's SYNC_READ and BULK_READ, answered by a status from each servo they list:
//! a requester over generated code's `SESSION` and one over the rules the run-time codec
//! builds are driven with the same frames and the same passing of time, and agree on every
//! step (what each frame is, the retries, the outcome and the ids that did not answer); and
//! generated servos answer a broadcast SYNC_READ through `dispatch`, each with its own id.

use crate::support;

use protocol_kit::session::{
    Due, IdSet, Outcome, Received, Requester, Resolution, SessionRef, Ticket,
};
use support::interpreter;

protocol_kit::protocol!("../specs/dynamixel.toml");

use dynamixel::{BulkRead, BulkReadServo, Header, Message, Packet, Status, SyncRead};

/// The broadcast id.
const BROADCAST: u8 = 0xFE;

fn encode(p: &Packet) -> Vec<u8> {
    let mut frame = vec![0u8; dynamixel::MAX_FRAME_LEN];
    let n = p.encode(&mut frame).expect("encodes");
    frame.truncate(n);
    frame
}

/// A SYNC_READ listing `ids`, of `address` and `length` (0xFFFF and 0xFD: the payload starts
/// `FF FF FD`, which the frame stuffs, so the ids lie one byte later on the wire).
fn sync_read(ids: &[u8], address: u16, length: u16) -> Vec<u8> {
    let mut list = protocol_kit::Group::new();
    for &id in ids {
        list.push(id).expect("room");
    }
    encode(&Packet {
        header: Header { id: BROADCAST },
        message: Message::SyncRead(SyncRead {
            address,
            length,
            ids: list,
        }),
    })
}

fn status(id: u8) -> Vec<u8> {
    encode(&Packet {
        header: Header { id },
        message: Message::Status(Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(&[0x10, 0x20, 0x30, 0x40]).expect("fits"),
        }),
    })
}

/// The two requesters, generated and run-time, fed alike.
struct Pair<'r, G: SessionRef> {
    generated: Requester<G, 2, { dynamixel::MAX_FRAME_LEN }>,
    codec: Requester<&'r protocol_kit::session::SessionRules<'r>, 2, { dynamixel::MAX_FRAME_LEN }>,
}

impl<G: SessionRef> Pair<'_, G> {
    fn send(&mut self, now: u64, frame: &[u8]) -> Ticket {
        let (mut a, mut b) = (frame.to_vec(), frame.to_vec());
        let ta = self.generated.send(now, &mut a);
        assert_eq!(ta, self.codec.send(now, &mut b));
        assert_eq!(a, b);
        ta.expect("sent").expect("answers are expected")
    }

    fn heard(&mut self, now: u64, frame: &[u8]) -> Received {
        let a = self.generated.on_frame(now, frame);
        assert_eq!(a, self.codec.on_frame(now, frame), "at {now}");
        a
    }

    /// What time asks for at `now`: a resend (its frame) or an outcome.
    fn poll(&mut self, now: u64) -> Option<Result<Vec<u8>, Outcome>> {
        let show = |d: Option<Due<'_>>| match d {
            Some(Due::Resend { frame, .. }) => Some(Ok(frame.to_vec())),
            Some(Due::Outcome(o)) => Some(Err(o)),
            None => None,
        };
        let a = show(self.generated.poll(now));
        assert_eq!(a, show(self.codec.poll(now)), "at {now}");
        a
    }
}

#[test]
fn a_sync_read_is_answered_by_every_listed_servo_alike_in_both_machines() {
    let i = interpreter("dynamixel");
    let codec = i.codec();
    codec
        .with_session(|rules| {
            let mut m = Pair {
                generated: Requester::new(dynamixel::Session),
                codec: Requester::new(rules),
            };
            let request = sync_read(&[1, 2, 3], 0xFFFF, 0xFD);
            // `FF FF FD` in the payload is stuffed: `FF FF FD FD`.
            assert_eq!(
                request.get(8..13),
                Some(&[0xFF, 0xFF, 0xFD, 0xFD, 0x00][..])
            );
            let t = m.send(0, &request);
            assert!(m.generated.several(t));
            assert_eq!(
                m.heard(5, &status(2)),
                Received::Partial {
                    ticket: t,
                    id: 2,
                    waiting: 2
                }
            );
            // A servo the request does not list, and the broadcast id, answer nothing.
            assert_eq!(m.heard(6, &status(4)), Received::Unsolicited);
            assert_eq!(m.heard(6, &status(BROADCAST)), Received::Unsolicited);
            assert!(matches!(m.heard(20, &status(1)), Received::Partial { .. }));
            // The wait is 50 ms per answer: from 20 ms, none is due at 69.
            assert_eq!(m.poll(69), None);
            assert_eq!(
                m.heard(69, &status(3)),
                Received::Outcome(Outcome {
                    ticket: t,
                    resolution: Resolution::Answered
                })
            );
            assert_eq!(m.generated.open(), 0);
        })
        .expect("a session");
}

#[test]
fn a_bulk_read_that_a_servo_misses_times_out_naming_it_alike_in_both_machines() {
    let i = interpreter("dynamixel");
    let codec = i.codec();
    codec
        .with_session(|rules| {
            let mut m = Pair {
                generated: Requester::new(dynamixel::Session),
                codec: Requester::new(rules),
            };
            let mut servos = protocol_kit::Group::new();
            for (id, address) in [(7u8, 132u16), (9, 146), (11, 132)] {
                let length = 4;
                servos
                    .push(BulkReadServo {
                        id,
                        address,
                        length,
                    })
                    .expect("room");
            }
            let request = encode(&Packet {
                header: Header { id: BROADCAST },
                message: Message::BulkRead(BulkRead { servos }),
            });
            let t = m.send(0, &request);
            assert!(matches!(m.heard(10, &status(9)), Received::Partial { .. }));
            assert!(matches!(m.heard(11, &status(7)), Received::Partial { .. }));
            // Dynamixel's spec does not retry: 50 ms after the last answer, the outcome.
            assert_eq!(m.poll(60), None);
            let mut missing = IdSet::EMPTY;
            missing.insert(11);
            assert_eq!(
                m.poll(61),
                Some(Err(Outcome {
                    ticket: t,
                    resolution: Resolution::Incomplete(missing)
                }))
            );
            assert_eq!(m.poll(1000), None);
        })
        .expect("a session");
}

/// A servo of one id, answering reads with its id as data.
struct Servo(u8);

impl dynamixel::Handler for Servo {
    fn sync_read(
        &mut self,
        _: &Header,
        payload: &SyncRead,
    ) -> protocol_kit::session::Reply<Status> {
        if !payload.ids.contains(&self.0) {
            return protocol_kit::session::Reply::Refuse;
        }
        protocol_kit::session::Reply::Answer(Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(&[self.0]).expect("fits"),
        })
    }
}

#[test]
fn servos_answer_a_broadcast_sync_read_with_their_own_ids() {
    let request = sync_read(&[3, 5], 132, 1);
    let packet = Packet::from_frame(&request).expect("decodes");
    let mut req = dynamixel::Requester::<2>::new(dynamixel::Session);
    let t = req
        .send(0, &mut request.clone())
        .expect("sent")
        .expect("answers");
    let mut heard = Vec::new();
    for id in [3u8, 4, 5] {
        let Some(mut answer) = dynamixel::dispatch(&mut Servo(id), &packet) else {
            assert_eq!(id, 4, "a listed servo answers");
            continue;
        };
        // The answer's header is the request's (the broadcast id): the servo sets its own.
        assert_eq!(answer.header.id, BROADCAST);
        answer.header.id = id;
        heard.push(req.on_frame(1, &encode(&answer)));
    }
    assert_eq!(
        heard,
        [
            Received::Partial {
                ticket: t,
                id: 3,
                waiting: 1
            },
            Received::Outcome(Outcome {
                ticket: t,
                resolution: Resolution::Answered
            }),
        ]
    );
}

/// A READ of servo `id`.
fn read(id: u8) -> Vec<u8> {
    encode(&Packet {
        header: Header { id },
        message: Message::Read(dynamixel::Read {
            address: 132,
            length: 4,
        }),
    })
}

#[test]
fn a_read_and_a_sync_read_that_one_status_could_answer_are_not_open_together() {
    use protocol_kit::session::SendError;
    let i = interpreter("dynamixel");
    let codec = i.codec();
    codec
        .with_session(|rules| {
            let mut m = Pair {
                generated: Requester::new(dynamixel::Session),
                codec: Requester::new(rules),
            };
            let both = |m: &mut Pair<'_, _>, frame: &[u8]| {
                let (mut a, mut b) = (frame.to_vec(), frame.to_vec());
                let r = m.generated.send(1, &mut a);
                assert_eq!(r, m.codec.send(1, &mut b));
                r
            };
            let read3 = m.send(0, &read(3));
            // A status from 3 could answer the READ or the SYNC_READ: the requester refuses
            // the second until the first resolves, in generated code and the codec alike.
            let listing3 = sync_read(&[1, 3], 132, 4);
            assert_eq!(both(&mut m, &listing3), Err(SendError::Ambiguous));
            let sync = m.send(1, &sync_read(&[1, 2], 132, 4));
            assert_eq!(both(&mut m, &read(2)), Err(SendError::Ambiguous));
            assert_eq!(
                m.heard(2, &status(3)),
                Received::Outcome(Outcome {
                    ticket: read3,
                    resolution: Resolution::Answered
                })
            );
            assert!(matches!(m.heard(3, &status(2)), Received::Partial { .. }));
            // 3 answered and the SYNC_READ waits for 1 alone: a READ of 2 and a SYNC_READ
            // of 3 are told apart from it.
            let read2 = m.send(4, &read(2));
            assert_eq!(
                m.heard(5, &status(2)),
                Received::Outcome(Outcome {
                    ticket: read2,
                    resolution: Resolution::Answered
                })
            );
            assert!(m.generated.open() == 1 && m.codec.open() == 1);
            assert_eq!(
                m.heard(6, &status(1)),
                Received::Outcome(Outcome {
                    ticket: sync,
                    resolution: Resolution::Answered
                })
            );
            m.send(7, &listing3);
        })
        .expect("the spec has a session");
}
