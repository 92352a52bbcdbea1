//! Number formats on the fixture `protocol-codegen/tests/features/number_formats.toml`: floats
//! scaled on the wire, integers of 40, 48 and 56 bits, and IEEE 754 half floats.
//!
//! The golden frames (`tests/vectors/number_formats.json`, written by
//! `tests/vectors/number_formats.py`) are packed by CPython's `struct` module (`'<e'`/`'>e'`
//! for halves, `'<f'`, `'>f'`, `'<d'`) and `int.to_bytes` (40-, 48- and 56-bit integers), with
//! a CRC from `binascii.crc_hqx`. Each decodes in generated code and in the run-time codec to
//! what Python packed (a scaled value to `raw * scale + offset`), encodes back to its bytes in
//! both, and a stream of them with garbage and corrupt copies yields exactly the good frames
//! at every chunk size. The C peer decodes the same frames in `protocol-cli`'s `c_peer` test,
//! which reads every vector file of a fixture. Values a width cannot carry (a 41-bit value in
//! `u40`, 65520 in a half, which Python's `struct` refuses too) are encode errors in both.

use protocol_dynamic::{Interpreter, Value};
use protocol_kit::EncodeError;
use protocol_kit::error::Place;
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/number_formats.toml");
}
use fixture::number_formats::{
    DECODER_BUFFER_LEN, LAYOUT, MAX_FRAME_LEN, Message, Packet, Station,
};

fn vectors() -> serde_json::Value {
    load_vectors("number_formats.json")
}

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/number_formats.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `(name, bytes, wire values)` of every golden frame.
fn frames() -> Vec<(String, Vec<u8>, serde_json::Value)> {
    vectors()["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .map(|f| {
            let name = f["name"].as_str().expect("a name").to_string();
            (
                name,
                hex(f["hex"].as_str().expect("hex")),
                f["wire"].clone(),
            )
        })
        .collect()
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

fn int(v: &serde_json::Value) -> i64 {
    v.as_i64().unwrap_or_else(|| panic!("an integer: {v}"))
}

/// `x` is `want` to within a few units in the last place of an `f64`: the runtime divides by
/// `1 / scale` where Python multiplies by `scale`.
fn near(x: f64, want: f64, what: &str) {
    assert!(
        (x - want).abs() <= 4.0 * f64::EPSILON * want.abs().max(1.0),
        "{what}: {x} != {want}"
    );
}

/// A half that Python wrote as a string (JSON has no infinities or NaN), or a number.
fn half(v: &serde_json::Value) -> f32 {
    match v.as_str() {
        Some("inf") => f32::INFINITY,
        Some("-inf") => f32::NEG_INFINITY,
        Some("NaN") => f32::NAN,
        Some("-0.0") => -0.0,
        Some(other) => panic!("{other}"),
        None => num(v) as f32,
    }
}

fn same_half(x: f32, want: f32, what: &str) {
    assert!(
        x.to_bits() == want.to_bits() || (x.is_nan() && want.is_nan()),
        "{what}: {x} != {want}"
    );
}

/// What generated code decoded is what Python packed.
fn check_values(name: &str, message: &Message, wire: &serde_json::Value) {
    match message {
        Message::ScaledFloats(s) => {
            near(s.speed, num(&wire["speed"]) * 0.01, "speed");
            near(
                s.temperature,
                num(&wire["temperature"]) * 0.1 - 40.0,
                "temperature",
            );
            near(s.latitude, num(&wire["latitude"]) * 1e-7, "latitude");
            assert_eq!(f64::from(s.gain), num(&wire["gain"]) * 4.0, "gain");
            near(s.trim, num(&wire["trim"]) * 0.5, "trim");
        }
        Message::WideInts(w) => {
            assert_eq!(w.timestamp, int(&wire["timestamp"]) as u64);
            assert_eq!(w.position, int(&wire["position"]));
            let odometer = wire["odometer"].as_u64().expect("u56") as f64;
            near(w.odometer, odometer * 0.001, "odometer");
            near(w.offset, int(&wire["offset"]) as f64 * 0.5 + 10.0, "offset");
            let history: Vec<i64> = wire["history"]
                .as_array()
                .expect("history")
                .iter()
                .map(int)
                .collect();
            assert_eq!(w.history.to_vec(), history);
            let station = match int(&wire["station"]) {
                0xFF_FFFF_FFFF => Station::Field,
                _ => Station::Home,
            };
            assert_eq!(w.station, station);
        }
        Message::Halves(h) => {
            let values = wire.get("read_back").unwrap_or(wire);
            same_half(h.throttle, half(&values["throttle"]), "throttle");
            let attitude = values["attitude"].as_array().expect("attitude");
            for (i, (x, want)) in h.attitude.iter().zip(attitude).enumerate() {
                same_half(*x, half(want), &format!("{name}: attitude[{i}]"));
            }
        }
    }
}

#[test]
fn python_struct_frames_decode_to_their_values_and_encode_back() {
    let frames = frames();
    assert_eq!(frames.len(), 7);
    let codec_owner = interpreter();
    let codec = codec_owner.codec();
    for (name, bytes, wire) in &frames {
        let packet = Packet::decode(bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        check_values(name, &packet.message, wire);
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(bytes), "{name}: generated encode");

        let decoded = codec
            .parse(0, bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, bytes);
        let encoded = codec.encode(&value).expect("the codec encodes");
        assert_eq!(F(&encoded.bytes), F(bytes), "{name}: codec encode");
    }
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::decode(f).is_ok(), "{:?}", F(f));
    });
}

/// Replaces `field` of the payload of `frame` (a decoded frame's value) by `value`.
fn with_payload_field(frame: &Value, field: &str, value: Value) -> Value {
    let mut frame = frame.clone();
    let Value::Struct(fields) = &mut frame else {
        panic!("a frame is an object")
    };
    let Some(Value::Struct(mut payload)) = fields.get("payload").cloned() else {
        panic!("the frame has a payload: {fields:?}")
    };
    payload.insert(field, value);
    fields.insert("payload", Value::Struct(payload));
    frame
}

#[test]
fn values_a_width_cannot_carry_are_encode_errors_never_truncated() {
    let frames = frames();
    let wide = &frames
        .iter()
        .find(|f| f.0 == "wide_ints")
        .expect("wide_ints")
        .1;
    let halves = &frames.iter().find(|f| f.0 == "halves").expect("halves").1;
    let mut buf = [0u8; MAX_FRAME_LEN];
    let place = |field| Place::new("WIDE_INTS", field);

    let mut p = Packet::decode(wide).expect("decodes");
    let Message::WideInts(w) = &mut p.message else {
        panic!()
    };
    w.timestamp = 1 << 40;
    assert_eq!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: place("WideInts.timestamp")
        })
    );
    let Message::WideInts(w) = &mut p.message else {
        panic!()
    };
    w.timestamp = 0;
    w.history[0] = 1 << 55;
    assert_eq!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: place("WideInts.history")
        })
    );

    // 65520 rounds beyond the largest half: Python's struct raises OverflowError for it.
    let mut p = Packet::decode(halves).expect("decodes");
    let Message::Halves(h) = &mut p.message else {
        panic!()
    };
    h.throttle = 65520.0;
    assert!(matches!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange { .. })
    ));
    let Message::Halves(h) = &mut p.message else {
        panic!()
    };
    h.throttle = 65519.0;
    assert!(p.encode(&mut buf).is_ok(), "65519 rounds to 65504");

    let codec_owner = interpreter();
    let codec = codec_owner.codec();
    let decoded = codec.parse(0, wide).expect("decodes");
    let value = codec.frame_value(&decoded, 0, wide);
    for (field, bad, named) in [
        ("timestamp", Value::UInt(1 << 40), "u40"),
        ("position", Value::Int(-(1 << 47) - 1), "i48"),
    ] {
        let e = codec
            .encode(&with_payload_field(&value, field, bad))
            .expect_err("the codec refuses it");
        assert!(e.to_string().contains(named), "{field}: {e}");
    }
    let decoded = codec.parse(0, halves).expect("decodes");
    let value = codec.frame_value(&decoded, 0, halves);
    let e = codec
        .encode(&with_payload_field(&value, "throttle", Value::F64(65520.0)))
        .expect_err("the codec refuses it");
    assert!(e.to_string().contains("f16"), "{e}");
}
