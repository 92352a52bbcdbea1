//! Cross-checks against implementations of the catalogued protocols that no one here wrote.
//!
//! The crates.io implementations of each protocol (the peers) check this project from the
//! outside, in two ways:
//!
//! - the golden vectors (`tests/vectors/*.json`) decode in their peer to the recorded values, so
//!   that the facts every spec is tested against are confirmed by a second decoder;
//! - random messages cross the boundary both ways ([`harness`]): what the peer writes decodes
//!   here to the same values, and what this project writes decodes in the peer.
//!
//! This crate is a workspace member that no other crate depends on, so the peers (and their
//! dependencies) never reach the runtime's dependency graph.

pub mod harness;

use serde_json::Value;

/// Bytes from a hex string (whitespace allowed).
///
/// # Panics
///
/// On a malformed string: the vectors are part of the test, a bad one is a test failure.
pub fn hex(text: &str) -> Vec<u8> {
    let digits: Vec<u8> = text.bytes().filter(|b| !b.is_ascii_whitespace()).collect();
    assert!(digits.len().is_multiple_of(2), "odd hex length: {text}");
    digits
        .chunks(2)
        .map(|pair| {
            let s = std::str::from_utf8(pair).expect("ascii");
            u8::from_str_radix(s, 16).unwrap_or_else(|_| panic!("bad hex {s:?} in {text}"))
        })
        .collect()
}

/// One vector file of `tests/vectors`, parsed.
///
/// # Panics
///
/// When the file is missing or not JSON.
pub fn load_vectors(name: &str) -> Value {
    let path = format!("{}/../vectors/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The frames of a vector file.
///
/// # Panics
///
/// When the file has no `frames` array.
pub fn frames(vectors: &Value) -> &[Value] {
    vectors["frames"].as_array().expect("frames")
}

/// A frame's bytes (its `hex`).
///
/// # Panics
///
/// When the frame has no `hex`.
pub fn frame_bytes(frame: &Value) -> Vec<u8> {
    hex(frame["hex"].as_str().expect("hex"))
}

/// A frame's name, for messages.
pub fn name(frame: &Value) -> &str {
    frame["name"].as_str().unwrap_or("?")
}

/// An unsigned integer of a JSON object.
///
/// # Panics
///
/// When the key is missing or not an unsigned integer.
pub fn uint(v: &Value, key: &str) -> u64 {
    v[key]
        .as_u64()
        .unwrap_or_else(|| panic!("{key}: not an unsigned integer in {v}"))
}

/// A signed integer of a JSON object.
///
/// # Panics
///
/// When the key is missing or not an integer.
pub fn int(v: &Value, key: &str) -> i64 {
    v[key]
        .as_i64()
        .unwrap_or_else(|| panic!("{key}: not an integer in {v}"))
}

/// A list of unsigned integers of a JSON object.
///
/// # Panics
///
/// When the key is missing or holds something else.
pub fn uints(v: &Value, key: &str) -> Vec<u64> {
    v[key]
        .as_array()
        .unwrap_or_else(|| panic!("{key}: not a list in {v}"))
        .iter()
        .map(|x| x.as_u64().expect("unsigned"))
        .collect()
}

/// The frames a stream must yield: each expected frame's offset and bytes.
///
/// # Panics
///
/// When the stream is malformed.
pub fn expected_frames(stream: &Value) -> Vec<(u64, Vec<u8>)> {
    stream["expected_frames"]
        .as_array()
        .expect("expected_frames")
        .iter()
        .map(|e| (uint(e, "offset"), hex(e["hex"].as_str().expect("hex"))))
        .collect()
}
