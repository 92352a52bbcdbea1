//! The run-time codec's integration tests: loading, hex input, the compatibility report, its
//! memory, and its agreement with generated code (values, serde JSON, session rules).
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-dynamic --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

#[path = "../support/mod.rs"]
mod support;

mod codec_memory;
mod compat;
mod compat_registers;
mod conversation;
mod hex;
mod interp_differential;
mod load;
mod optional_bytes;
mod registers;
mod serde_agreement;
mod session_agreement;
mod session_fanout;
