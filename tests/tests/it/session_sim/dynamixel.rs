//! Dynamixel 2.0 in the simulated conversation: a host reads four servos on one bus with
//! SYNC_READ and BULK_READ (sent to the broadcast id, answered by a status from each servo
//! they list, one after another) and with READ (one servo, one status). The device side plays
//! every servo: it answers a request with one status per listed id, carrying as many bytes as
//! the request asks of that servo.

use crate::handler::dynamixel::{
    self, BulkRead, BulkReadServo, Header, Message, Packet, Read, Status, SyncRead,
};

use super::sim::Peer;

/// The broadcast id.
const BROADCAST: u8 = 0xFE;

fn encode(p: &Packet) -> Vec<u8> {
    let mut frame = vec![0u8; dynamixel::MAX_FRAME_LEN];
    let n = p.encode(&mut frame).expect("encodes");
    frame.truncate(n);
    frame
}

/// Servos 1 to 4 as the bits of `mode` pick them (one of them when it picks none).
fn servos(mode: u8) -> Vec<u8> {
    let picked: Vec<u8> = (1..=4u8).filter(|i| mode & (1 << (i - 1)) != 0).collect();
    if picked.is_empty() {
        vec![1 + (mode >> 4) % 4]
    } else {
        picked
    }
}

/// A status from servo `id` with `len` bytes of data.
fn status(id: u8, len: u16) -> Vec<u8> {
    let data = vec![id; usize::from(len)];
    encode(&Packet {
        header: Header { id },
        message: Message::Status(Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(&data).expect("fits"),
        }),
    })
}

/// The host reads a bus of four servos.
pub struct Dynamixel;

impl Peer for Dynamixel {
    type Session = dynamixel::Session;
    fn session() -> dynamixel::Session {
        dynamixel::Session
    }

    fn request(kind: u8, mode: u8) -> Vec<u8> {
        let ids = servos(mode);
        let (id, message) = match kind % 3 {
            0 => {
                let mut list = protocol_kit::Group::new();
                for &id in &ids {
                    list.push(id).expect("room");
                }
                let sync = SyncRead {
                    address: 132,
                    length: 4,
                    ids: list,
                };
                (BROADCAST, Message::SyncRead(sync))
            }
            1 => {
                let mut list = protocol_kit::Group::new();
                for &id in &ids {
                    let servo = BulkReadServo {
                        id,
                        address: 120 + u16::from(id),
                        length: u16::from(id),
                    };
                    list.push(servo).expect("room");
                }
                (BROADCAST, Message::BulkRead(BulkRead { servos: list }))
            }
            _ => {
                let read = Read {
                    address: 146,
                    length: 1,
                };
                (ids[0], Message::Read(read))
            }
        };
        encode(&Packet {
            header: Header { id },
            message,
        })
    }

    fn handshake() -> Option<Vec<u8>> {
        None
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        Self::answers(request).remove(0)
    }

    fn answers(request: &[u8]) -> Vec<Vec<u8>> {
        let packet = Packet::from_frame(request).expect("the responder delivers requests");
        let mut sent: Vec<u8> = Vec::new();
        let mut once = |id: u8| {
            let first = !sent.contains(&id);
            sent.push(id);
            first
        };
        match packet.message {
            Message::SyncRead(s) => s
                .ids
                .iter()
                .filter(|&&id| once(id))
                .map(|&id| status(id, s.length))
                .collect(),
            Message::BulkRead(b) => b
                .servos
                .iter()
                .filter(|s| once(s.id))
                .map(|s| status(s.id, s.length))
                .collect(),
            Message::Read(r) => vec![status(packet.header.id, r.length)],
            other => panic!("not a request of the plan: {other:?}"),
        }
    }

    fn decodes(frame: &[u8]) -> bool {
        dynamixel::LAYOUT
            .parse(frame)
            .is_ok_and(|f| f.len() == frame.len())
            && Packet::from_frame(frame).is_ok()
    }
}
