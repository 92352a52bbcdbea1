//! Inverted booleans (`invert = true`) on the fixture
//! `protocol-codegen/tests/features/inverted_bool.toml`: a single field, a fixed array and a
//! repeated array of active-low flags beside a plain `bool`.
//!
//! The golden frames (`tests/vectors/inverted_bool.json`, written by
//! `tests/vectors/inverted_bool.py`) pack each inverted flag as CPython `struct`'s `'?'` of
//! its negation. Each decodes in generated code and in the run-time codec to the values Python
//! packed, encodes back to its bytes in both, and a stream of them with garbage and corrupt
//! copies yields exactly the good frames at every chunk size. The C peer decodes the same
//! frames in `protocol-cli`'s `c_peer` test, which reads every vector file of a fixture.

use protocol_dynamic::{Interpreter, Value};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/inverted_bool.toml");
}
use fixture::inverted_bool::{DECODER_BUFFER_LEN, LAYOUT, MAX_FRAME_LEN, Message, Packet};

fn vectors() -> serde_json::Value {
    load_vectors("inverted_bool.json")
}

fn bools(v: &serde_json::Value) -> Vec<bool> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|b| b.as_bool().expect("a bool"))
        .collect()
}

#[test]
fn python_struct_frames_decode_to_their_flags_and_encode_back() {
    let v = vectors();
    let path = format!(
        "{}/../protocol-codegen/tests/features/inverted_bool.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let codec = interp.codec();
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 3);
    for f in frames {
        let (name, bytes, want) = (
            &f["name"],
            hex(f["hex"].as_str().expect("hex")),
            &f["fields"],
        );
        let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let Message::Status(s) = &packet.message;
        assert_eq!(s.ready, want["ready"].as_bool().expect("ready"), "{name}");
        assert_eq!(s.armed, want["armed"].as_bool().expect("armed"), "{name}");
        assert_eq!(s.lamps_on.to_vec(), bools(&want["lamps_on"]), "{name}");
        assert_eq!(
            s.ports_up.as_slice().to_vec(),
            bools(&want["ports_up"]),
            "{name}"
        );
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: generated encode");

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let payload = value.get("payload").expect("a payload");
        assert_eq!(
            payload.get("ready"),
            Some(&Value::Bool(s.ready)),
            "{name}: codec"
        );
        let encoded = codec.encode(&value).expect("the codec encodes");
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: codec encode");
    }
    // Any byte but 0 is false, as any byte but 0 is true for a plain bool.
    let odd = hex("7e0610050505050500 15");
    let Message::Status(s) = Packet::decode(&odd).expect("decodes").message;
    assert!(!s.ready && s.armed && s.lamps_on == [false; 3]);
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::decode(f).is_ok(), "{:?}", F(f));
    });
}
