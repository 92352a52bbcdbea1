//! `protocol import mavlink`: a MAVLink dialect's XML (and the files it includes) as a spec.
//!
//! The stages, one module each: [`xml`] reads the document, [`model`] reads MAVLink's
//! definitions from it (and puts fields in wire order), [`crc_extra`] derives each message's
//! CRC_EXTRA, and [`emit`] writes the spec text. The importer writes each CRC_EXTRA as the
//! command's `check_extra`, so the spec language needs no MAVLink rule and every backend reads
//! the byte as it reads a hand-typed one.

pub mod crc_extra;
pub mod emit;
pub mod model;
pub mod xml;

use std::path::Path;

/// The spec text of the dialect at `path`.
///
/// # Errors
/// The dialect or a file it includes cannot be read or is not a MAVLink definition, or its
/// names would collide in the spec (the message says which).
pub fn import(path: &Path) -> Result<String, String> {
    let dialect = model::load(path)?;
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    emit::spec_text(&dialect, &stem)
}
