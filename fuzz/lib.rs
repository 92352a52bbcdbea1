//! The fuzz targets' shared code: the robustness harness of the tests crate, included by path
//! so that the fuzzers and the stable corpus test (`tests/tests/it/robustness/fuzz_corpus.rs`) run
//! the same entry points (`support::fuzz`).
#![forbid(unsafe_code)]

#[path = "../tests/tests/support/mod.rs"]
pub mod support;
