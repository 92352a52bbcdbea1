//! The spec front end's integration tests: the JSON Schema of the spec format and the spec
//! fuzzer's dictionary, both against the serde model.
//!
//! One binary for the package's integration tests, each file here a module named as the file
//! (`cargo test -p protocol-spec --test it -- NAME::` runs one): every test binary links the
//! crates under test and their dependencies once more, so one binary builds and links them once.
//! A new file `NAME.rs` here joins with a `mod NAME;` line (docs/architecture.md, "Tests").

mod extra_direct;
mod fuzz_dict;
mod schema;
