//! Golden frames of the check algorithms, each from a public reference source named where it
//! is used: UBX (Fletcher sums modulo 256), Dynamixel Protocol 1.0 (the one's complement of a
//! byte sum), iBUS (0xFFFF minus a 16-bit byte sum) and MAVLink v1 (CRC-16/MCRF4XX with each
//! message's CRC_EXTRA folded in). Every frame decodes to its recorded values and encodes back
//! to its bytes, by generated code and by the run-time codec (`protocol_dynamic`); a stream of
//! the frames with garbage and corrupt copies between them yields exactly the good frames at
//! every chunk size, in both; a corrupt check is rejected.
//!
//! The specs are small fixtures under `tests/check_specs/`.

use protocol_dynamic::{Interpreter, Item};
use protocol_kit::{DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex};

mod ubx {
    protocol_kit::protocol!("check_specs/ubx.toml");
}
mod dxl1 {
    protocol_kit::protocol!("check_specs/dynamixel1.toml");
}
mod ibus {
    protocol_kit::protocol!("check_specs/ibus.toml");
}
mod mav1 {
    protocol_kit::protocol!("check_specs/mavlink1.toml");
}

fn interpreter(spec: &str) -> Interpreter {
    let path = format!("{}/check_specs/{spec}", env!("CARGO_MANIFEST_DIR"));
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The run-time codec on `frames`: each decodes and re-encodes to its bytes; a copy with its
/// last byte (part of the check) flipped is refused.
fn dynamic_round_trips(interp: &Interpreter, frames: &[Vec<u8>]) {
    let codec = interp.codec();
    for bytes in frames {
        let decoded = codec
            .parse(0, bytes)
            .unwrap_or_else(|e| panic!("{:?}: {e:?}", F(bytes)));
        let value = codec.frame_value(&decoded, 0, bytes);
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{:?}: {e:?}", F(bytes)));
        assert_eq!(F(&encoded.bytes), F(bytes), "dynamic encode");
        let mut bad = bytes.clone();
        *bad.last_mut().expect("a frame") ^= 0x01;
        assert!(codec.parse(0, &bad).is_err(), "{:?} accepted", F(&bad));
    }
}

/// `frames` in a stream: garbage first, then each frame after a copy of it with a corrupt check
/// (its last byte flipped), then a stray sync byte. Returns the stream and the good frames
/// with their offsets.
fn stream_of(frames: &[Vec<u8>]) -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let mut stream = vec![0x00, 0x13, 0x37];
    let mut expected = Vec::new();
    for f in frames {
        let mut bad = f.clone();
        *bad.last_mut().expect("a frame") ^= 0x80;
        stream.extend_from_slice(&bad);
        expected.push((stream.len() as u64, f.clone()));
        stream.extend_from_slice(f);
    }
    stream.push(frames[0][0]);
    (stream, expected)
}

/// The run-time codec's stream on `stream` at every chunk size: exactly `expected`, every
/// frame decoded.
fn dynamic_stream(interp: &Interpreter, stream: &[u8], expected: &[(u64, Vec<u8>)]) {
    let codec = interp.codec();
    for chunk in 1..=stream.len() {
        let mut s = codec.stream(0).expect("a frame format");
        let mut got = Vec::new();
        let mut rejected = 0;
        for part in stream.chunks(chunk) {
            let mut input = part;
            while let Some(item) = s.next_item(&mut input) {
                match item {
                    Item::Frame {
                        offset,
                        bytes,
                        decoded,
                    } => {
                        assert!(decoded.is_ok(), "chunk {chunk}: {decoded:?}");
                        got.push((offset, bytes.to_vec()));
                    }
                    Item::Rejected { .. } => rejected += 1,
                    Item::Skipped { .. } => {}
                }
            }
        }
        assert_eq!(got, expected, "chunk size {chunk}");
        assert!(
            rejected >= expected.len(),
            "chunk size {chunk}: {rejected} rejected"
        );
    }
}

// ---- UBX: Fletcher sums modulo 256 ----

/// UBX-CFG-RATE and UBX-CFG-MSG frames as u-blox u-center writes them, widely quoted in
/// receiver set-up code: `B5 62 06 08 06 00 64 00 01 00 01 00 7A 12` (100 ms, 10 Hz),
/// `... E8 03 01 00 01 00 01 39` (1000 ms), `... C8 00 01 00 01 00 DE 6A` (200 ms), and
/// `B5 62 06 01 03 00 F0 01 00 FB 11` (NMEA GLL off), `... F0 05 00 FF 19` (NMEA VTG off).
fn ubx_frames() -> Vec<(Vec<u8>, ubx::ubx_checks::Message)> {
    use ubx::ubx_checks::{CfgMsg, CfgRate, Message};
    let rate = |meas_rate| {
        Message::CfgRate(CfgRate {
            meas_rate,
            nav_rate: 1,
            time_ref: 1,
        })
    };
    let msg = |msg_id| {
        Message::CfgMsg(CfgMsg {
            msg_class: 0xF0,
            msg_id,
            rate: 0,
        })
    };
    vec![
        (hex("B5 62 06 08 06 00 64 00 01 00 01 00 7A 12"), rate(100)),
        (hex("B5 62 06 08 06 00 E8 03 01 00 01 00 01 39"), rate(1000)),
        (hex("B5 62 06 08 06 00 C8 00 01 00 01 00 DE 6A"), rate(200)),
        (hex("B5 62 06 01 03 00 F0 01 00 FB 11"), msg(0x01)),
        (hex("B5 62 06 01 03 00 F0 05 00 FF 19"), msg(0x05)),
    ]
}

#[test]
fn ubx_frames_decode_and_encode() {
    use ubx::ubx_checks::{Header, LAYOUT, MAX_FRAME_LEN, Packet};
    let frames = ubx_frames();
    for (bytes, message) in &frames {
        let packet = Packet {
            header: Header {},
            message: *message,
        };
        assert_eq!(Packet::decode(bytes), Ok(packet), "{:?}", F(bytes));
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(bytes));
        let mut bad = bytes.clone();
        bad[bytes.len() - 2] ^= 0x01;
        assert_eq!(
            Packet::decode(&bad),
            Err(DecodeError::Frame(Reject::BadChecksum))
        );
    }
    let bytes: Vec<Vec<u8>> = frames.into_iter().map(|(b, _)| b).collect();
    let (stream, expected) = stream_of(&bytes);
    assert_stream_at_every_chunk_size::<{ ubx::ubx_checks::DECODER_BUFFER_LEN }>(
        &LAYOUT,
        &stream,
        &expected,
        |f| assert!(Packet::decode(f).is_ok()),
    );
    let interp = interpreter("ubx.toml");
    dynamic_round_trips(&interp, &bytes);
    dynamic_stream(&interp, &stream, &expected);
}

// ---- Dynamixel Protocol 1.0: the one's complement of a byte sum ----

/// Instruction packets of the ROBOTIS Dynamixel Protocol 1.0 manuals (DX/RX/AX series,
/// "Instruction Packet" examples): PING of id 1, READ_DATA of the internal temperature
/// (address 0x2B, 1 byte) of id 1, and WRITE_DATA of id 1 to address 3 (the id) from the
/// broadcast id.
fn dxl1_frames() -> Vec<(Vec<u8>, u8, dxl1::dynamixel1_checks::Message)> {
    use dxl1::dynamixel1_checks::{Message, ReadData, WriteData};
    vec![
        (hex("FF FF 01 02 01 FB"), 0x01, Message::Ping),
        (
            hex("FF FF 01 04 02 2B 01 CC"),
            0x01,
            Message::ReadData(ReadData {
                address: 0x2B,
                length: 1,
            }),
        ),
        (
            hex("FF FF FE 04 03 03 01 F6"),
            0xFE,
            Message::WriteData(WriteData {
                address: 0x03,
                value: 0x01,
            }),
        ),
    ]
}

#[test]
fn dynamixel1_frames_decode_and_encode() {
    use dxl1::dynamixel1_checks::{Header, LAYOUT, MAX_FRAME_LEN, Packet};
    let frames = dxl1_frames();
    for (bytes, id, message) in &frames {
        let packet = Packet {
            header: Header { id: *id },
            message: *message,
        };
        assert_eq!(Packet::decode(bytes), Ok(packet), "{:?}", F(bytes));
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(bytes));
    }
    let bytes: Vec<Vec<u8>> = frames.into_iter().map(|(b, _, _)| b).collect();
    let (stream, expected) = stream_of(&bytes);
    assert_stream_at_every_chunk_size::<{ dxl1::dynamixel1_checks::DECODER_BUFFER_LEN }>(
        &LAYOUT,
        &stream,
        &expected,
        |f| assert!(Packet::decode(f).is_ok()),
    );
    let interp = interpreter("dynamixel1.toml");
    dynamic_round_trips(&interp, &bytes);
    dynamic_stream(&interp, &stream, &expected);
}

// ---- iBUS: 0xFFFF minus a 16-bit byte sum ----

/// The iBUS frame of ArduPilot's RC protocol test (`ibus_bytes`, decoded there to
/// `ibus_output`: channel 3 at 1000 µs, the other thirteen at 1500 µs), and one built from it
/// with other channel values (the check is what the test asserts).
fn ibus_frames() -> Vec<(Vec<u8>, [u16; 14])> {
    let ardupilot = hex(
        "20 40 DC 05 DC 05 E8 03 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 DC 05 47 F3",
    );
    let mut channels = [1500u16; 14];
    channels[2] = 1000;
    vec![(ardupilot, channels)]
}

#[test]
fn ibus_frames_decode_and_encode() {
    use ibus::ibus_checks::{Channels, HEADER_LEN, LAYOUT, MAX_FRAME_LEN, MAX_PAYLOAD_LEN};
    use protocol_kit::Payload;
    let mut frames = ibus_frames();
    // A second frame: other channel values, sealed by generated code.
    let mut other = [0u16; 14];
    for (i, c) in other.iter_mut().enumerate() {
        *c = 1000 + 70 * i as u16;
    }
    let mut buf = [0u8; MAX_FRAME_LEN];
    buf[..2].copy_from_slice(&[0x20, 0x40]);
    Channels { channels: other }
        .to_bytes(&mut buf[HEADER_LEN..HEADER_LEN + MAX_PAYLOAD_LEN])
        .expect("fits");
    LAYOUT.seal(&mut buf).expect("seals");
    let sum: u32 = buf[..30].iter().map(|&b| u32::from(b)).sum();
    assert_eq!(u16::from_le_bytes([buf[30], buf[31]]), 0xFFFF - sum as u16);
    frames.push((buf.to_vec(), other));
    for (bytes, channels) in &frames {
        let frame = LAYOUT.parse(bytes).expect("a valid frame");
        let decoded = Channels::from_bytes(&frame[HEADER_LEN..HEADER_LEN + MAX_PAYLOAD_LEN]);
        assert_eq!(decoded.map(|c| c.channels), Ok(*channels));
        let mut out = [0u8; MAX_FRAME_LEN];
        out[..2].copy_from_slice(&[0x20, 0x40]);
        Channels {
            channels: *channels,
        }
        .to_bytes(&mut out[HEADER_LEN..HEADER_LEN + MAX_PAYLOAD_LEN])
        .expect("fits");
        LAYOUT.seal(&mut out).expect("seals");
        assert_eq!(F(&out), F(bytes));
        let mut bad = bytes.clone();
        bad[5] ^= 0x10;
        assert_eq!(
            LAYOUT.parse(&bad),
            Err(DecodeError::Frame(Reject::BadChecksum))
        );
    }
    let bytes: Vec<Vec<u8>> = frames.into_iter().map(|(b, _)| b).collect();
    let (stream, expected) = stream_of(&bytes);
    assert_stream_at_every_chunk_size::<{ ibus::ibus_checks::DECODER_BUFFER_LEN }>(
        &LAYOUT,
        &stream,
        &expected,
        |f| assert!(LAYOUT.parse(f).is_ok()),
    );
    let interp = interpreter("ibus.toml");
    dynamic_round_trips(&interp, &bytes);
    dynamic_stream(&interp, &stream, &expected);
}

// ---- MAVLink v1: CRC-16/MCRF4XX, then each message's CRC_EXTRA ----

/// The MAVLink v1 HEARTBEAT frame quoted in the ArduPilot discussion forum thread "CRC
/// calculation from the heatbeat messages" (`FE 09 4E 01 01 00 ...  1C 7F`: seq 0x4E, system
/// and component 1, type 2 quadrotor, autopilot 3 ArduPilotMega, base_mode 0x51,
/// system_status 4 active, mavlink_version 3), whose CRC holds with HEARTBEAT's CRC_EXTRA 50.
fn heartbeat() -> Vec<u8> {
    hex("FE 09 4E 01 01 00 00 00 00 00 02 03 51 04 03 1C 7F")
}

#[test]
fn mavlink_heartbeat_decodes_and_encodes_with_its_crc_extra() {
    use mav1::mavlink1_checks::{Header, Heartbeat, MAX_FRAME_LEN, Message, Packet};
    let packet = Packet {
        header: Header {
            seq: 0x4E,
            sysid: 1,
            compid: 1,
        },
        message: Message::Heartbeat(Heartbeat {
            custom_mode: 0,
            r#type: 2,
            autopilot: 3,
            base_mode: 0x51,
            system_status: 4,
            mavlink_version: 3,
        }),
    };
    let bytes = heartbeat();
    assert_eq!(Packet::decode(&bytes), Ok(packet));
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    assert_eq!(F(&buf[..n]), F(&bytes));
    // Without the extra byte, the CRC over LEN..payload alone differs from the stored one.
    let plain = crc::Crc::<u16>::new(&crc::CRC_16_MCRF4XX).checksum(&bytes[1..15]);
    assert_ne!(plain, 0x7F1C);
    let interp = interpreter("mavlink1.toml");
    dynamic_round_trips(&interp, &[bytes]);
}

/// A frame of a message id no command declares: the CRC cannot be verified without its
/// CRC_EXTRA, so the candidate is rejected as a bad check whatever extra byte (or none) was
/// folded into it, and the search resumes at the next byte: the HEARTBEAT after it is found.
#[test]
fn an_unknown_message_id_is_rejected_and_the_next_frame_found() {
    use mav1::mavlink1_checks::{DECODER_BUFFER_LEN, LAYOUT, Packet};
    let mut unknown = heartbeat();
    unknown[5] = 0x07;
    let mut candidates = Vec::new();
    let covered = unknown[1..15].to_vec();
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_MCRF4XX);
    for extra in [None, Some(0u8), Some(50), Some(0xFF)] {
        let mut d = crc.digest();
        d.update(&covered);
        if let Some(e) = extra {
            d.update(&[e]);
        }
        let mut frame = unknown.clone();
        frame[15..].copy_from_slice(&d.finalize().to_le_bytes());
        assert_eq!(
            Packet::decode(&frame),
            Err(DecodeError::Frame(Reject::BadChecksum)),
            "extra {extra:?}"
        );
        candidates.push(frame);
    }
    let interp = interpreter("mavlink1.toml");
    let codec = interp.codec();
    for frame in &candidates {
        assert!(codec.parse(0, frame).is_err(), "{:?}", F(frame));
    }
    let mut stream = Vec::new();
    for frame in &candidates {
        stream.extend_from_slice(frame);
    }
    let at = stream.len() as u64;
    stream.extend_from_slice(&heartbeat());
    let expected = vec![(at, heartbeat())];
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &stream, &expected, |f| {
        assert!(Packet::decode(f).is_ok());
    });
    dynamic_stream(&interp, &stream, &expected);
}

/// Every command folds its own CRC_EXTRA: a SYSTEM_TIME frame (id 2, extra 137) encoded by
/// generated code verifies with 137 and decodes in both codecs.
#[test]
fn each_command_folds_its_own_extra() {
    use mav1::mavlink1_checks::{Header, MAX_FRAME_LEN, Message, Packet, SystemTime};
    let packet = Packet {
        header: Header {
            seq: 7,
            sysid: 255,
            compid: 190,
        },
        message: Message::SystemTime(SystemTime {
            time_unix_usec: 1_700_000_000_000_000,
            time_boot_ms: 123_456,
        }),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    let frame = &buf[..n];
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_MCRF4XX);
    let mut d = crc.digest();
    d.update(&frame[1..n - 2]);
    d.update(&[137]);
    assert_eq!(
        u16::from_le_bytes([frame[n - 2], frame[n - 1]]),
        d.finalize()
    );
    assert_eq!(Packet::decode(frame), Ok(packet));
    let interp = interpreter("mavlink1.toml");
    dynamic_round_trips(&interp, &[frame.to_vec()]);
    let (stream, expected) = stream_of(&[heartbeat(), frame.to_vec()]);
    assert_stream_at_every_chunk_size::<{ mav1::mavlink1_checks::DECODER_BUFFER_LEN }>(
        &mav1::mavlink1_checks::LAYOUT,
        &stream,
        &expected,
        |f| assert!(Packet::decode(f).is_ok()),
    );
    dynamic_stream(&interp, &stream, &expected);
}
