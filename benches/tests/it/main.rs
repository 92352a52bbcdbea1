//! The benchmark crate's tests: every benchmarked decoder and encoder against the ground truth,
//! and the macro's expansion time on a large spec.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-benches --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

mod decoders;
mod expansion;
