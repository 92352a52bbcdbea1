//! `char[N]` text fields (`protocol-codegen/tests/features/text.toml`): generated code and the
//! run-time codec keep every byte of a text (bytes after its NUL, bytes that are not UTF-8)
//! from decode to encode, show a canonical text as a string and any other as its bytes, and
//! refuse a text longer than its field.

use crate::golden;

use protocol_dynamic::{Interpreter, Value};
use protocol_kit::{EncodeError, FixedStr, Group, Payload};
use protocol_tests::F;

protocol_kit::protocol!("../protocol-codegen/tests/features/text.toml");

use text::*;

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/text.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A payload built by hand: "v1.2" padded, a hardware text with junk after its NUL and a byte
/// that is not UTF-8, two tags (one filling its 4 bytes), one extension.
fn payload() -> Vec<u8> {
    let padded = |text: &[u8], n: usize| {
        let mut b = text.to_vec();
        b.resize(n, 0);
        b
    };
    let mut p = padded(b"v1.2", 30);
    p.extend_from_slice(b"hw\xFF\0junk\0\0");
    p.extend_from_slice(b"abcd");
    p.extend_from_slice(b"x\0\0\0");
    p.extend_from_slice(&padded(b"PROT=18", 30));
    p
}

fn frame(payload: &[u8]) -> Vec<u8> {
    let mut f = vec![0xAA, payload.len() as u8, 0x01];
    f.extend_from_slice(payload);
    let sum = f.iter().fold(0u8, |a, &b| a.wrapping_add(b));
    f.push(sum);
    f
}

#[test]
fn generated_code_keeps_every_byte_of_a_text() {
    let bytes = frame(&payload());
    let packet = Packet::decode(&bytes).expect("decodes");
    let Message::Version(v) = packet.message;
    assert_eq!(v.software.as_str(), Ok("v1.2"));
    assert!(v.software.is_canonical());
    assert_eq!(v.hardware.text(), b"hw\xFF");
    assert!(v.hardware.as_str().is_err(), "not UTF-8, and no panic");
    assert!(!v.hardware.is_canonical());
    assert_eq!(v.hardware.as_bytes(), b"hw\xFF\0junk\0\0");
    assert_eq!(
        v.tags[0].as_str(),
        Ok("abcd"),
        "a text that fills its field"
    );
    assert_eq!(v.tags[1].as_str(), Ok("x"));
    assert_eq!(v.extensions.len(), 1);
    assert_eq!(v.extensions[0].text.as_str(), Ok("PROT=18"));
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    assert_eq!(F(&buf[..n]), F(&bytes), "the same bytes back");
    // Built from text: padded with NUL.
    let mut extensions = Group::new();
    extensions
        .push(Extension {
            text: FixedStr::from_text("PROT=18").expect("fits"),
        })
        .expect("room");
    let built = Version {
        software: FixedStr::from_text("v1.2").expect("fits"),
        hardware: FixedStr::from_bytes(*b"hw\xFF\0junk\0\0"),
        tags: [
            FixedStr::from_text("abcd").expect("fits"),
            FixedStr::from_text("x").expect("fits"),
        ],
        extensions,
    };
    assert_eq!(built, v);
    assert_eq!(
        FixedStr::<4>::from_text("abcde"),
        None,
        "too long for char[4]"
    );
    let mut small = [0u8; 10];
    assert!(matches!(
        built.to_bytes(&mut small),
        Err(EncodeError::BufferTooSmall { .. })
    ));
}

#[test]
fn the_codec_shows_a_canonical_text_as_a_string_and_any_other_as_its_bytes() {
    let bytes = frame(&payload());
    let hardware: Vec<u64> = b"hw\xFF\0junk\0\0".iter().map(|&b| u64::from(b)).collect();
    let expected = serde_json::json!({
        "software": "v1.2",
        "hardware": hardware,
        "tags": ["abcd", "x"],
        "extensions": [{ "text": "PROT=18" }],
    });
    golden::frame(&interpreter(), "text", &bytes, Some("VERSION"), &expected);
}

#[test]
fn the_codec_refuses_a_text_longer_than_its_field() {
    let interp = interpreter();
    let codec = interp.codec();
    let object = |hardware: serde_json::Value| -> Value {
        serde_json::from_value(serde_json::json!({
            "command": "VERSION",
            "payload": {
                "software": "v1.2",
                "hardware": hardware,
                "tags": ["abcd", "x"],
                "extensions": [],
            },
        }))
        .expect("a frame object")
    };
    let err = codec
        .encode(&object(serde_json::json!("hardware-11")))
        .expect_err("11 bytes do not fit char[10]");
    assert!(err.to_string().contains("hardware"), "{err}");
    assert!(codec.encode(&object(serde_json::json!([1, 2, 3]))).is_err());
    assert!(
        codec
            .encode(&object(serde_json::json!("hardware10")))
            .is_ok()
    );
}
