//! Dynamixel 2.0 golden vectors (`tests/vectors/dynamixel_protocol2.json`, made by running the
//! DynamixelSDK's C++): every packet, byte-stuffed ones included, decodes to its recorded fields
//! and encodes back to the exact bytes; the status stream yields its expected packets at every
//! chunk size. The companion feedback frame has no vectors from running code: it is checked
//! against frames built here by hand from the blog's layout.

use protocol_kit::{Bytes, DecodeError, Group, MessagePayload};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/dynamixel.toml");

use dynamixel::*;

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

/// A goal position of `len` bytes, little-endian (two's complement for negative values).
fn le_bytes(value: i64, len: usize) -> Vec<u8> {
    value.to_le_bytes()[..len].to_vec()
}

fn expected(frame: &Value) -> Message {
    let v = &frame["fields"];
    let params = hex(frame["params_unstuffed_hex"].as_str().expect("params"));
    match frame["instruction_name"].as_str().expect("instruction") {
        "SYNC_WRITE" => {
            let len = u(v, "data_length") as usize;
            let mut servos = Group::new();
            let listed: Vec<(u64, i64)> = match v["servos"].as_array() {
                Some(list) => list
                    .iter()
                    .map(|s| (u(s, "id"), s["goal_position"].as_i64().expect("position")))
                    .collect(),
                // The 253-servo vector states its rule instead of listing the servos.
                None => {
                    assert_eq!(v["servos"], "ids 0..252, goal_position = (id*16) & 0xFFF");
                    (0..253)
                        .map(|id| (id, ((id * 16) & 0xFFF) as i64))
                        .collect()
                }
            };
            for (id, position) in listed {
                let data = le_bytes(position, len);
                servos
                    .push(SyncWriteServo {
                        id: id as u8,
                        data: Bytes::from_slice(&data).expect("fits"),
                    })
                    .expect("room");
            }
            Message::SyncWrite(SyncWrite {
                start_address: u(v, "start_address") as u16,
                data_length: len as u16,
                servos,
            })
        }
        "PING" => Message::Ping,
        "WRITE" => Message::Write(Write {
            address: u(v, "address") as u16,
            data: Bytes::from_slice(&le_bytes(u(v, "value") as i64, params.len() - 2))
                .expect("fits"),
        }),
        "STATUS" => {
            let data = match v["data_hex"].as_str() {
                Some(h) => hex(h),
                None => le_bytes(u(v, "present_position") as i64, params.len() - 1),
            };
            let error = u(v, "error") as u8;
            Message::Status(Status {
                error_number: error & 0x7F,
                alert: error & 0x80 != 0,
                data: Bytes::from_slice(&data).expect("fits"),
            })
        }
        other => panic!("vector not covered: {other}"),
    }
}

#[test]
fn every_packet_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("dynamixel_protocol2.json");
    let mut stuffed = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let packet = Packet {
            header: Header {
                id: u(frame, "id") as u8,
            },
            message: expected(frame),
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
        assert_eq!(
            packet.encoded_len(),
            n,
            "{name}: encoded_len counts the stuffing"
        );
        if frame["stuffed"] == true {
            stuffed += 1;
            let unstuffed = HEADER_LEN + packet.message.payload_len() + TRAILER_LEN;
            assert!(n > unstuffed, "{name}: stuffing added bytes");
        }
    }
    assert_eq!(stuffed, 2);
}

#[test]
fn the_largest_sync_write_has_253_servos() {
    let v = load_vectors("dynamixel_protocol2.json");
    let frame = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .find(|f| f["name"] == "sync_write_253servos_max")
        .expect("vector");
    let bytes = hex(frame["hex"].as_str().expect("hex"));
    assert_eq!(bytes.len(), 773);
    let Ok(Packet {
        message: Message::SyncWrite(w),
        ..
    }) = Packet::decode(&bytes)
    else {
        panic!("decodes")
    };
    assert_eq!(w.servos.len(), 253);
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = Packet {
        header: Header { id: 0xFE },
        message: Message::SyncWrite(w),
    }
    .encode(&mut buf)
    .expect("encodes");
    assert_eq!(F(&buf[..n]), F(&bytes));
}

#[test]
fn a_servo_whose_data_disagrees_with_data_length_is_an_error_both_ways() {
    let mut servos = Group::new();
    servos
        .push(SyncWriteServo {
            id: 1,
            data: Bytes::from_slice(&[1, 2, 3]).expect("fits"),
        })
        .expect("room");
    let w = Packet {
        header: Header { id: 0xFE },
        message: Message::SyncWrite(SyncWrite {
            start_address: 116,
            data_length: 2,
            servos,
        }),
    };
    assert!(w.encode(&mut [0u8; 64]).is_err());
    // 5 bytes after the 4 fixed ones with data_length 2: 1 + 2, then a servo cut short.
    let frame = hex("fffffd00fe0d00837400020001000802ff");
    let mut sealed = [0u8; 64];
    sealed[..frame.len()].copy_from_slice(&frame);
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_UMTS).checksum(&frame);
    sealed[frame.len()..frame.len() + 2].copy_from_slice(&crc.to_le_bytes());
    let sealed = &sealed[..frame.len() + 2];
    // LEN must count this shorter packet.
    let mut fixed = sealed.to_vec();
    fixed[5] = (fixed.len() - 7) as u8;
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_UMTS).checksum(&fixed[..fixed.len() - 2]);
    let end = fixed.len();
    fixed[end - 2..].copy_from_slice(&crc.to_le_bytes());
    assert!(matches!(
        Packet::decode(&fixed),
        Err(DecodeError::Truncated { .. }
            | DecodeError::SizeMismatch { .. }
            | DecodeError::PayloadLength { .. })
    ));
}

#[test]
fn status_stream_yields_expected_packets_at_every_chunk_size() {
    let v = load_vectors("dynamixel_protocol2.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        assert!(matches!(
            Packet::from_frame(frame),
            Ok(Packet {
                message: Message::Status(_),
                ..
            })
        ));
    });
}

/// A feedback frame built by hand from the blog's layout: `12 34 LEN`, per servo position and
/// speed (u16 BE), nine gyro values (i16 BE), optionally eight foot sensors (u16 LE), the sum of
/// LEN and the content modulo 256, `1F 2F`.
fn feedback_frame(servos: &[(u16, u16)], gyro: &[i16; 9], foot: Option<[u16; 8]>) -> Vec<u8> {
    let mut content = Vec::new();
    for (p, s) in servos {
        content.extend_from_slice(&p.to_be_bytes());
        content.extend_from_slice(&s.to_be_bytes());
    }
    for g in gyro {
        content.extend_from_slice(&g.to_be_bytes());
    }
    if let Some(f) = foot {
        for x in f {
            content.extend_from_slice(&x.to_le_bytes());
        }
    }
    let len = (content.len() + 6) as u8;
    let sum = content.iter().fold(len, |a, b| a.wrapping_add(*b));
    let mut frame = vec![0x12, 0x34, len];
    frame.extend_from_slice(&content);
    frame.extend_from_slice(&[sum, 0x1F, 0x2F]);
    frame
}

#[test]
fn feedback_frames_with_and_without_foot_sensors() {
    let servos: Vec<(u16, u16)> = (0..SERVO_COUNT as u16)
        .map(|i| (2048 + i, 10 * i))
        .collect();
    let gyro = [-1, 2, -300, 4, 5, 6, 7, 8, i16::MIN];
    for foot in [None, Some([1, 2, 3, 4, 5, 6, 7, 0xFFFF])] {
        let bytes = feedback_frame(&servos, &gyro, foot);
        assert_eq!(
            bytes.len(),
            if foot.is_some() {
                40 + 4 * 12
            } else {
                24 + 4 * 12
            }
        );
        let p = FeedbackPacket::decode(&bytes).expect("decodes");
        assert_eq!(p.payload.gyro, gyro, "two's complement, not x - 65535");
        assert_eq!(p.payload.foot, foot);
        assert_eq!(
            p.payload.servos[3],
            ServoFeedback {
                position: 2051,
                speed: 30
            }
        );
        let mut buf = [0u8; FEEDBACK_MAX_FRAME_LEN];
        let n = p.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes));
        // The stream decoder finds it among garbage.
        let mut dec = feedback_decoder();
        let stream = [&[0x12, 0x34, 0x03, 0x00][..], &bytes, &[0x12]].concat();
        let mut input = &stream[..];
        let frame = dec.decode(&mut input).expect("found");
        assert_eq!(frame.bytes, &bytes[..]);
    }
    // A LEN of 3 or less froze the blog's C parser; here it is a bad length.
    assert!(FeedbackPacket::decode(&[0x12, 0x34, 0x02, 0x00, 0x1F, 0x2F]).is_err());
}
