//! `protocol decode --direction` and `protocol encode --direction` on `specs/dynamixel1.toml`,
//! whose instruction and status packets share one layout: the direction picks how frames
//! decode, it is required for such a spec and refused for a spec whose header tells its
//! directions, and `decode | encode` gives back every frame.

use crate::support;

use serde_json::Value;
use support::{json_lines, protocol, root, text, unhex};

const SPEC: &str = "specs/dynamixel1.toml";

/// Stderr with miette's wrapping undone: one line, single spaces.
fn message(out: &std::process::Output) -> String {
    text(&out.stderr)
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

fn vectors() -> Value {
    let path = root().join("tests/vectors/dynamixel_protocol1.json");
    serde_json::from_str(&std::fs::read_to_string(path).expect("vectors")).expect("JSON")
}

/// The vector frames of one packet kind, back to back.
fn packets(kind: &str) -> (Vec<Value>, Vec<u8>) {
    let v = vectors();
    let frames: Vec<Value> = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .filter(|f| f["packet"] == kind)
        .cloned()
        .collect();
    let bytes = frames
        .iter()
        .flat_map(|f| unhex(f["hex"].as_str().expect("hex")))
        .collect();
    (frames, bytes)
}

#[test]
fn decode_without_a_direction_names_the_choices() {
    let (_, bytes) = packets("instruction");
    let out = protocol(&["decode", SPEC, "--format", "json"], &bytes);
    assert!(!out.status.success());
    let err = message(&out);
    assert!(err.contains("--direction"), "{err}");
    assert!(
        err.contains("`request`") && err.contains("`response`"),
        "{err}"
    );
    assert!(out.stdout.is_empty(), "nothing decoded without a direction");
}

#[test]
fn a_direction_the_spec_lacks_or_cannot_use_is_refused() {
    let out = protocol(
        &["decode", SPEC, "--hex", "--direction", "status"],
        b"ffff010200fc",
    );
    assert!(!out.status.success());
    let err = message(&out);
    assert!(
        err.contains("no such direction") && err.contains("`request`, `response`"),
        "{err}"
    );
    // HFLink's header tells its directions: `--direction` has nothing to choose.
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "--hex",
            "--direction",
            "request",
        ],
        b"ff",
    );
    assert!(!out.status.success());
    let err = message(&out);
    assert!(err.contains("by a header field"), "{err}");
    let out = protocol(
        &[
            "decode",
            "specs/ibus.toml",
            "--hex",
            "--direction",
            "request",
        ],
        b"ff",
    );
    assert!(message(&out).contains("has no directions"));
}

#[test]
fn instruction_packets_decode_as_requests_and_encode_back() {
    let (frames, bytes) = packets("instruction");
    let out = protocol(
        &["decode", SPEC, "--format", "json", "--direction", "request"],
        &bytes,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    assert_eq!(lines.len(), frames.len(), "one line per packet, no event");
    for (line, f) in lines.iter().zip(&frames) {
        assert_eq!(line["direction"], "request");
        assert_eq!(line["id"], f["instruction"], "{}", f["name"]);
        assert_eq!(line["hex"], f["hex"]);
    }
    // `decode | encode` gives back every packet.
    let back = protocol(&["encode", SPEC], &out.stdout);
    assert!(back.status.success(), "{}", text(&back.stderr));
    assert_eq!(back.stdout, bytes);
    // Objects that name no direction take `encode --direction`; without it they are refused.
    let stripped: String = lines
        .iter()
        .map(|l| {
            let mut l = l.clone();
            l.as_object_mut().expect("object").remove("direction");
            format!("{l}\n")
        })
        .collect();
    let refused = protocol(&["encode", SPEC], stripped.as_bytes());
    assert!(!refused.status.success());
    assert!(message(&refused).contains("`direction`"));
    let given = protocol(
        &["encode", SPEC, "--direction", "request"],
        stripped.as_bytes(),
    );
    assert!(given.status.success(), "{}", text(&given.stderr));
    assert_eq!(given.stdout, bytes);
}

#[test]
fn the_status_stream_decodes_as_responses() {
    let v = vectors();
    let stream = &v["streams"][0];
    let bytes = unhex(stream["hex"].as_str().expect("hex"));
    let out = protocol(
        &[
            "decode",
            SPEC,
            "--format",
            "json",
            "--direction",
            "response",
        ],
        &bytes,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let lines = json_lines(&out.stdout);
    let frames: Vec<(u64, &str)> = lines
        .iter()
        .filter(|l| l.get("event").is_none())
        .map(|l| {
            assert_eq!(l["direction"], "response");
            assert!(l.get("command").is_none(), "a status packet has no command");
            (
                l["offset"].as_u64().expect("offset"),
                l["hex"].as_str().expect("hex"),
            )
        })
        .collect();
    let expected: Vec<(u64, &str)> = stream["expected_frames"]
        .as_array()
        .expect("expected")
        .iter()
        .map(|f| {
            (
                f["offset"].as_u64().expect("offset"),
                f["hex"].as_str().expect("hex"),
            )
        })
        .collect();
    assert_eq!(frames, expected);
    // Frame lengths plus event bytes are the input.
    let covered: u64 = lines
        .iter()
        .map(|l| {
            l.get("length")
                .or(l.get("bytes"))
                .and_then(Value::as_u64)
                .expect("a length")
        })
        .sum();
    assert_eq!(covered, bytes.len() as u64);
    let table = protocol(
        &[
            "decode",
            SPEC,
            "--format",
            "table",
            "--direction",
            "response",
        ],
        &bytes,
    );
    let shown = text(&table.stdout);
    assert!(
        shown.contains("(Status)") && shown.contains("overload=true"),
        "{shown}"
    );
}
