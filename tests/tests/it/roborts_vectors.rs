//! RoboRTS SDK golden vectors (`tests/vectors/roborts_sdk.json`, made by running the SDK's
//! C++): every frame decodes to its recorded header and fields and encodes back to the exact
//! bytes, the header-only acknowledgement included; the stream yields exactly its expected
//! frames at every chunk size; what the original rejects is rejected.

use protocol_kit::{Bytes, DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/roborts.toml");

use roborts::*;

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn i(v: &Value, k: &str) -> i64 {
    v[k].as_i64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn header(h: &Value) -> Header {
    Header {
        session_id: u(h, "session_id") as u8,
        sender: u(h, "sender") as u8,
        receiver: u(h, "receiver") as u8,
        seq_num: u(h, "seq_num") as u16,
    }
}

/// The message a vector records, built from its JSON fields.
fn expected(frame: &Value) -> Message {
    let v = &frame["fields"];
    if frame["header"]["is_ack"] == 1 {
        return Message::Ack(
            Bytes::from_slice(&hex(frame["data_hex"].as_str().unwrap_or(""))).expect("fits"),
        );
    }
    match (u(frame, "cmd_set"), u(frame, "cmd_id")) {
        (0x03, 0x03) => Message::SetGimbalAngle(GimbalAngle {
            yaw_mode: AngleMode::from_raw(u(&v["ctrl"], "yaw_mode") as u8).expect("0 or 1"),
            pitch_mode: AngleMode::from_raw(u(&v["ctrl"], "pitch_mode") as u8).expect("0 or 1"),
            pitch: i(v, "pitch") as i16,
            yaw: i(v, "yaw") as i16,
        }),
        (0x02, 0x03) => Message::SetChassisSpeed(ChassisSpeed {
            vx: i(v, "vx") as i16,
            vy: i(v, "vy") as i16,
            vw: i(v, "vw") as i16,
            rotate_x_offset: i(v, "rotate_x_offset") as i16,
            rotate_y_offset: i(v, "rotate_y_offset") as i16,
        }),
        (0x00, 0x01) => Message::Heartbeat(Heartbeat {
            heartbeat: u(v, "heartbeat") as u32,
        }),
        (0x01, 0x01) => Message::RefereeSendData(SupplyProjectileBooking {
            cmd: u(v, "cmd") as u16,
            supply_projectile_id: u(v, "supply_projectile_id") as u8,
            supply_robot_id: u(v, "supply_robot_id") as u8,
            supply_num: u(v, "supply_num") as u8,
        }),
        (0xFF, 0x00) => {
            // "bytes (i*7+0xAA)&0xFF, i=0..1004"
            let data: Vec<u8> = (0..1005u32)
                .map(|i| ((i * 7 + 0xAA) & 0xFF) as u8)
                .collect();
            assert_eq!(data, hex(frame["data_hex"].as_str().expect("data")));
            Message::TextEchoTransmit(RawData {
                data: Bytes::from_slice(&data).expect("1005 bytes fit"),
            })
        }
        (0x02, 0x01) => Message::PushChassisInfo(ChassisInfo {
            gyro_angle: i(v, "gyro_angle") as i16,
            gyro_rate: i(v, "gyro_rate") as i16,
            position_x_mm: i(v, "position_x_mm") as i32,
            position_y_mm: i(v, "position_y_mm") as i32,
            angle_deg: i(v, "angle_deg") as i16,
            v_x_mm: i(v, "v_x_mm") as i16,
            v_y_mm: i(v, "v_y_mm") as i16,
        }),
        (0x42, 0x01) => Message::RobotStatus(GameRobotState {
            robot_id: u(v, "robot_id") as u8,
            robot_level: u(v, "robot_level") as u8,
            remain_hp: u(v, "remain_HP") as u16,
            max_hp: u(v, "max_HP") as u16,
            shooter_heat0_cooling_rate: u(v, "shooter_heat0_cooling_rate") as u16,
            shooter_heat0_cooling_limit: u(v, "shooter_heat0_cooling_limit") as u16,
            shooter_heat1_cooling_rate: u(v, "shooter_heat1_cooling_rate") as u16,
            shooter_heat1_cooling_limit: u(v, "shooter_heat1_cooling_limit") as u16,
            mains_power_gimbal_output: u(v, "mains_power_gimbal_output") == 1,
            mains_power_chassis_output: u(v, "mains_power_chassis_output") == 1,
            mains_power_shooter_output: u(v, "mains_power_shooter_output") == 1,
        }),
        (0x04, 0x02) => {
            let d: Vec<i16> = v["distance"]
                .as_array()
                .expect("distance")
                .iter()
                .map(|x| x.as_i64().expect("int") as i16)
                .collect();
            Message::PushUwbInfo(UwbInfo {
                x: i(v, "x") as i16,
                y: i(v, "y") as i16,
                yaw: u(v, "yaw") as u16,
                distance: d.try_into().expect("6 distances"),
                error: u(v, "error") as u16,
                res: u(v, "res") as u16,
            })
        }
        other => panic!("vector not covered: {other:?}"),
    }
}

#[test]
fn every_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("roborts_sdk.json");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let packet = Packet {
            header: header(&frame["header"]),
            message: expected(frame),
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..len]), F(&bytes), "{name}: encode");
        n += 1;
    }
    assert_eq!(n, 9);
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("roborts_sdk.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        let p = Packet::from_frame(frame).expect("decodes");
        assert!(p.message.command().is_some());
    });
}

/// Re-seal a header after editing it, so that only the edited rule can reject it.
fn with_header_crc(mut header: [u8; 12]) -> [u8; 12] {
    let crc = crc::Crc::<u16>::new(&crc::Algorithm {
        width: 16,
        poly: 0x8005,
        init: 0xC55C,
        refin: true,
        refout: true,
        xorout: 0,
        check: 0x2752,
        residue: 0,
    })
    .checksum(&header[..10]);
    header[10..].copy_from_slice(&crc.to_le_bytes());
    header
}

#[test]
fn rejects_what_the_original_rejects() {
    // The header-only acknowledgement of the vectors.
    let ack: [u8; 12] = hex("aa0c0025000200000700a0bc")
        .try_into()
        .expect("12 bytes");
    assert!(Packet::decode(&ack).is_ok());
    // Version 1 (bits 10..16 of the length word).
    let mut h = ack;
    h[2] |= 0x04;
    assert_eq!(
        LAYOUT.parse(&with_header_crc(h)),
        Err(DecodeError::Frame(Reject::BadHeader))
    );
    // Reserved bits of the session byte.
    let mut h = ack;
    h[3] |= 0x80;
    assert_eq!(
        LAYOUT.parse(&with_header_crc(h)),
        Err(DecodeError::Frame(Reject::BadHeader))
    );
    // reserved1.
    let mut h = ack;
    h[6] = 1;
    assert_eq!(
        LAYOUT.parse(&with_header_crc(h)),
        Err(DecodeError::Frame(Reject::BadHeader))
    );
    // A length below 12, and lengths 13 to 15 (no room for the CRC32).
    for len in [0u8, 5, 11, 13, 14, 15] {
        let mut h = ack;
        h[1] = len;
        assert_eq!(
            LAYOUT.parse(&with_header_crc(h)),
            Err(DecodeError::Frame(Reject::BadLength)),
            "length {len}"
        );
    }
    // A command payload of 1006 bytes would wrap the 10-bit length: the payload type cannot
    // even hold it, and the largest ones (1005 bytes of command data, 1007 of ack data) encode
    // to a 1023-byte frame.
    assert!(Bytes::<1005>::from_slice(&[0u8; 1006]).is_none());
    let header = Header {
        session_id: 0,
        sender: 0,
        receiver: 2,
        seq_num: 0,
    };
    let largest_ack = Packet {
        header,
        message: Message::Ack(Bytes::from_slice(&[7u8; 1007]).expect("fits")),
    };
    let largest_cmd = Packet {
        header,
        message: Message::TextEchoTransmit(RawData {
            data: Bytes::from_slice(&[7u8; 1005]).expect("fits"),
        }),
    };
    for p in [largest_ack, largest_cmd] {
        let mut buf = [0u8; 1100];
        assert_eq!(p.encode(&mut buf), Ok(1023));
        assert_eq!(Packet::decode(&buf[..1023]), Ok(p));
    }
}
