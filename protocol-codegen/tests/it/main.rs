//! The printers' integration tests: expansion and diagnostics snapshots, the rule catalogue,
//! derive rules, the C printer, the rendered Markdown references, buffer refusals and checks.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-codegen --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

// The tests of one printer need its feature (all are on by default).
mod buffer_refusal;
#[cfg(feature = "c")]
mod c_escape_can;
#[cfg(feature = "c")]
mod c_printer;
mod checks;
#[cfg(feature = "rust")]
mod derive_rules;
#[cfg(feature = "rust")]
mod diagnostics;
#[cfg(feature = "rust")]
mod expand;
mod lints;
#[cfg(feature = "markdown")]
mod protocol_docs;
mod rule_catalogue;
