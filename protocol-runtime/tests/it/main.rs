//! The runtime's integration tests: the stream engine and frame layouts of the reference
//! protocols, written by hand (no generated code), on golden vectors and random input.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-runtime --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

#[path = "../common/mod.rs"]
mod common;

mod bare_header;
mod conditional;
mod escaped;
mod formats;
mod hflink;
mod layouts;
mod robustness;
mod rule_kinds;
mod sizing;
