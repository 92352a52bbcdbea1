//! The run-time codec (`protocol_dynamic`) on the golden vectors of a bundled spec: what the
//! generated-code tests check of the typed values, checked here of the JSON values that
//! `protocol decode` prints and `protocol encode` reads. Each test file uses part of it.
#![allow(dead_code)]

use protocol_dynamic::{Interpreter, Item, Value};
use protocol_tests::F;

/// The interpreter of `specs/NAME.toml`.
pub fn interpreter(name: &str) -> Interpreter {
    let path = format!("{}/../specs/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// One golden frame: `bytes` decode to `command` (none for a format without commands) and
/// `payload`, and the frame object of those values encodes to `bytes`.
pub fn frame(
    interp: &Interpreter,
    name: &str,
    bytes: &[u8],
    command: Option<&str>,
    payload: &serde_json::Value,
) {
    let codec = interp.codec();
    let decoded = codec
        .parse(0, bytes)
        .unwrap_or_else(|e| panic!("{name}: the codec does not decode it: {e:?}"));
    // Through the JSON text, as `protocol decode` prints it: `to_value` would widen an `f32` to
    // the `f64` of its bits (12.300000190734863 for 12.3).
    let text = serde_json::to_string(&codec.frame_value(&decoded, 0, bytes)).expect("JSON");
    let shown: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(shown["command"].as_str(), command, "{name}: command");
    assert_eq!(&shown["payload"], payload, "{name}: decoded payload");
    let mut object = serde_json::json!({ "header": {}, "payload": payload });
    if let Some(command) = command {
        object["command"] = serde_json::Value::from(command);
    }
    let object: Value = serde_json::from_value(object).expect("a frame object");
    let encoded = codec
        .encode(&object)
        .unwrap_or_else(|e| panic!("{name}: the codec does not encode it: {e}"));
    assert_eq!(F(&encoded.bytes), F(bytes), "{name}: encoded bytes");
}

/// The codec's stream decoder of the link (every command format) on `stream` at every chunk
/// size yields exactly `expected` (offset and bytes), each frame decoded.
pub fn stream(interp: &Interpreter, stream: &[u8], expected: &[(u64, Vec<u8>)]) {
    let codec = interp.codec();
    for chunk in 1..=stream.len() {
        let mut s = codec.link_stream().expect("a frame format");
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
