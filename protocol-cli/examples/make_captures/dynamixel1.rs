//! ROBOTIS Dynamixel Protocol 1.0 on a half-duplex bus: a controller and three AX-12 servos,
//! instruction and status packets on one wire, as a sniffer sees them. Nothing in a packet
//! tells an instruction from a status: `protocol decode --session` reads each status by its
//! place after the instruction it answers.

use protocol_kit::Bytes;

use crate::Stream;

protocol_kit::protocol!("../specs/dynamixel1.toml");

/// Goal position and present position of the AX-12's control table.
const GOAL_POSITION: u8 = 30;
const PRESENT_POSITION: u8 = 36;

/// 20 cycles: the controller writes each servo's goal (a status answers), reads each present
/// position (a status with two bytes answers), every fifth cycle writes every LED with a
/// broadcast (no status), and every fourth cycle looks for a servo 4 that is not on the bus (a
/// READ no status answers).
pub fn half_duplex_capture() -> Stream {
    use dynamixel1::*;
    let mut s = Stream::new(0x4458_4C31_5345_5353, &[0xFF, 0xFF]);
    s.undamaged(&[0xFF]);
    fn send(s: &mut Stream, id: u8, message: Message) {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet {
            header: Header { id },
            message,
        }
        .encode(&mut buf)
        .expect("encodes");
        s.frame(&buf[..n]);
    }
    let status = |params: &[u8]| {
        Message::Response(Status {
            params: Bytes::from_slice(params).expect("fits"),
            ..Status::default()
        })
    };
    for cycle in 0..20u16 {
        if cycle % 5 == 0 {
            let led = Write {
                address: 25,
                data: Bytes::from_slice(&[u8::from(cycle % 10 == 0)]).expect("fits"),
            };
            send(&mut s, 0xFE, Message::Request(Request::Write(led)));
        }
        for id in 1..=3u8 {
            let goal = 512 + (cycle * 7 + u16::from(id) * 31) % 200;
            let write = Write {
                address: GOAL_POSITION,
                data: Bytes::from_slice(&goal.to_le_bytes()).expect("fits"),
            };
            send(&mut s, id, Message::Request(Request::Write(write)));
            send(&mut s, id, status(&[]));
            let read = Read {
                address: PRESENT_POSITION,
                length: 2,
            };
            send(&mut s, id, Message::Request(Request::Read(read)));
            let present = goal.saturating_sub(3);
            send(&mut s, id, status(&present.to_le_bytes()));
        }
        if cycle % 4 == 3 {
            let read = Read {
                address: PRESENT_POSITION,
                length: 2,
            };
            send(&mut s, 4, Message::Request(Request::Read(read)));
        }
    }
    s
}
