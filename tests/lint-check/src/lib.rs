//! Every spec of `specs/` expanded as plain source (by `build.rs`), so that
//! `cargo clippy --workspace` checks the generated code of every spec against the lints that
//! prove it cannot panic: no indexing or slicing that can go out of bounds, no `unwrap`,
//! `expect` or `panic!`, and no arithmetic that can overflow. A new spec in `specs/` is checked
//! without any change here.
//!
//! Clippy's default groups are allowed: generated code is written for clarity of review, not to
//! clippy's style, and users never see its warnings (they come out of a macro).
#![no_std]
#![forbid(unsafe_code)]
#![deny(
    missing_docs,
    clippy::indexing_slicing,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::panic
)]
#![deny(clippy::arithmetic_side_effects)]
#![allow(unused, clippy::all)]

include!(concat!(env!("OUT_DIR"), "/specs.rs"));
