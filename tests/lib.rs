//! Helpers shared by the end-to-end tests: golden vector loading and hex formatting. The
//! vectors are the project's own copies (`tests/vectors/`) of the shared golden files.

use std::fmt;

use serde_json::Value;

/// Parse hex text (whitespace ignored).
///
/// # Panics
/// On invalid hex: vectors are trusted test data.
pub fn hex(text: &str) -> Vec<u8> {
    let clean: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    (0..clean.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&clean[i..i + 2], 16).expect("valid hex"))
        .collect()
}

/// Load `tests/vectors/NAME`.
///
/// # Panics
/// When the file is missing or not JSON.
pub fn load_vectors(name: &str) -> Value {
    let path = format!("{}/vectors/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("vector file is JSON")
}

/// Bytes that print as hex in assertion messages.
#[derive(PartialEq, Eq)]
pub struct F<'a>(pub &'a [u8]);

impl fmt::Debug for F<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for b in self.0 {
            write!(f, "{b:02x}")?;
        }
        Ok(())
    }
}

/// The bytes of a vector stream and its `expected_frames` as (offset, bytes).
///
/// # Panics
/// When the vector lacks them.
pub fn stream_vector(stream: &Value) -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let bytes = hex(stream["hex"].as_str().expect("stream hex"));
    let expected = stream["expected_frames"]
        .as_array()
        .expect("expected_frames")
        .iter()
        .map(|f| {
            (
                f["offset"].as_u64().expect("offset"),
                hex(f["hex"].as_str().expect("frame hex")),
            )
        })
        .collect();
    (bytes, expected)
}

/// Feed `bytes` to a fresh decoder of `layout` in chunks of every size from 1 to the whole
/// stream; every run must yield exactly `expected` (offset and bytes), every byte must be
/// accounted for, and `each` sees every frame (to check it decodes).
///
/// # Panics
/// On the first chunk size whose frames differ.
pub fn assert_stream_at_every_chunk_size<const N: usize>(
    layout: &'static protocol_kit::FrameLayout<'static>,
    bytes: &[u8],
    expected: &[(u64, Vec<u8>)],
    mut each: impl FnMut(&[u8]),
) {
    assert_link_stream_at_every_chunk_size::<_, N>(layout, bytes, expected, |frame| {
        each(frame.bytes);
    });
}

/// [`assert_stream_at_every_chunk_size`] for any layout, a link of several frame formats
/// too: `each` sees every frame with the format it came in.
pub fn assert_link_stream_at_every_chunk_size<L: protocol_kit::LayoutRef, const N: usize>(
    layout: L,
    bytes: &[u8],
    expected: &[(u64, Vec<u8>)],
    mut each: impl FnMut(&protocol_kit::Frame<'_>),
) {
    for chunk in 1..=bytes.len() {
        let mut dec = protocol_kit::StreamDecoder::<_, N>::new(layout);
        let mut got = Vec::new();
        for part in bytes.chunks(chunk) {
            let mut input = part;
            while let Some(frame) = dec.decode(&mut input) {
                each(&frame);
                got.push((frame.offset, frame.bytes.to_vec()));
            }
        }
        assert_eq!(got, expected, "chunk size {chunk}");
        let s = dec.stats();
        assert_eq!(
            s.frame_bytes + s.skipped_bytes + dec.pending() as u64,
            bytes.len() as u64,
            "chunk size {chunk}: every byte accounted for"
        );
    }
}
