//! Checks narrower than their register and checks seeded with a constant, on the feature
//! fixtures `protocol-codegen/tests/features/crc24_rtcm3.toml` and `seeded_checks.toml`.
//!
//! RTCM 3 frames (CRC-24Q, three bytes, after a 10-bit length in a header word) come from the
//! PyPI package pyrtcm 1.2.1: messages 1005 and 1006 built bit by bit from RTCM 10403.3's
//! field table, serialized by `RTCMMessage(payload=...).serialize()` (which computes the
//! CRC-24Q) and parsed back by its `RTCMReader`, which checks the CRC (it read station ids
//! 2003, 4095 and 17, ECEF X 1114104.5999 m, -2694685.473 m and 4075580.372 m, and the 1006's
//! antenna height 1.5 m). Every frame decodes and encodes back to its bytes in generated code
//! and in the run-time codec, a changed byte is a bad check, and a stream of them with
//! garbage, corrupt and truncated copies yields exactly the good frames at every chunk size.
//!
//! The seeded fixture's frames are encoded by generated code and their checks recomputed here
//! with naive loops and the `crc` crate, whose catalogue gives CRC-12/UMTS and CRC-7/MMC. The
//! frames of `check_before_payload.toml` (a payload CRC stored in the header) are assembled
//! here with the `crc` crate and compared with what generated code encodes.

use protocol_dynamic::{Interpreter, Item};
use protocol_kit::{DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex};

mod rtcm {
    protocol_kit::protocol!("../protocol-codegen/tests/features/crc24_rtcm3.toml");
}
mod seeded {
    protocol_kit::protocol!("../protocol-codegen/tests/features/seeded_checks.toml");
}

fn interpreter(spec: &str) -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/{spec}",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The pyrtcm frames: 1005 of station 2003, 1005 of station 4095, 1006 of station 17.
fn rtcm_frames() -> Vec<Vec<u8>> {
    [
        "D3 00 13 3E D7 D3 03 02 98 0E DE EF 34 F2 64 D9 3D 09 D4 BE 30 EF C6 07 C4",
        "D3 00 13 3E DF FF 03 39 B9 D7 A0 B6 36 00 CA 2B 10 08 FB 79 9B 78 D3 AA F0",
        "D3 00 15 3E E0 11 03 09 7D 3C 36 48 02 2B 6D A4 16 0B 2D F5 29 12 3A 98 2E 1E AB",
    ]
    .into_iter()
    .map(hex)
    .collect()
}

/// `frames` in a stream: garbage, then per frame a copy with a corrupt check, a copy cut
/// short (it claims bytes the next frame holds), then the frame. Returns the stream and the
/// good frames with their offsets.
fn stream_of(frames: &[Vec<u8>]) -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let mut stream = vec![0x00, 0x13, 0x37];
    let mut expected = Vec::new();
    for f in frames {
        let mut bad = f.clone();
        *bad.last_mut().expect("a frame") ^= 0x80;
        stream.extend_from_slice(&bad);
        stream.extend_from_slice(&f[..f.len() - 4]);
        expected.push((stream.len() as u64, f.clone()));
        stream.extend_from_slice(f);
    }
    stream.push(frames[0][0]);
    (stream, expected)
}

/// The run-time codec: each frame decodes and re-encodes to its bytes, a copy with a flipped
/// check bit is refused, and the stream yields exactly `expected` at every chunk size.
fn dynamic_agrees(
    interp: &Interpreter,
    frames: &[Vec<u8>],
    stream: &[u8],
    expected: &[(u64, Vec<u8>)],
) {
    let codec = interp.codec();
    for bytes in frames {
        let decoded = codec
            .parse(0, bytes)
            .unwrap_or_else(|e| panic!("{:?}: {e:?}", F(bytes)));
        let value = codec.frame_value(&decoded, 0, bytes);
        let encoded = codec.encode(&value).expect("encodes");
        assert_eq!(F(&encoded.bytes), F(bytes), "dynamic encode");
        let mut bad = bytes.clone();
        *bad.last_mut().expect("a frame") ^= 0x01;
        assert!(codec.parse(0, &bad).is_err(), "{:?} accepted", F(&bad));
    }
    for chunk in 1..=stream.len() {
        let mut s = codec.stream(0).expect("a frame format");
        let mut got = Vec::new();
        for part in stream.chunks(chunk) {
            let mut input = part;
            while let Some(item) = s.next_item(&mut input) {
                if let Item::Frame {
                    offset,
                    bytes,
                    decoded,
                } = item
                {
                    assert!(decoded.is_ok(), "chunk {chunk}: {decoded:?}");
                    got.push((offset, bytes.to_vec()));
                }
            }
        }
        assert_eq!(got, expected, "chunk size {chunk}");
    }
}

#[test]
fn rtcm3_frames_decode_and_encode_with_their_crc24q() {
    use rtcm::crc24_rtcm3::{
        DECODER_BUFFER_LEN, Header, LAYOUT, MAX_FRAME_LEN, Packet, RtcmMessage,
    };
    let frames = rtcm_frames();
    let crc24q = crc::Crc::<u32>::new(&crc::CRC_24_LTE_A);
    for bytes in &frames {
        let n = bytes.len();
        // The stored value is the catalogue CRC, big-endian in three bytes.
        let stored = u32::from_be_bytes([0, bytes[n - 3], bytes[n - 2], bytes[n - 1]]);
        assert_eq!(stored, crc24q.checksum(&bytes[..n - 3]));
        // The 10-bit length in the low bits of the word after the preamble.
        assert_eq!(
            usize::from(bytes[1] & 0x03) << 8 | usize::from(bytes[2]),
            n - 6
        );
        let packet = Packet {
            header: Header {},
            payload: RtcmMessage {
                data: protocol_kit::Bytes::from_slice(&bytes[3..n - 3]).expect("fits"),
            },
        };
        assert_eq!(Packet::decode(bytes), Ok(packet), "{:?}", F(bytes));
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..len]), F(bytes));
        for at in [3, n - 3, n - 1] {
            let mut bad = bytes.clone();
            bad[at] ^= 0x01;
            assert_eq!(
                Packet::decode(&bad),
                Err(DecodeError::Frame(Reject::BadChecksum)),
                "byte {at}"
            );
        }
    }
    let (stream, expected) = stream_of(&frames);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &stream, &expected, |f| {
        assert!(Packet::decode(f).is_ok());
    });
    dynamic_agrees(
        &interpreter("crc24_rtcm3.toml"),
        &frames,
        &stream,
        &expected,
    );
}

/// What each check of `seeded_checks.toml` holds, recomputed with naive loops and the `crc`
/// crate: the sum of the header from 0x1234 (little-endian), CRC-12/UMTS of id..payload (the
/// header sum included; big-endian), CRC-7/MMC of the payload, the XOR of every byte before it from 0xA5.
fn assert_seeded_checks(frame: &[u8]) {
    let n = frame.len();
    let payload = &frame[5..n - 4];
    let sum = frame[..3]
        .iter()
        .fold(0x1234u16, |s, &b| s.wrapping_add(u16::from(b)));
    assert_eq!(u16::from_le_bytes([frame[3], frame[4]]), sum);
    let crc12 = crc::Crc::<u16>::new(&crc::CRC_12_UMTS);
    // `id..payload` is a run of elements: the header sum between them is in it.
    let covered = &frame[1..n - 4];
    assert_eq!(
        u16::from_be_bytes([frame[n - 4], frame[n - 3]]),
        crc12.checksum(covered)
    );
    let crc7 = crc::Crc::<u8>::new(&crc::CRC_7_MMC);
    assert_eq!(frame[n - 2], crc7.checksum(payload));
    let xor = frame[..n - 1].iter().fold(0xA5u8, |x, &b| x ^ b);
    assert_eq!(frame[n - 1], xor);
}

#[test]
fn seeded_and_narrow_checks_hold_what_naive_loops_compute() {
    use seeded::seeded_checks::{
        DECODER_BUFFER_LEN, Header, LAYOUT, MAX_FRAME_LEN, Message, Move, Packet,
    };
    // The catalogue's own check values of the two narrow CRCs.
    assert_eq!(crc::CRC_12_UMTS.check, 0xDAF);
    assert_eq!(crc::CRC_7_MMC.check, 0x75);
    let packets = [
        Packet {
            header: Header {},
            message: Message::Ping,
        },
        Packet {
            header: Header {},
            message: Message::Move(Move {
                x: -300,
                y: 1200,
                speed: 0xFE,
            }),
        },
    ];
    let mut frames = Vec::new();
    for packet in &packets {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_seeded_checks(&buf[..n]);
        assert_eq!(Packet::decode(&buf[..n]), Ok(*packet));
        for at in 0..n {
            let mut bad = buf[..n].to_vec();
            bad[at] ^= 0x40;
            assert!(
                Packet::decode(&bad).is_err(),
                "byte {at} changed: {:?}",
                F(&bad)
            );
        }
        frames.push(buf[..n].to_vec());
    }
    let (stream, expected) = stream_of(&frames);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &stream, &expected, |f| {
        assert!(Packet::decode(f).is_ok());
    });
    dynamic_agrees(
        &interpreter("seeded_checks.toml"),
        &frames,
        &stream,
        &expected,
    );
}

mod before {
    protocol_kit::protocol!("../protocol-codegen/tests/features/check_before_payload.toml");
}

/// A frame of `check_before_payload.toml` assembled by hand: the payload's CRC-16/XMODEM
/// (big-endian) right after the sync, then the length, the command, their CRC-8/SMBUS, and
/// the payload.
fn assembled_before(cmd: u8, payload: &[u8]) -> Vec<u8> {
    let crc16 = crc::Crc::<u16>::new(&crc::CRC_16_XMODEM);
    let crc8 = crc::Crc::<u8>::new(&crc::CRC_8_SMBUS);
    let len = payload.len() as u8;
    let mut frame = vec![0xAA, 0x55];
    frame.extend_from_slice(&crc16.checksum(payload).to_be_bytes());
    frame.extend_from_slice(&[len, cmd, crc8.checksum(&[len, cmd])]);
    frame.extend_from_slice(payload);
    frame
}

#[test]
fn a_check_before_the_payload_is_verified_and_filled_after_it() {
    use before::check_before_payload::{
        DECODER_BUFFER_LEN, Header, LAYOUT, MAX_FRAME_LEN, Message, Move, Packet,
    };
    let cases = [
        (
            Packet {
                header: Header {},
                message: Message::Ping,
            },
            assembled_before(1, &[]),
        ),
        (
            Packet {
                header: Header {},
                message: Message::Move(Move {
                    x: -300,
                    y: 1200,
                    speed: 0xFE,
                }),
            },
            assembled_before(2, &[0xD4, 0xFE, 0xB0, 0x04, 0xFE]),
        ),
    ];
    let mut frames = Vec::new();
    for (packet, bytes) in &cases {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(
            F(&buf[..n]),
            F(bytes),
            "the encoder fills the check after the payload"
        );
        assert_eq!(Packet::decode(bytes), Ok(*packet));
        for at in 0..bytes.len() {
            let mut bad = bytes.clone();
            bad[at] ^= 0x40;
            assert!(
                Packet::decode(&bad).is_err(),
                "byte {at} changed: {:?}",
                F(&bad)
            );
        }
        frames.push(bytes.clone());
    }
    // A changed payload byte fails the check stored before it.
    let mut bad = frames[1].clone();
    bad[8] ^= 0x01;
    assert_eq!(
        Packet::decode(&bad),
        Err(DecodeError::Frame(Reject::BadChecksum))
    );
    let (stream, expected) = stream_of(&frames);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &stream, &expected, |f| {
        assert!(Packet::decode(f).is_ok());
    });
    dynamic_agrees(
        &interpreter("check_before_payload.toml"),
        &frames,
        &stream,
        &expected,
    );
}
