//! Random specs through the C peer: a batch of specs from the seeded generator
//! (`tests/tests/support/random_spec.rs`), each validated by the front end, then compared
//! C against the run-time codec as the bundled specs are (`check_spec`: random and edge frames
//! decoded and encoded again, a fault-injection stream per decoder at several chunk sizes).
//!
//! `RANDOM_SPECS` sets the batch size (default 6) and `RANDOM_SPECS_SEED` its first seed
//! (default 0, so that CI runs the same specs); the test prints both. A failing spec is printed
//! whole with its seed, to be kept as a fixture in this directory.

use std::panic::{AssertUnwindSafe, catch_unwind, resume_unwind};

use protocol_spec::diag::render_all;
use protocol_spec::source::SpecSource;

#[path = "../../../tests/tests/support/random_spec.rs"]
mod random_spec;

/// The batch: (first seed, count), from the environment or the defaults.
fn batch() -> (u64, u64) {
    let var = |name: &str, default: u64| {
        std::env::var(name).ok().map_or(default, |v| {
            v.parse()
                .unwrap_or_else(|_| panic!("{name}={v}: not a number"))
        })
    };
    (var("RANDOM_SPECS_SEED", 0), var("RANDOM_SPECS", 6))
}

#[test]
fn random_specs_agree_in_c_and_rust() {
    let (first, count) = batch();
    eprintln!(
        "random specs: seeds {first}..{} ({count} specs)",
        first + count
    );
    let dir = tempfile::tempdir().expect("a temporary directory");
    let mut refused = 0;
    for seed in first..first + count {
        let name = format!("rand_{seed}");
        let text = random_spec::spec(seed, &name);
        let source = SpecSource::new(format!("{name}.toml"), text.clone());
        if let Err(diagnostics) = protocol_spec::compile(&source) {
            panic!(
                "seed {seed}: the generator wrote a spec the front end refuses:\n{text}\n{}",
                render_all(&diagnostics, &source)
            );
        }
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, &text).expect("write the spec");
        match catch_unwind(AssertUnwindSafe(|| super::check_spec(&path, 1000))) {
            Ok((_, what)) => {
                if what.starts_with("refused") {
                    refused += 1;
                }
                eprintln!("seed {seed}: {what}");
            }
            Err(panic) => {
                eprintln!("seed {seed}: C and Rust disagree on this spec:\n{text}");
                resume_unwind(panic);
            }
        }
    }
    // A batch the C printer refuses whole compares nothing.
    assert!(
        refused < count,
        "the C printer refuses all {count} random specs"
    );
}
