//! UBX frames written and decoded by pyubx2 (`tests/vectors/ubx_pyubx2.json`, made by
//! `scripts/ubx_pyubx2_vectors.py`): random messages of every command of `specs/ubx.toml`.
//!
//! The generated code and the run-time codec each decode every frame to pyubx2's values (a
//! scaled field within half its scale of pyubx2's, every other value equal, bit members and
//! enumerations included), and encode pyubx2's values back to the frame's bytes. Where pyubx2
//! adds a high-precision part into its main field (NAV-HPPOSLLH's `lon` is `lon + lon_hp`), the
//! sum of the spec's two fields is checked against pyubx2's.

use crate::golden;
use crate::peer_frames::{assert_agrees, assert_encodes_back, shown};

use protocol_tests::{hex, load_vectors};
use serde_json::{Value, json};
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/ubx.toml", derive(serde));
}

use generated::ubx;

/// pyubx2's sums of a main field and its high-precision part, against the spec's two fields.
fn assert_sums(payload: &Value, frame: &Value, at: &str) {
    let Some(sums) = frame["pyubx2_sums"].as_object() else {
        return;
    };
    for (main, check) in sums {
        let theirs = check[0].as_f64().expect("pyubx2's sum");
        let hp = check[1][1].as_str().expect("the high-precision field");
        let ours =
            payload[main].as_f64().expect("a number") + payload[hp].as_f64().expect("a number");
        let scale = frame["scales"][hp].as_f64().expect("the part's scale");
        let within = scale / 2.0 + theirs.abs() * 1e-12;
        assert!(
            (ours - theirs).abs() <= within,
            "{at}: {main} + {hp} is {ours}, pyubx2 {theirs}"
        );
    }
}

#[test]
fn every_pyubx2_frame_decodes_to_its_values_and_encodes_to_its_bytes() {
    let v = load_vectors("ubx_pyubx2.json");
    let interp = golden::interpreter("ubx");
    let codec = interp.codec();
    let mut covered = BTreeSet::new();
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let at = frame["name"].as_str().expect("a name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let command = frame["message"].as_str().expect("the command");
        let expected = &frame["payload"];
        let scales = frame["scales"].as_object().expect("scales");

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
        let by_codec = shown(&codec.frame_value(&decoded, 0, &bytes));
        assert_eq!(by_codec["command"], command, "{at}: the codec's command");
        assert_agrees(
            &by_codec["payload"],
            expected,
            "",
            scales,
            &format!("{at} (codec)"),
        );
        assert_sums(&by_codec["payload"], frame, &format!("{at} (codec)"));

        let packet = ubx::Packet::decode(&bytes).unwrap_or_else(|e| panic!("{at}: {e}"));
        let by_rust = shown(&packet);
        assert_eq!(by_rust["command"], command, "{at}: the generated command");
        assert_agrees(
            &by_rust["payload"],
            expected,
            "",
            scales,
            &format!("{at} (Rust)"),
        );
        assert_sums(&by_rust["payload"], frame, &format!("{at} (Rust)"));

        // pyubx2's values, encoded by each, are the frame again.
        let object = json!({ "command": command, "header": {}, "payload": expected });
        assert_encodes_back(&codec, object, &bytes, at, |packet: &ubx::Packet| {
            let mut buf = [0u8; ubx::MAX_FRAME_LEN];
            let n = packet
                .encode(&mut buf)
                .unwrap_or_else(|e| panic!("{at}: {e}"));
            buf[..n].to_vec()
        });
        covered.insert(command.to_owned());
    }
    let all: BTreeSet<String> = ubx::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(covered, all, "every command of the spec has pyubx2 frames");
    assert!(frames.len() >= 4 * all.len(), "{} frames", frames.len());
}
