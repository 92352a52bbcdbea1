//! Variable-length arrays of primitives, NUL-terminated text and checks inside a payload
//! (`protocol-codegen/tests/features/payload_types.toml`): payloads built by hand from the
//! spec's rules (a check value computed here with the `crc` crate over the prefix and the
//! covered bytes) decode to their values and encode to their bytes, in generated code and in
//! the run-time codec, and every rule it breaks is the same error in both.

use crate::golden;

use protocol_dynamic::{DecodeIssue, Interpreter, Value};
use protocol_kit::{DecodeError, EncodeError, Group, NulStr};
use protocol_tests::F;
use serde_json::json;

protocol_kit::protocol!("../protocol-codegen/tests/features/payload_types.toml");

use payload_types::*;

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/payload_types.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn frame(command: u8, payload: &[u8]) -> Vec<u8> {
    let mut f = vec![0xAA, payload.len() as u8, command];
    f.extend_from_slice(payload);
    let sum = f.iter().fold(0u8, |a, &b| a.wrapping_add(b));
    f.push(sum);
    f
}

/// Count 2, values -2 and 300 (little-endian), the name "abc" and its NUL, modes RUN, IDLE.
const READINGS: &[u8] = &[2, 0xFE, 0xFF, 0x2C, 0x01, b'a', b'b', b'c', 0, 1, 0];

/// Source 7, then levels 1.5 V and 12.3 V as big-endian tenths.
const LEVELS: &[u8] = &[7, 0x00, 0x0F, 0x00, 0x7B];

/// Target 0x11 and its xor, code 0x22, data 1 2 3, then the CRC-16 (poly 0x1021, init
/// 0xFFFF: CRC-16/IBM-3740) of the command id 0x03 and code..data, big-endian.
fn sealed(target: u8, data: &[u8]) -> Vec<u8> {
    let mut p = vec![target, target, 0x22];
    p.extend_from_slice(data);
    let mut covered = vec![0x03];
    covered.extend_from_slice(&p[2..]);
    let crc = crc::Crc::<u16>::new(&crc::CRC_16_IBM_3740).checksum(&covered);
    p.extend_from_slice(&crc.to_be_bytes());
    p
}

fn encode(packet: &Packet) -> Result<Vec<u8>, EncodeError> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf)?;
    Ok(buf[..n].to_vec())
}

#[test]
fn every_payload_decodes_to_its_values_and_encodes_to_its_bytes() {
    let readings = Readings {
        count: 2,
        values: Group::from_slice(&[-2, 300]).expect("fits"),
        name: NulStr::from_text("abc").expect("fits"),
        modes: Group::from_slice(&[Mode::Run, Mode::Idle]).expect("fits"),
    };
    let levels = Levels {
        source: 7,
        levels: Group::from_slice(&[1.5, 12.3]).expect("fits"),
    };
    let sealed_value = Sealed {
        target: 0x11,
        code: 0x22,
        data: protocol_kit::Bytes::from_slice(&[1, 2, 3]).expect("fits"),
    };
    let cases = [
        (frame(1, READINGS), Message::Readings(readings)),
        (frame(2, LEVELS), Message::Levels(levels)),
        (
            frame(3, &sealed(0x11, &[1, 2, 3])),
            Message::Sealed(sealed_value),
        ),
    ];
    for (bytes, message) in cases {
        let packet = Packet {
            header: Header {},
            message,
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{message:?}");
        let encoded = encode(&packet).expect("encodes");
        assert_eq!(F(&encoded), F(&bytes), "{message:?}");
    }
    // The run-time codec: the same bytes, shown as JSON values.
    let interp = interpreter();
    golden::frame(
        &interp,
        "readings",
        &frame(1, READINGS),
        Some("READINGS"),
        &json!({ "count": 2, "values": [-2, 300], "name": "abc", "modes": ["RUN", "IDLE"] }),
    );
    golden::frame(
        &interp,
        "levels",
        &frame(2, LEVELS),
        Some("LEVELS"),
        &json!({ "source": 7, "levels": [1.5, 12.3] }),
    );
    golden::frame(
        &interp,
        "sealed",
        &frame(3, &sealed(0x11, &[1, 2, 3])),
        Some("SEALED"),
        &json!({ "target": 0x11, "code": 0x22, "data": "010203" }),
    );
    // Empty arrays, an empty text, no data.
    golden::frame(
        &interp,
        "empty",
        &frame(1, &[0, 0]),
        Some("READINGS"),
        &json!({ "count": 0, "values": [], "name": "", "modes": [] }),
    );
    golden::frame(
        &interp,
        "no data",
        &frame(3, &sealed(0x00, &[])),
        Some("SEALED"),
        &json!({ "target": 0, "code": 0x22, "data": "" }),
    );
}

/// The error of the generated decoder and of the run-time codec on `bytes`.
fn both_errors(bytes: &[u8]) -> (Option<DecodeError>, Option<DecodeIssue>) {
    let interp = interpreter();
    let dynamic = interp.codec().parse(0, bytes).err();
    (Packet::decode(bytes).err(), dynamic)
}

fn assert_both(bytes: &[u8], expected: DecodeError) {
    let (generated, dynamic) = both_errors(bytes);
    assert_eq!(generated, Some(expected), "generated");
    match dynamic {
        // The codec names places in its own errors; a runtime error it passes on names none.
        Some(DecodeIssue::Frame(e)) => assert_eq!(e, expected.without_place(), "run-time codec"),
        Some(DecodeIssue::PayloadLength {
            expected: e,
            actual,
            ..
        }) => assert_eq!(
            DecodeError::PayloadLength {
                expected: e,
                actual
            },
            expected,
            "run-time codec"
        ),
        other => panic!("run-time codec: {other:?}, expected {expected:?}"),
    }
}

#[test]
fn a_bad_count_a_missing_nul_an_overflow_and_a_wrong_check_are_errors() {
    // A count above the arrays' most elements.
    let mut p = READINGS.to_vec();
    p[0] = 9;
    assert_both(
        &frame(1, &p),
        DecodeError::SizeMismatch {
            place: protocol_kit::error::Place::new("READINGS", "Readings.values"),
        },
    );
    // A count the bytes do not hold: the payload ends early (shorter than its struct).
    let mut p = READINGS.to_vec();
    p[0] = 3;
    assert_both(
        &frame(1, &p),
        DecodeError::PayloadLength {
            expected: 2,
            actual: 11,
        },
    );
    // A name without its NUL before the payload ends.
    assert_both(
        &frame(1, &[0, b'a', b'b']),
        DecodeError::Unterminated {
            place: protocol_kit::error::Place::new("READINGS", "Readings.name"),
        },
    );
    // A name of 17 bytes (the most is 16).
    let mut p = vec![0u8];
    p.extend_from_slice(&[b'x'; 17]);
    p.push(0);
    assert_both(
        &frame(1, &p),
        DecodeError::Unterminated {
            place: protocol_kit::error::Place::new("READINGS", "Readings.name"),
        },
    );
    // 11 levels (the most is 10): the payload is longer than the struct's largest size.
    let mut p = vec![7u8];
    p.extend_from_slice(&[0; 22]);
    assert_both(
        &frame(2, &p),
        DecodeError::PayloadLength {
            expected: 21,
            actual: 23,
        },
    );
    // A wrong CRC, and a wrong sum over one field.
    let mut p = sealed(0x11, &[1, 2, 3]);
    let n = p.len();
    p[n - 1] ^= 0x80;
    assert_both(
        &frame(3, &p),
        DecodeError::PayloadCheck {
            place: protocol_kit::error::Place::new("SEALED", ""),
        },
    );
    let mut p = sealed(0x11, &[1, 2, 3]);
    p[1] = 0x12;
    assert_both(
        &frame(3, &p),
        DecodeError::PayloadCheck {
            place: protocol_kit::error::Place::new("SEALED", ""),
        },
    );
    // The CRC alone, no room for data: truncated is a payload of the wrong length.
    assert_both(
        &frame(3, &[0x11, 0x11, 0x22, 0x00]),
        DecodeError::PayloadLength {
            expected: 5,
            actual: 4,
        },
    );
}

#[test]
fn a_value_that_does_not_fit_is_an_encode_error_never_cut() {
    // Arrays whose length is not the count.
    let readings = Readings {
        count: 3,
        values: Group::from_slice(&[1, 2]).expect("fits"),
        name: NulStr::new(),
        modes: Group::from_slice(&[Mode::Run, Mode::Run, Mode::Run]).expect("fits"),
    };
    let packet = Packet {
        header: Header {},
        message: Message::Readings(readings),
    };
    assert_eq!(
        encode(&packet),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::new("READINGS", "Readings.values")
        })
    );
    assert_eq!(NulStr::<16>::from_text(&"x".repeat(17)), None);
    // The run-time codec refuses the same values, and texts a `NulStr` cannot hold.
    let interp = interpreter();
    let codec = interp.codec();
    let object = |payload: serde_json::Value| -> Value {
        serde_json::from_value(json!({ "command": "READINGS", "payload": payload }))
            .expect("a frame object")
    };
    for bad in [
        json!({ "count": 3, "values": [1, 2], "name": "", "modes": ["RUN", "RUN", "RUN"] }),
        json!({ "count": 9, "values": vec![0; 9], "name": "", "modes": vec!["RUN"; 9] }),
        json!({ "count": 0, "values": [], "name": "x".repeat(17), "modes": [] }),
        json!({ "count": 0, "values": [], "name": "a\u{0}b", "modes": [] }),
    ] {
        assert!(codec.encode(&object(bad.clone())).is_err(), "{bad}");
    }
    let levels: Value = serde_json::from_value(
        json!({ "command": "LEVELS", "payload": { "source": 1, "levels": vec![0.0; 11] } }),
    )
    .expect("a frame object");
    assert!(codec.encode(&levels).is_err(), "11 levels");
}
