//! MSP frames framed and parsed by YAMSPy (`tests/vectors/msp_yamspy.json`, made by
//! `scripts/msp_yamspy_vectors.py`): random messages of the commands of `specs/msp.toml`, v1 and
//! v2, requests written by YAMSPy and replies read back by YAMSPy's parser.
//!
//! The generated code and the run-time codec each decode every frame to the recorded payload
//! and to YAMSPy's reading of the bytes (each value YAMSPy read, at its scale, within half that
//! scale: ours as it is where the spec scales the field too, ours times the scale where the
//! spec keeps the wire integer), and encode the payload back to the frame's bytes.

use crate::golden;

use protocol_tests::{F, hex, load_vectors};
use serde_json::Value;
use std::collections::BTreeSet;

pub(crate) mod generated {
    protocol_kit::protocol!("../specs/msp.toml", derive(serde));
}

use generated::msp;

/// A JSON value through its text, as a decoder prints it.
pub(crate) fn shown(value: &impl serde::Serialize) -> Value {
    serde_json::from_str(&serde_json::to_string(value).expect("JSON")).expect("JSON")
}

/// The value at a dotted path (`pids.2.p`), array elements by index.
fn at_path<'a>(payload: &'a Value, path: &str) -> &'a Value {
    path.split('.')
        .fold(payload, |v, key| match key.parse::<usize>() {
            Ok(n) => &v[n],
            Err(_) => &v[key],
        })
}

/// Every value the peer read (`frame[peer]`: `[path, value, scale]`) agrees with ours: equal,
/// or within half the scale of the peer's, ours as it is where it is a physical value (a
/// float: the spec scales the field) and ours times the scale where it is the wire integer.
pub(crate) fn assert_peer_agrees(payload: &Value, frame: &Value, peer: &str, at: &str) {
    for check in frame[peer].as_array().expect("the peer's values") {
        let path = check[0].as_str().expect("a path");
        let ours = at_path(payload, path);
        let theirs = &check[1];
        match check[2].as_f64() {
            None => assert_eq!(ours, theirs, "{at}: `{path}`"),
            Some(scale) => {
                let physical = ours.is_f64();
                let ours = ours
                    .as_f64()
                    .unwrap_or_else(|| panic!("{at}: `{path}` is {ours}"));
                let ours = if physical { ours } else { ours * scale };
                let theirs = theirs.as_f64().expect("a number");
                assert!(
                    (ours - theirs).abs() <= scale / 2.0,
                    "{at}: `{path}` is {ours} at {scale}, {peer} {theirs}"
                );
            }
        }
    }
}

#[test]
fn every_yamspy_frame_decodes_to_its_values_and_encodes_to_its_bytes() {
    let v = load_vectors("msp_yamspy.json");
    let interp = golden::interpreter("msp");
    let codec = interp.codec();
    let mut covered = BTreeSet::new();
    let mut compared = 0;
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let at = frame["name"].as_str().expect("a name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let command = frame["message"].as_str().expect("the command");
        let v2 = frame["version"] == "v2";
        let direction = if frame["direction"] == "request" {
            b'<'
        } else {
            b'>'
        };
        let expected = &frame["payload"];

        let decoded = codec
            .parse(usize::from(v2), &bytes)
            .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let by_codec = shown(&value);
        assert_eq!(by_codec["command"], command, "{at}: the codec's command");
        assert_eq!(by_codec["header"]["direction"], direction, "{at}");
        assert_eq!(&by_codec["payload"], expected, "{at}: the codec's payload");
        assert_peer_agrees(
            &by_codec["payload"],
            frame,
            "yamspy",
            &format!("{at} (codec)"),
        );
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{at}: the codec does not encode it: {e}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{at}: the codec's bytes");

        let by_rust = if v2 {
            let packet = msp::V2Packet::decode(&bytes).unwrap_or_else(|e| panic!("{at}: {e}"));
            let mut buf = [0u8; msp::V2_MAX_FRAME_LEN];
            let n = packet.encode(&mut buf).expect("encode");
            assert_eq!(F(&buf[..n]), F(&bytes), "{at}: the generated code's bytes");
            shown(&packet)
        } else {
            let packet = msp::Packet::decode(&bytes).unwrap_or_else(|e| panic!("{at}: {e}"));
            let mut buf = [0u8; msp::MAX_FRAME_LEN];
            let n = packet.encode(&mut buf).expect("encode");
            assert_eq!(F(&buf[..n]), F(&bytes), "{at}: the generated code's bytes");
            shown(&packet)
        };
        assert_eq!(by_rust["command"], command, "{at}: the generated command");
        assert_eq!(by_rust["header"]["direction"], direction, "{at}: {by_rust}");
        let rust_payload = &by_rust["payload"];
        assert_eq!(rust_payload, expected, "{at}: the generated payload");
        assert_peer_agrees(rust_payload, frame, "yamspy", &format!("{at} (Rust)"));
        compared += frame["yamspy"].as_array().map_or(0, Vec::len);
        covered.insert(command.to_owned());
    }
    let all: BTreeSet<String> = msp::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    let left_out: BTreeSet<String> = v["source"]["left_out"]
        .as_object()
        .expect("left_out")
        .keys()
        .cloned()
        .collect();
    let missing: BTreeSet<_> = all.difference(&covered).cloned().collect();
    assert_eq!(
        missing, left_out,
        "every command but those left out has frames"
    );
    assert!(compared > 500, "{compared} values compared with YAMSPy's");
}
