//! Fields a mask announces on the fixture `protocol-codegen/tests/features/mask_fields.toml`:
//! values present when a bit of an earlier flags field is set (`when`), anywhere in the
//! payload, and an array of one element per set bit of a channel mask (`mask`).
//!
//! The golden frames (`tests/vectors/mask_fields.json`, written by
//! `tests/vectors/mask_fields.py`) are packed by CPython's `struct` module with a CRC from
//! `binascii.crc_hqx`: each group of fields only when its flag bit is set, one channel value
//! per set bit of the mask. Each decodes in generated code and in the run-time codec to what
//! Python packed (`null` for a group that is absent), encodes back to its bytes in both, and a
//! stream of them with garbage and corrupt copies yields exactly the good frames at every
//! chunk size. A value whose presence or count disagrees with its mask is an encode error in
//! both codecs. The C peer decodes the same frames in `protocol-cli`'s `c_peer` test, which
//! reads every vector file of a fixture.

use protocol_dynamic::{Codec, Interpreter};
use protocol_kit::error::Place;
use protocol_kit::{DecodeError, EncodeError, Group};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/mask_fields.toml");
}
use fixture::mask_fields::{
    CrankRevolutions, DECODER_BUFFER_LEN, LAYOUT, MAX_FRAME_LEN, Message, Packet,
};

fn vectors() -> serde_json::Value {
    load_vectors("mask_fields.json")
}

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/mask_fields.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `(name, bytes, fields)` of every golden frame.
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
                f["fields"].clone(),
            )
        })
        .collect()
}

fn frame(name: &str) -> Vec<u8> {
    frames()
        .into_iter()
        .find(|f| f.0 == name)
        .unwrap_or_else(|| panic!("no frame {name}"))
        .1
}

/// The JSON of a crank revolution group, as Python wrote it.
fn crank_json(c: &Option<CrankRevolutions>) -> serde_json::Value {
    match c {
        None => serde_json::Value::Null,
        Some(c) => serde_json::json!({
            "cumulative_crank_revolutions": c.cumulative_crank_revolutions,
            "last_crank_event_time": f64::from(c.last_crank_event_time),
        }),
    }
}

/// The values of a generated message as the vector file writes them.
fn generated_json(m: &Message) -> serde_json::Value {
    match m {
        Message::ControlData(c) => serde_json::json!({
            "command": c.command,
            "reply_id": c.reply_id,
            "rssi": c.rssi,
            "frame_losses": c.frame_losses,
            "channel_mask": c.channel_mask,
            "channels": c.channels.as_slice(),
        }),
        Message::CscMeasurement(c) => serde_json::json!({
            "flags": c.flags,
            "wheel": c.wheel.map(|w| serde_json::json!({
                "cumulative_wheel_revolutions": w.cumulative_wheel_revolutions,
                "last_wheel_event_time": f64::from(w.last_wheel_event_time),
            })),
            "crank": crank_json(&c.crank),
        }),
        Message::CyclingPower(p) => serde_json::json!({
            "flags": p.flags,
            "instantaneous_power": p.instantaneous_power,
            "pedal_power_balance": p.pedal_power_balance.map(f64::from),
            "accumulated_torque": p.accumulated_torque.map(f64::from),
            "wheel_revolutions": p.wheel_revolutions,
            "last_wheel_event_time": p.last_wheel_event_time.map(f64::from),
            "crank": crank_json(&p.crank),
        }),
    }
}

/// The run-time codec's payload of `bytes` as JSON, and its encoding of the whole frame.
fn codec_json(codec: &Codec<'_>, bytes: &[u8]) -> (serde_json::Value, Vec<u8>) {
    let decoded = codec.parse(0, bytes).expect("the codec decodes");
    let value = codec.frame_value(&decoded, 0, bytes);
    let payload = value.get("payload").expect("a payload");
    let json = serde_json::to_value(payload).expect("JSON");
    let encoded = codec.encode(&value).expect("the codec encodes");
    (json, encoded.bytes)
}

#[test]
fn python_struct_frames_decode_to_their_fields_and_encode_back() {
    let interp = interpreter();
    let codec = interp.codec();
    let frames = frames();
    assert_eq!(frames.len(), 13);
    for (name, bytes, want) in &frames {
        let packet = Packet::decode(bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(generated_json(&packet.message), *want, "{name}: generated");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(F(&buf[..n]), F(bytes), "{name}: generated encode");

        let (json, encoded) = codec_json(&codec, bytes);
        assert_eq!(json, *want, "{name}: codec");
        assert_eq!(F(&encoded), F(bytes), "{name}: codec encode");
    }
}

#[test]
fn a_value_that_disagrees_with_its_mask_is_an_encode_error_in_both_codecs() {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let place = |command, field| Place::new(command, field);

    // A crank group given while bit 1 of the flags is clear.
    let mut p = Packet::decode(&frame("csc_wheel")).expect("decodes");
    let Message::CscMeasurement(c) = &mut p.message else {
        panic!("a CSC measurement")
    };
    c.crank = Some(CrankRevolutions::default());
    assert_eq!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: place("CSC_MEASUREMENT", "CscMeasurement.crank")
        })
    );
    // Absent while its bit says present.
    let Message::CscMeasurement(c) = &mut p.message else {
        panic!("a CSC measurement")
    };
    c.crank = None;
    c.wheel = None;
    assert_eq!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: place("CSC_MEASUREMENT", "CscMeasurement.wheel")
        })
    );
    // The flags set to agree: it encodes, and decodes back to the same message.
    let Message::CscMeasurement(c) = &mut p.message else {
        panic!("a CSC measurement")
    };
    c.flags = 0;
    let n = p.encode(&mut buf).expect("encodes");
    assert_eq!(Packet::decode(&buf[..n]).expect("decodes"), p);

    // Three channel values under a mask of four bits.
    let mut p = Packet::decode(&frame("four_channels")).expect("decodes");
    let Message::ControlData(c) = &mut p.message else {
        panic!("control data")
    };
    c.channels = Group::from_slice(&[1, 2, 3]).expect("fits");
    assert_eq!(
        p.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: place("CONTROL_DATA", "ControlData.channels")
        })
    );

    let interp = interpreter();
    let codec = interp.codec();
    let crank = serde_json::json!({
        "cumulative_crank_revolutions": 1,
        "last_crank_event_time": 0.0,
    });
    for (name, key, wrong) in [
        ("csc_wheel", "crank", crank),
        ("csc_both", "crank", serde_json::Value::Null),
        (
            "four_channels",
            "channels",
            serde_json::json!([1, 2, 3, 4, 5]),
        ),
    ] {
        let bytes = frame(name);
        let decoded = codec.parse(0, &bytes).expect("decodes");
        let value = codec.frame_value(&decoded, 0, &bytes);
        let mut json = serde_json::to_value(&value).expect("JSON");
        json["payload"][key] = wrong;
        let changed: protocol_dynamic::Value = serde_json::from_value(json).expect("a value");
        let err = codec.encode(&changed).expect_err(name);
        assert!(err.to_string().contains(key), "{name}: {err}");
    }
}

#[test]
fn a_mask_that_announces_missing_bytes_fails_alike() {
    let interp = interpreter();
    let codec = interp.codec();
    // Channel data whose mask names a fifth channel the payload does not carry: its CRC is
    // recomputed, so only the payload is wrong.
    let mut bytes = frame("four_channels");
    bytes[9] = 0x1F;
    let n = bytes.len();
    let crc = crc16_xmodem(&bytes[..n - 2]);
    bytes[n - 2..].copy_from_slice(&crc.to_be_bytes());
    let generated = Packet::decode(&bytes);
    assert!(
        matches!(
            generated,
            Err(DecodeError::Truncated { .. } | DecodeError::PayloadLength { .. })
        ),
        "{generated:?}"
    );
    assert!(codec.parse(0, &bytes).is_err());
    // Bit 1 cleared in a CSC measurement that carries crank data: two bytes too many.
    let mut bytes = frame("csc_both");
    bytes[3] = 0x01;
    let n = bytes.len();
    let crc = crc16_xmodem(&bytes[..n - 2]);
    bytes[n - 2..].copy_from_slice(&crc.to_be_bytes());
    assert!(matches!(
        Packet::decode(&bytes),
        Err(DecodeError::PayloadLength { .. })
    ));
    assert!(codec.parse(0, &bytes).is_err());
}

/// CRC-16/XMODEM, bit by bit (poly 0x1021, init 0), to seal edited frames.
fn crc16_xmodem(data: &[u8]) -> u16 {
    let mut crc = 0u16;
    for &b in data {
        crc ^= u16::from(b) << 8;
        for _ in 0..8 {
            crc = if crc & 0x8000 != 0 {
                (crc << 1) ^ 0x1021
            } else {
                crc << 1
            };
        }
    }
    crc
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_eq!(expected.len(), 13);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::decode(f).is_ok(), "{:?}", F(f));
    });
}
