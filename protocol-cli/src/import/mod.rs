//! Importers: a message set defined in another language, read and written out as a spec of
//! this project (TOML text), so that nothing of it is typed by hand.
//!
//! This module owns the formats read and the spec text they become; checking that text is the
//! spec pipeline's work ([`crate::spec`]), as for any spec.

pub mod mavlink;
