//! Byte escaping between flags (`escape`) on the fixtures
//! `protocol-codegen/tests/features/escaped_hdlc.toml` (HDLC's form: 7E, 7D, 11 and 13 sent as
//! 7D and the byte XOR 0x20) and `escaped_slip.toml` (SLIP's table: C0 as DB DC, DB as DB DD).
//!
//! The golden frames (`tests/vectors/escaped_hdlc.json`, `escaped_slip.json`, written by
//! `tests/vectors/escaped.py`) are escaped by independent implementations: the PyPI packages
//! `sensirion-shdlc-driver` and `sliplib`. Each frame decodes in generated code and in the
//! run-time codec to the values the script wrote, encodes back to the same bytes in both (the
//! encoder escapes), and the streams of them, with garbage, damaged copies and frames sharing a
//! flag, yield exactly the good frames, unescaped, at every chunk size.

use protocol_dynamic::{Interpreter, Value};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/escaped_hdlc.toml");
    protocol_kit::protocol!("../protocol-codegen/tests/features/escaped_slip.toml");
}
use fixture::{escaped_hdlc as hdlc, escaped_slip as slip};

fn vectors(name: &str) -> serde_json::Value {
    let path = format!("{}/vectors/{name}.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("the vector file is JSON")
}

fn bytes_of(v: &serde_json::Value) -> Vec<u8> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|b| u8::try_from(b.as_u64().expect("a byte")).expect("a byte"))
        .collect()
}

fn int(v: &serde_json::Value) -> i64 {
    v.as_i64().expect("an integer")
}

/// The run-time codec decodes `wire` to the payload `fields` and encodes it back to `wire`.
fn codec_agrees(fixture: &str, wire: &[u8], unescaped: &[u8], fields: &serde_json::Value) {
    let path = format!(
        "{}/../protocol-codegen/tests/features/{fixture}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let codec = interp.codec();
    let decoded = codec
        .parse(0, wire)
        .unwrap_or_else(|e| panic!("{fixture}: {e:?}"));
    let value = codec.frame_value(&decoded, 0, unescaped);
    for (key, want) in fields.as_object().expect("fields") {
        let got = value
            .get("payload")
            .and_then(|p| p.get(key))
            .unwrap_or_else(|| panic!("{fixture}: no `{key}` in {value:?}"));
        match (got, want) {
            (Value::Bytes(b), serde_json::Value::Array(_)) => {
                assert_eq!(b.to_vec(), bytes_of(want), "{fixture}: codec `{key}`");
            }
            (Value::Int(i), _) => assert_eq!(*i, int(want), "{fixture}: `{key}`"),
            (Value::UInt(u), _) => {
                assert_eq!(
                    i64::try_from(*u).ok(),
                    Some(int(want)),
                    "{fixture}: `{key}`"
                );
            }
            other => panic!("{fixture}: `{key}` is {other:?}"),
        }
    }
    let encoded = codec.encode(&value).expect("the codec encodes");
    assert_eq!(
        F(&encoded.bytes),
        F(wire),
        "{fixture}: codec encode escapes"
    );
}

#[test]
fn hdlc_frames_escaped_by_the_shdlc_driver_decode_and_encode_back() {
    let v = vectors("escaped_hdlc");
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 12);
    for f in frames {
        let name = f["name"].as_str().expect("name");
        let wire = hex(f["hex"].as_str().expect("hex"));
        let unescaped = hex(f["unescaped"].as_str().expect("unescaped"));
        let packet = hdlc::Packet::decode(&wire).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(
            i64::from(packet.header.address),
            int(&f["address"]),
            "{name}"
        );
        let fields = &f["fields"];
        match (&packet.message, f["command"].as_str()) {
            (hdlc::Message::Ping, Some("PING")) => {}
            (hdlc::Message::Set(s), Some("SET")) => {
                assert_eq!(i64::from(s.value), int(&fields["value"]), "{name}");
                assert_eq!(i64::from(s.flags), int(&fields["flags"]), "{name}");
            }
            (hdlc::Message::Data(d), Some("DATA")) => {
                assert_eq!(d.bytes.as_slice(), bytes_of(&fields["bytes"]), "{name}");
            }
            (m, c) => panic!("{name}: decoded {m:?}, the script wrote {c:?}"),
        }
        assert_eq!(packet.encoded_len(), wire.len(), "{name}: encoded_len");
        let mut buf = [0u8; 2 * hdlc::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&wire), "{name}: generated encode escapes");
        let mut short = vec![0u8; wire.len() - 1];
        assert!(packet.encode(&mut short).is_err(), "{name}: a short buffer");
        assert_eq!(hdlc::Packet::from_frame(&unescaped), Ok(packet), "{name}");
        codec_agrees("escaped_hdlc", &wire, &unescaped, fields);
    }
}

#[test]
fn slip_frames_escaped_by_sliplib_decode_and_encode_back() {
    let v = vectors("escaped_slip");
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 12);
    for f in frames {
        let name = f["name"].as_str().expect("name");
        let wire = hex(f["hex"].as_str().expect("hex"));
        let unescaped = hex(f["unescaped"].as_str().expect("unescaped"));
        let packet = slip::Packet::decode(&wire).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let fields = &f["fields"];
        match (&packet.message, f["command"].as_str()) {
            (slip::Message::Hello, Some("HELLO")) => {}
            (slip::Message::Reading(r), Some("READING")) => {
                assert_eq!(i64::from(r.sensor), int(&fields["sensor"]), "{name}");
                assert_eq!(i64::from(r.value), int(&fields["value"]), "{name}");
            }
            (slip::Message::Text(t), Some("TEXT")) => {
                assert_eq!(t.text.as_slice(), bytes_of(&fields["text"]), "{name}");
            }
            (m, c) => panic!("{name}: decoded {m:?}, the script wrote {c:?}"),
        }
        assert_eq!(packet.encoded_len(), wire.len(), "{name}: encoded_len");
        let mut buf = [0u8; 2 * slip::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&wire), "{name}: generated encode escapes");
        codec_agrees("escaped_slip", &wire, &unescaped, fields);
    }
}

fn expected(stream: &serde_json::Value) -> Vec<(u64, Vec<u8>)> {
    stream["expected_frames"]
        .as_array()
        .expect("expected frames")
        .iter()
        .map(|f| {
            let offset = f["offset"].as_u64().expect("offset");
            (offset, hex(f["hex"].as_str().expect("hex")))
        })
        .collect()
}

#[test]
fn streams_yield_exactly_the_good_frames_at_every_chunk_size() {
    for s in vectors("escaped_hdlc")["streams"]
        .as_array()
        .expect("streams")
    {
        let bytes = hex(s["hex"].as_str().expect("hex"));
        assert_stream_at_every_chunk_size::<{ hdlc::DECODER_BUFFER_LEN }>(
            &hdlc::LAYOUT,
            &bytes,
            &expected(s),
            |f| assert!(hdlc::Packet::from_frame(f).is_ok(), "{:?}", F(f)),
        );
    }
    for s in vectors("escaped_slip")["streams"]
        .as_array()
        .expect("streams")
    {
        let bytes = hex(s["hex"].as_str().expect("hex"));
        assert_stream_at_every_chunk_size::<{ slip::DECODER_BUFFER_LEN }>(
            &slip::LAYOUT,
            &bytes,
            &expected(s),
            |f| assert!(slip::Packet::from_frame(f).is_ok(), "{:?}", F(f)),
        );
    }
}

#[test]
fn a_damaged_escape_is_refused_by_both_decoders() {
    let v = vectors("escaped_slip");
    let mut wire = hex(v["frames"][1]["hex"].as_str().expect("hex"));
    // An escape byte followed by a byte that is no substitute.
    wire[2] = 0xDB;
    wire[3] = 0x01;
    assert!(slip::Packet::decode(&wire).is_err());
    let path = format!(
        "{}/../protocol-codegen/tests/features/escaped_slip.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).expect("loads");
    assert!(interp.codec().parse(0, &wire).is_err());
}
