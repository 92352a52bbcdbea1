//! MSP in the simulated conversation: a ground station asks a flight controller for
//! API_VERSION, ATTITUDE, STATUS and UID (no sequence number: a second request of a command
//! waits for the first to resolve). The flight controller answers the first two and refuses
//! the others with the error reply of their command (`!`), which resolves them as refused.

use crate::msp_yamspy::generated::msp::{
    self, ApiVersion, Attitude, Header, Message, Packet, Request, Response,
};

use super::sim::Peer;

fn encode(p: &Packet) -> Vec<u8> {
    let mut frame = vec![0u8; msp::MAX_FRAME_LEN];
    let n = p.encode(&mut frame).expect("encodes");
    frame.truncate(n);
    frame
}

/// The ground station (requester) and the flight controller (responder).
pub struct Msp;

impl Peer for Msp {
    type Session = msp::Session;
    fn session() -> msp::Session {
        msp::Session
    }

    fn request(kind: u8, _mode: u8) -> Vec<u8> {
        let request = match kind % 4 {
            0 => Request::ApiVersion,
            1 => Request::Attitude,
            2 => Request::Status,
            _ => Request::Uid,
        };
        encode(&Packet {
            header: Header { direction: b'<' },
            message: Message::Request(request),
        })
    }

    fn handshake() -> Option<Vec<u8>> {
        None
    }

    fn answer(request: &[u8]) -> Vec<u8> {
        let Ok(Packet {
            message: Message::Request(r),
            ..
        }) = Packet::from_frame(request)
        else {
            panic!("the responder delivers requests");
        };
        let (direction, message) = match r {
            Request::ApiVersion => (
                b'>',
                Message::Response(Response::ApiVersion(ApiVersion {
                    protocol_version: 0,
                    api_version_major: 1,
                    api_version_minor: 46,
                })),
            ),
            Request::Attitude => (
                b'>',
                Message::Response(Response::Attitude(Attitude {
                    roll: 1.5,
                    pitch: -2.0,
                    yaw: 90,
                })),
            ),
            other => (b'!', Message::Error(Message::Request(other).command())),
        };
        encode(&Packet {
            header: Header { direction },
            message,
        })
    }

    fn decodes(frame: &[u8]) -> bool {
        msp::LAYOUT
            .parse(frame)
            .is_ok_and(|f| f.len() == frame.len())
            && Packet::from_frame(frame).is_ok()
    }
}
