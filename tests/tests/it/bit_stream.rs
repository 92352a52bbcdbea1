//! Bit streams (`type = "bitstream"`) and signed and scaled bit members on the fixture
//! `protocol-codegen/tests/features/bit_stream.toml`: members of 1 to 38 bits read most
//! significant bit first across bytes, a 38-bit two's complement coordinate scaled to metres,
//! an enum, a scaled member with an offset, and signed and scaled members of a bitfield word.
//!
//! The golden frames (`tests/vectors/bit_stream.json`, written by `tests/vectors/bit_stream.py`)
//! are packed with CPython's `int.to_bytes`, independently of this crate. Each decodes in
//! generated code and in the run-time codec to the values Python packed, encodes back to its
//! bytes in both, and a stream of them with garbage and corrupt copies yields exactly the
//! good frames at every chunk size. Values that do not fit their members are encode errors.

use protocol_dynamic::{Interpreter, Value};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/bit_stream.toml");
}
use fixture::bit_stream::{
    DECODER_BUFFER_LEN, Header, LAYOUT, MAX_FRAME_LEN, Message, Packet, Position, Quality, Trim,
};

fn vectors() -> serde_json::Value {
    load_vectors("bit_stream.json")
}

fn int(v: &serde_json::Value, key: &str) -> i64 {
    v[key].as_i64().unwrap_or_else(|| panic!("{key}"))
}

fn float(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key}"))
}

fn check_position(p: &Position, want: &serde_json::Value, name: &str) {
    assert_eq!(i64::from(p.seq), int(want, "seq"), "{name}");
    assert_eq!(i64::from(p.number), int(want, "number"), "{name}");
    assert_eq!(i64::from(p.station), int(want, "station"), "{name}");
    assert_eq!(
        (p.x / 0.0001).round() as i64,
        int(want, "x_raw"),
        "{name}: x"
    );
    assert_eq!(p.valid, want["valid"].as_bool().expect("valid"), "{name}");
    let quality = match p.quality {
        Quality::None => 0,
        Quality::Fix => 1,
        Quality::Rtk => 4,
        Quality::Unknown(raw) => raw,
    };
    assert_eq!(i64::from(quality), int(want, "quality"), "{name}");
    assert_eq!(p.raw_y, int(want, "raw_y"), "{name}");
    assert_eq!(f64::from(p.height), float(want, "height"), "{name}");
    assert_eq!(i64::from(p.tail), int(want, "tail"), "{name}");
}

fn check_trim(t: &Trim, want: &serde_json::Value, name: &str) {
    assert_eq!(i64::from(t.pitch), int(want, "pitch"), "{name}");
    assert_eq!(f64::from(t.roll), float(want, "roll"), "{name}");
    assert_eq!(
        (f64::from(t.gain) / 0.1).round() as i64,
        int(want, "gain_raw"),
        "{name}"
    );
    assert_eq!(i64::from(t.level), int(want, "level"), "{name}");
}

#[test]
fn python_packed_frames_decode_to_their_values_and_encode_back() {
    let v = vectors();
    let path = format!(
        "{}/../protocol-codegen/tests/features/bit_stream.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let interp = Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let codec = interp.codec();
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 10);
    for f in frames {
        let name = f["name"].as_str().expect("name");
        let (bytes, want) = (hex(f["hex"].as_str().expect("hex")), &f["fields"]);
        let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        match &packet.message {
            Message::Position(p) => check_position(p, want, name),
            Message::Trim(t) => check_trim(t, want, name),
        }
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: generated encode");

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let payload = value.get("payload").expect("a payload");
        match &packet.message {
            Message::Position(p) => {
                assert_eq!(payload.get("raw_y"), Some(&Value::Int(p.raw_y)), "{name}");
                assert_eq!(payload.get("x"), Some(&Value::F64(p.x)), "{name}");
                assert_eq!(payload.get("height"), Some(&Value::F32(p.height)), "{name}");
            }
            Message::Trim(t) => {
                let pitch = Value::Int(i64::from(t.pitch));
                assert_eq!(payload.get("pitch"), Some(&pitch), "{name}");
                assert_eq!(payload.get("roll"), Some(&Value::F32(t.roll)), "{name}");
            }
        }
        let encoded = codec.encode(&value).expect("the codec encodes");
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: codec encode");
    }
}

#[test]
fn values_that_do_not_fit_their_members_are_encode_errors() {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let trim = |pitch, roll, gain| Packet {
        header: Header {},
        message: Message::Trim(Trim {
            pitch,
            roll,
            gain,
            level: 0,
        }),
    };
    assert!(trim(31, 3.75, 1.5).encode(&mut buf).is_ok());
    assert!(trim(-32, -4.0, 0.0).encode(&mut buf).is_ok());
    // Six bits of two's complement hold -32..=31; five, scaled by 0.25, -4.0..=3.75.
    assert!(trim(32, 0.0, 0.0).encode(&mut buf).is_err());
    assert!(trim(-33, 0.0, 0.0).encode(&mut buf).is_err());
    assert!(trim(0, 4.0, 0.0).encode(&mut buf).is_err());
    assert!(trim(0, -4.25, 0.0).encode(&mut buf).is_err());
    // Four unsigned bits scaled by 0.1: 0.0..=1.5, never saturated.
    assert!(trim(0, 0.0, 1.6).encode(&mut buf).is_err());
    assert!(trim(0, 0.0, -0.1).encode(&mut buf).is_err());
    let position = |number, x| Packet {
        header: Header {},
        message: Message::Position(Position {
            seq: 0,
            number,
            station: 0,
            x,
            valid: false,
            quality: Quality::Fix,
            raw_y: 0,
            height: 0.0,
            tail: 0,
        }),
    };
    assert!(position(4095, 13_743_895.347_1).encode(&mut buf).is_ok());
    assert!(position(4096, 0.0).encode(&mut buf).is_err());
    assert!(position(0, 13_743_895.347_2).encode(&mut buf).is_err());
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::decode(f).is_ok(), "{:?}", F(f));
    });
}
