//! ROBOTIS Dynamixel Protocol 2.0: a host and four X-series servos on one bus, and the
//! companion board's feedback frames.

use protocol_kit::{Bytes, Group};

use crate::{Stream, wave};

protocol_kit::protocol!("../specs/dynamixel.toml");

/// Goal position register of X-series servos, and present position.
const GOAL_POSITION: u16 = 116;
const PRESENT_POSITION: u16 = 132;

/// A host and servos 1 to 4 for 0.5 s: a broadcast ping and its statuses, torque on, then at
/// 50 Hz a sync write of the four goal positions and a read of each present position with its
/// status. A goal of -131073 (`FF FF FD FF`) is byte-stuffed on the wire. One packet carries an
/// instruction this spec does not have.
pub fn capture() -> Stream {
    use dynamixel::*;
    let mut s = Stream::new(0x4459_4E41_4D49_0006, &[0xFF, 0xFD]);
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
    let status = |data: &[u8]| {
        Message::Status(Status {
            error_number: 0,
            alert: false,
            data: Bytes::from_slice(data).expect("fits"),
        })
    };
    send(&mut s, 0xFE, Message::Ping);
    for id in 1..=4u8 {
        // Model 1020 (XM430-W350), firmware 45.
        send(&mut s, id, status(&[0xFC, 0x03, 0x2D]));
    }
    for id in 1..=4u8 {
        let write = Write {
            address: 64,
            data: Bytes::from_slice(&[1]).expect("fits"),
        };
        send(&mut s, id, Message::Write(write));
        send(&mut s, id, status(&[]));
    }
    for cycle in 0..25u32 {
        let t = cycle as f32 * 0.02;
        let goals: [i32; 4] = [
            2048 + (600.0 * wave(t, 0.5)) as i32,
            2048 - (600.0 * wave(t, 0.5)) as i32,
            if cycle % 8 == 3 { -131_073 } else { 1024 },
            3072,
        ];
        let servos: Vec<SyncWriteServo> = goals
            .iter()
            .zip(1u8..)
            .map(|(g, id)| SyncWriteServo {
                id,
                data: Bytes::from_slice(&g.to_le_bytes()).expect("fits"),
            })
            .collect();
        let sync = SyncWrite {
            start_address: GOAL_POSITION,
            data_length: 4,
            servos: Group::from_slice(&servos).expect("fits"),
        };
        send(&mut s, 0xFE, Message::SyncWrite(sync));
        for (goal, id) in goals.iter().zip(1u8..) {
            send(
                &mut s,
                id,
                Message::Read(Read {
                    address: PRESENT_POSITION,
                    length: 4,
                }),
            );
            let present = goal - 12 + s.rng.below(25) as i32;
            send(&mut s, id, status(&present.to_le_bytes()));
        }
        if cycle == 17 {
            // Instruction 0x99, which no Protocol 2.0 document defines.
            let mut frame = [0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x00, 0x00, 0x99, 0x00, 0x00];
            LAYOUT.seal(&mut frame).expect("seals");
            s.unknown(&frame);
        }
    }
    s
}

/// The companion board's feedback frames at 100 Hz for 0.3 s: twelve servos' positions and
/// speeds, the gyro, and every other frame the foot sensors (the frame is then longer).
pub fn feedback_capture() -> Stream {
    use dynamixel::*;
    let mut s = Stream::new(0x4644_4241_434B_0007, &[0x12, 0x34]);
    for frame_no in 0..30u16 {
        let t = f32::from(frame_no) * 0.01;
        let mut servos = [ServoFeedback {
            position: 0,
            speed: 0,
        }; 12];
        for (i, servo) in servos.iter_mut().enumerate() {
            servo.position = 512 + (200.0 * wave(t + i as f32 * 0.05, 0.3)) as u16;
            servo.speed = 40 + s.rng.below(8) as u16;
        }
        let mut gyro = [0i16; 9];
        for g in &mut gyro {
            *g = s.rng.jitter(300.0) as i16;
        }
        let foot = (frame_no % 2 == 0).then(|| [300 + frame_no, 310, 0, 0, 295, 305, 0, 0]);
        let packet = FeedbackPacket {
            header: FeedbackHeader {},
            payload: Feedback { servos, gyro, foot },
        };
        let mut buf = [0u8; FEEDBACK_MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        s.frame(&buf[..n]);
    }
    s
}
