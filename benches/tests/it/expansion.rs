//! The `protocol!` macro's work on large specs: loading, validating and expanding a synthetic
//! spec of 256 commands must take under a second. Tests run unoptimized, as cargo builds
//! proc-macros, so this is the time the macro takes in a user's build (rustc's own work on the
//! tokens comes on top). `cargo run -p protocol-benches --bin synth -- expand` prints the
//! scaling table of `BENCHMARKS.md`.

use std::time::{Duration, Instant};

use protocol_benches::synth;
use protocol_codegen::codegen::{RuntimePath, expand};
use protocol_codegen::source::SpecSource;

fn expansion_time(commands: usize) -> (Duration, usize) {
    let source = SpecSource::new("synth.toml", synth::spec(commands));
    let start = Instant::now();
    let protocol = match protocol_codegen::compile(&source) {
        Ok(p) => p,
        Err(diags) => panic!("the synthetic spec of {commands} commands: {diags:?}"),
    };
    let tokens = expand(&protocol, &RuntimePath::default());
    (start.elapsed(), tokens.to_string().len())
}

#[test]
fn synthetic_specs_validate_and_grow_linearly() {
    let (_, small) = expansion_time(16);
    let (_, large) = expansion_time(256);
    // 16 times the commands: the expansion grows about as much, never quadratically.
    let growth = large as f64 / small as f64;
    assert!((8.0..20.0).contains(&growth), "expansion grew {growth}x");
}

#[test]
fn expanding_256_commands_takes_under_a_second() {
    // The best of three runs, so that a busy machine does not fail the budget by accident.
    let best = (0..3)
        .map(|_| expansion_time(256).0)
        .min()
        .unwrap_or_default();
    assert!(best < Duration::from_secs(1), "256 commands took {best:?}");
}
