//! `protocol decode --session` on captures where a request hears more than one answer: a
//! MAVLink COMMAND_LONG answered first by a COMMAND_ACK whose `result` says it is in progress,
//! then by the final one (both answer the request; the first leaves it open), and a Dynamixel
//! 2.0 SYNC_READ answered by a status from each servo it lists (each answers the request, the
//! last closes it). An answer that comes after its request closed answers nothing. Each status
//! answering a SYNC_READ or a BULK_READ is typed by the registers its servo was asked for.

use crate::support;

use support::{json_lines, protocol, text};

protocol_kit::protocol!("../specs/mavlink.toml");
protocol_kit::protocol!("../specs/dynamixel.toml");

/// The decoded frames of `capture` through `spec`'s conversation, as JSON lines.
fn decode(spec: &str, capture: &[u8]) -> Vec<serde_json::Value> {
    let out = protocol(
        &["decode", spec, "-", "--session", "--format", "json"],
        capture,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    json_lines(&out.stdout)
        .into_iter()
        .filter(|l| l.get("hex").is_some())
        .collect()
}

fn mavlink_frame(packet: &mavlink::Packet) -> Vec<u8> {
    let mut buf = vec![0u8; mavlink::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

/// A COMMAND_ACK of command 400 from the autopilot to the ground station with `result`.
fn ack(result: u8) -> Vec<u8> {
    use mavlink::{CommandAck, Header, Message, Packet};
    mavlink_frame(&Packet {
        header: Header {
            sysid: 1,
            compid: 1,
            ..Header::default()
        },
        message: Message::CommandAck(CommandAck {
            command: 400,
            result,
            progress: 0,
            result_param2: 0,
            target_system: 255,
            target_component: 190,
        }),
    })
}

#[test]
fn a_final_ack_after_an_in_progress_one_answers_the_same_command() {
    use mavlink::{CommandLong, Header, Message, Packet};
    let mut capture = mavlink_frame(&Packet {
        header: Header {
            sysid: 255,
            compid: 190,
            ..Header::default()
        },
        message: Message::CommandLong(CommandLong {
            param1: 1.0,
            param2: 0.0,
            param3: 0.0,
            param4: 0.0,
            param5: 0.0,
            param6: 0.0,
            param7: 0.0,
            command: 400,
            target_system: 1,
            target_component: 1,
            confirmation: 0,
        }),
    });
    // MAV_RESULT_IN_PROGRESS (5), then MAV_RESULT_ACCEPTED (0), then an ACCEPTED too many.
    for result in [5, 0, 0] {
        capture.extend(ack(result));
    }
    let frames = decode("specs/mavlink.toml", &capture);
    assert_eq!(frames.len(), 4);
    assert_eq!(frames[1]["answers"], 0, "{}", frames[1]);
    assert_eq!(frames[1]["request_open"], true, "{}", frames[1]);
    assert_eq!(frames[2]["answers"], 0, "{}", frames[2]);
    assert!(frames[2].get("request_open").is_none(), "{}", frames[2]);
    assert!(frames[3].get("answers").is_none(), "{}", frames[3]);

    let out = protocol(
        &[
            "decode",
            "specs/mavlink.toml",
            "-",
            "--session",
            "--stats",
            "--format",
            "table",
        ],
        &capture,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("answers #0 (more to come)"), "{stdout}");
    assert!(
        stdout
            .contains("conversation: 2 answers paired with their requests, 0 requests unanswered"),
        "{stdout}"
    );
}

fn dynamixel_frame(id: u8, message: dynamixel::Message) -> Vec<u8> {
    let mut buf = vec![0u8; dynamixel::MAX_FRAME_LEN];
    let packet = dynamixel::Packet {
        header: dynamixel::Header { id },
        message,
    };
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

fn status(id: u8) -> Vec<u8> {
    dynamixel_frame(
        id,
        dynamixel::Message::Status(dynamixel::Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(&[0x00, 0x08, 0x00, 0x00]).expect("fits"),
        }),
    )
}

#[test]
fn each_listed_servo_answers_a_sync_read_and_the_last_closes_it() {
    let mut ids = protocol_kit::Group::new();
    for id in [1u8, 2] {
        ids.push(id).expect("room");
    }
    let mut capture = dynamixel_frame(
        0xFE,
        dynamixel::Message::SyncRead(dynamixel::SyncRead {
            address: 132,
            length: 4,
            ids,
        }),
    );
    // Servo 3 is not listed; servo 1 answers again after the request closed.
    for id in [2u8, 3, 1, 1] {
        capture.extend(status(id));
    }
    let frames = decode("specs/dynamixel.toml", &capture);
    assert_eq!(frames.len(), 5);
    assert_eq!(frames[1]["answers"], 0, "{}", frames[1]);
    assert_eq!(frames[1]["request_open"], true, "{}", frames[1]);
    assert!(frames[2].get("answers").is_none(), "{}", frames[2]);
    assert_eq!(frames[3]["answers"], 0, "{}", frames[3]);
    assert!(frames[3].get("request_open").is_none(), "{}", frames[3]);
    assert!(frames[4].get("answers").is_none(), "{}", frames[4]);
}

/// A status from servo `id` carrying `data`.
fn status_with(id: u8, data: &[u8]) -> Vec<u8> {
    dynamixel_frame(
        id,
        dynamixel::Message::Status(dynamixel::Status {
            error_number: 0,
            alert: false,
            data: protocol_kit::Bytes::from_slice(data).expect("fits"),
        }),
    )
}

#[test]
fn each_status_answering_a_sync_read_is_typed_by_the_run_every_servo_was_asked() {
    let mut ids = protocol_kit::Group::new();
    for id in [4u8, 9] {
        ids.push(id).expect("room");
    }
    // Present velocity (128, i32) and present position (132, i32), 8 bytes from 128.
    let mut capture = dynamixel_frame(
        0xFE,
        dynamixel::Message::SyncRead(dynamixel::SyncRead {
            address: 128,
            length: 8,
            ids,
        }),
    );
    capture.extend(status_with(
        9,
        &[0xFD, 0xFF, 0xFF, 0xFF, 0x00, 0x08, 0x00, 0x00],
    ));
    capture.extend(status_with(4, &[0x05, 0x00, 0x00, 0x00, 0x10, 0x00, 0x00]));
    let frames = decode("specs/dynamixel.toml", &capture);
    assert_eq!(frames.len(), 3);
    // Present velocity is 0.229 rpm per unit.
    let velocity = |f: &serde_json::Value| f["registers"]["present_velocity"].as_f64();
    assert_eq!(frames[1]["answers"], 0, "{}", frames[1]);
    assert_eq!(
        frames[1]["registers"]["present_position"], 2048,
        "{}",
        frames[1]
    );
    assert!((velocity(&frames[1]).expect("velocity") + 3.0 * 0.229).abs() < 1e-9);
    assert!(frames[1].get("registers_note").is_none(), "{}", frames[1]);
    // Servo 4 sent 7 of the 8 bytes: the velocity whole, the position cut.
    assert_eq!(frames[2]["answers"], 0, "{}", frames[2]);
    assert!((velocity(&frames[2]).expect("velocity") - 5.0 * 0.229).abs() < 1e-9);
    assert!(
        frames[2]["registers"].get("present_position").is_none(),
        "{}",
        frames[2]
    );
    let note = frames[2]["registers_note"].as_str().expect("a note");
    assert!(note.contains("carries 7 of the 8 bytes asked"), "{note}");
}

#[test]
fn each_status_answering_a_bulk_read_is_typed_by_the_run_its_own_servo_was_asked() {
    use dynamixel::{BulkRead, BulkReadServo};
    let mut servos = protocol_kit::Group::new();
    // Servo 7: present temperature (146, 1 byte); servo 2: present position (132, 4 bytes).
    for (id, address, length) in [(7u8, 146u16, 1u16), (2, 132, 4)] {
        let servo = BulkReadServo {
            id,
            address,
            length,
        };
        servos.push(servo).expect("room");
    }
    let mut capture = dynamixel_frame(0xFE, dynamixel::Message::BulkRead(BulkRead { servos }));
    // The servos answer in id order; one not listed answers nothing.
    capture.extend(status_with(2, &[0x00, 0x04, 0x00, 0x00]));
    capture.extend(status_with(5, &[0x2A]));
    capture.extend(status_with(7, &[0x2A]));
    let frames = decode("specs/dynamixel.toml", &capture);
    assert_eq!(frames.len(), 4);
    assert_eq!(frames[1]["answers"], 0, "{}", frames[1]);
    assert_eq!(
        frames[1]["registers"],
        serde_json::json!({ "present_position": 1024 }),
        "{}",
        frames[1]
    );
    assert!(frames[2].get("answers").is_none(), "{}", frames[2]);
    assert!(frames[2].get("registers").is_none(), "{}", frames[2]);
    assert_eq!(frames[3]["answers"], 0, "{}", frames[3]);
    assert_eq!(
        frames[3]["registers"],
        serde_json::json!({ "present_temperature": 42 }),
        "{}",
        frames[3]
    );
    for f in &frames[1..] {
        assert!(f.get("registers_note").is_none(), "{f}");
    }
}
