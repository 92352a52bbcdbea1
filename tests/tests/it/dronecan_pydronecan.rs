//! DroneCAN frames written and decoded by pydronecan (`tests/vectors/dronecan_pydronecan.json`,
//! made by `scripts/dronecan_pydronecan_vectors.py`): random messages of every command of
//! `specs/dronecan.toml`, each a CAN frame whose 29-bit identifier and tail byte pydronecan's
//! transport built.
//!
//! The generated code (`Packet::decode_can`) and the run-time codec (`decode_can`) each decode
//! every frame to pydronecan's values: the members of the identifier (priority, message type,
//! source node) and of the tail byte as header values, and the message (a float16 field as the
//! float pydronecan decoded, bit members and enumerations included); both encode pydronecan's
//! values back to the same identifier and data. A sequence of frames with damaged ones between
//! them decodes to exactly the good frames.

use crate::golden;

use protocol_kit::{CanFrame, DecodeError, Reject};
use protocol_tests::{hex, load_vectors};
use serde_json::{Value, json};
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/dronecan.toml", derive(serde));
}

use generated::dronecan;

/// A JSON value through its text, as a decoder prints it (an `f32` keeps its shortest form).
fn shown(value: &impl serde::Serialize) -> Value {
    serde_json::from_str(&serde_json::to_string(value).expect("JSON")).expect("JSON")
}

/// `ours` is pydronecan's `theirs`: the same keys, integers equal, floats equal to the
/// precision a decoder prints them with (a half or single float printed in its shortest form).
fn assert_agrees(ours: &Value, theirs: &Value, at: &str) {
    match (ours, theirs) {
        (Value::Object(o), Value::Object(t)) => {
            let ok: BTreeSet<_> = o.keys().collect();
            let tk: BTreeSet<_> = t.keys().collect();
            assert_eq!(ok, tk, "{at}: the fields");
            for (k, v) in t {
                assert_agrees(&o[k], v, &format!("{at}.{k}"));
            }
        }
        (Value::Number(o), Value::Number(t)) if t.is_f64() => {
            let (o, t) = (o.as_f64().expect("a number"), t.as_f64().expect("a number"));
            assert!(
                (o - t).abs() <= t.abs() * 1e-7,
                "{at} is {o}, pydronecan {t}"
            );
        }
        _ => assert_eq!(ours, theirs, "{at}"),
    }
}

/// The CAN frame a vector records.
fn can_frame(frame: &Value) -> CanFrame {
    let id = frame["can_id"].as_u64().expect("can_id") as u32;
    let data = hex(frame["data"].as_str().expect("data"));
    assert_eq!(frame["extended"], true, "DroneCAN ids are extended");
    CanFrame::new(id, &data)
        .expect("8 bytes at most")
        .into_extended()
}

#[test]
fn every_pydronecan_frame_decodes_to_its_values_and_encodes_to_its_frame() {
    let v = load_vectors("dronecan_pydronecan.json");
    let interp = golden::interpreter("dronecan");
    let codec = interp.codec();
    let mut covered = BTreeSet::new();
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let at = frame["name"].as_str().expect("a name");
        let can = can_frame(frame);
        let command = frame["command"].as_str().expect("the command");
        let (header, payload) = (&frame["header"], &frame["payload"]);

        let decoded = codec
            .decode_can(0, &can)
            .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
        let by_codec = shown(&codec.frame_value(&decoded, 0, can.data()));
        assert_eq!(by_codec["command"], command, "{at}: the codec's command");
        assert_eq!(by_codec["can_id"], frame["can_id"], "{at}: the codec's id");
        assert_agrees(&by_codec["header"], header, &format!("{at} (codec) header"));
        assert_agrees(&by_codec["payload"], payload, &format!("{at} (codec)"));

        let packet = dronecan::Packet::decode_can(&can).unwrap_or_else(|e| panic!("{at}: {e}"));
        let by_rust = shown(&packet);
        assert_eq!(by_rust["command"], command, "{at}: the generated command");
        assert_agrees(&by_rust["header"], header, &format!("{at} (Rust) header"));
        assert_agrees(&by_rust["payload"], payload, &format!("{at} (Rust)"));

        // pydronecan's values, encoded by each, are the frame again: the same id and data.
        let object = json!({ "command": command, "header": header, "payload": payload });
        let value: protocol_dynamic::Value =
            serde_json::from_value(object.clone()).expect("a frame object");
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{at}: the codec does not encode it: {e}"));
        assert_eq!(encoded.can, Some(can), "{at}: the codec's CAN frame");
        let packet: dronecan::Packet =
            serde_json::from_value(object).unwrap_or_else(|e| panic!("{at}: {e}"));
        let sent = packet.encode_can().unwrap_or_else(|e| panic!("{at}: {e}"));
        assert_eq!(sent, can, "{at}: the generated code's CAN frame");
        covered.insert(command.to_owned());
    }
    let all: BTreeSet<String> = dronecan::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(
        covered, all,
        "every command of the spec has pydronecan frames"
    );
    assert!(frames.len() >= 6 * all.len(), "{} frames", frames.len());
}

/// What each decoder makes of a frame: the command's name, or the error's text.
fn outcomes(codec: &protocol_dynamic::Codec<'_>, can: &CanFrame) -> (String, String) {
    let by_codec = match codec.decode_can(0, can) {
        Ok(d) => shown(&codec.frame_value(&d, 0, can.data()))["command"].to_string(),
        Err(e) => format!("{e:?}"),
    };
    let by_rust = match dronecan::Packet::decode_can(can) {
        Ok(p) => shown(&p)["command"].to_string(),
        Err(e) => format!("{e:?}"),
    };
    (by_codec, by_rust)
}

#[test]
fn a_bus_with_damaged_frames_between_the_good_ones_decodes_to_exactly_the_good_ones() {
    let v = load_vectors("dronecan_pydronecan.json");
    let interp = golden::interpreter("dronecan");
    let codec = interp.codec();
    let good: Vec<CanFrame> = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .step_by(5)
        .map(can_frame)
        .collect();
    let mut bus = Vec::new();
    for (i, can) in good.iter().enumerate() {
        bus.push((true, *can));
        let damaged = match i % 4 {
            // A service frame (the service flag set): another layout of the identifier.
            0 => CanFrame {
                id: can.id | 0x80,
                ..*can
            },
            // The same identifier as a standard frame: another protocol's frame.
            1 => CanFrame {
                id: can.id & 0x7FF,
                extended: false,
                ..*can
            },
            // One data byte fewer: the message's payload is short.
            2 => CanFrame {
                len: can.len - 1,
                ..*can
            },
            // A message type id the spec does not have (uavcan.equipment.esc.Status).
            _ => CanFrame {
                id: (can.id & !0x00FF_FF00) | (1034 << 8),
                ..*can
            },
        };
        bus.push((false, damaged));
    }
    let mut decoded = Vec::new();
    for (is_good, can) in &bus {
        let (by_codec, by_rust) = outcomes(&codec, can);
        let rust_ok = dronecan::Packet::decode_can(can).is_ok();
        assert_eq!(
            codec.decode_can(0, can).is_ok(),
            rust_ok,
            "{can:?}: codec {by_codec}, Rust {by_rust}"
        );
        if rust_ok {
            decoded.push(*can);
        } else {
            assert!(!is_good, "{can:?} is good: {by_rust}");
        }
    }
    assert_eq!(decoded, good, "exactly the good frames decode");
    // A service frame fails its constant flag, a standard frame its kind: a bad header.
    let service = CanFrame {
        id: good[0].id | 0x80,
        ..good[0]
    };
    assert_eq!(
        dronecan::Packet::decode_can(&service),
        Err(DecodeError::Frame(Reject::BadHeader))
    );
}
