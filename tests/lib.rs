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
