//! Text without a terminator (`type = "str"`) on the fixture
//! `protocol-codegen/tests/features/unterminated_text.toml`: to the end of the payload, of the
//! length an earlier field states, and to the end but a check after it.
//!
//! The golden frames (`tests/vectors/unterminated_text.json`, written by
//! `tests/vectors/unterminated_text.py`) are the texts' bytes as CPython wrote them, a NUL and
//! invalid UTF-8 among them. Each decodes in generated code and in the run-time codec to the
//! text Python wrote, encodes back to its bytes in both, and a stream of them with garbage
//! and corrupt copies yields exactly the good frames at every chunk size. The C peer decodes
//! the same frames in `protocol-cli`'s `c_peer` test, which reads every vector file of a
//! fixture.

use protocol_dynamic::{Interpreter, Value};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/unterminated_text.toml");
}
use fixture::unterminated_text::{DECODER_BUFFER_LEN, LAYOUT, MAX_FRAME_LEN, Message, Packet};

fn vectors() -> serde_json::Value {
    load_vectors("unterminated_text.json")
}

/// A text's bytes as the vector file gives them: a string, or the array of its bytes.
fn text_bytes(v: &serde_json::Value) -> Vec<u8> {
    match v {
        serde_json::Value::String(s) => s.as_bytes().to_vec(),
        serde_json::Value::Array(items) => items
            .iter()
            .map(|b| b.as_u64().expect("a byte") as u8)
            .collect(),
        other => panic!("not a text: {other}"),
    }
}

/// The run-time codec's value of the same text.
fn codec_text(bytes: &[u8]) -> Value {
    match std::str::from_utf8(bytes) {
        Ok(s) => Value::from(s.to_string()),
        Err(_) => Value::Array(bytes.iter().map(|&b| Value::UInt(u64::from(b))).collect()),
    }
}

#[test]
fn python_frames_decode_to_their_texts_and_encode_back() {
    let v = vectors();
    let path = format!(
        "{}/../protocol-codegen/tests/features/unterminated_text.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let codec = interp.codec();
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 8);
    for f in frames {
        let (name, bytes, want) = (
            &f["name"],
            hex(f["hex"].as_str().expect("hex")),
            &f["fields"],
        );
        let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let (key, text) = match &packet.message {
            Message::Log(m) => {
                assert_eq!(u64::from(m.level), want["level"].as_u64().expect("level"));
                ("text", m.text.text().to_vec())
            }
            Message::Named(m) => {
                assert_eq!(i64::from(m.value), want["value"].as_i64().expect("value"));
                assert_eq!(usize::from(m.name_size), m.name.len(), "{name}");
                ("name", m.name.text().to_vec())
            }
            Message::Note(m) => ("note", m.note.text().to_vec()),
        };
        assert_eq!(text, text_bytes(&want[key]), "{name}: generated decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: generated encode");

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let payload = value.get("payload").expect("a payload");
        assert_eq!(payload.get(key), Some(&codec_text(&text)), "{name}: codec");
        let encoded = codec.encode(&value).expect("the codec encodes");
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: codec encode");
    }
}

#[test]
fn a_text_longer_than_max_is_the_payload_of_the_wrong_length() {
    // LOG with 65 bytes of text: one more than `max`.
    let mut payload = vec![0x06];
    payload.extend([b'x'; 65]);
    let mut frame = vec![0x7E, payload.len() as u8, 0x01];
    frame.extend(&payload);
    let xor = frame[2..].iter().fold(0, |a, b| a ^ b);
    frame.push(xor);
    assert!(Packet::decode(&frame).is_err());
    // NAMED stating more bytes than `max`.
    let frame = {
        let mut f = vec![0x7E, 3, 0x02, 17, 0, 0];
        let xor = f[2..].iter().fold(0, |a, b| a ^ b);
        f.push(xor);
        f
    };
    assert!(Packet::decode(&frame).is_err());
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::decode(f).is_ok(), "{:?}", F(f));
    });
}
