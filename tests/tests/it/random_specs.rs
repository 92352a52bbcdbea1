//! Random specs through generated Rust and the run-time codec: a batch of specs from the seeded
//! generator (`support/random_spec.rs`), expanded with `protocol!` by the build script
//! (`tests/build.rs`), each checked as the bundled specs are by the robustness harness:
//!
//! - random valid frames (the spec-driven model) and each with one bit flipped: generated
//!   code and `protocol_dynamic` accept the same ones and encode them back to the same bytes
//!   (`support::fuzz::interp`); the stream decoder finds the same frames fed whole and in
//!   random chunks (`support::fuzz::stream`);
//! - a stream of the frames back to back, fed in random chunks: exactly the frames sent;
//! - a fault-injection stream (`support::fault`) in random chunks: every invariant of the
//!   checked stream driver (`support::stream::run`), no panic.
//!
//! The seed and count are printed (`--nocapture`); set `RANDOM_SPECS` and `RANDOM_SPECS_SEED`
//! at build time for another batch, or `RANDOM_SPEC_FILE` for one spec file (`tests/build.rs`).
//! A failing spec is printed with its seed and the commands that shrink it: generated code
//! needs a compile per spec, so shrinking runs where no compile is needed (the C peer's test
//! against the run-time codec), and a shrunk candidate comes back here as a file.

use crate::support;

use support::fault::build;
use support::model::model;
use support::stream::run;
use support::{Rng, Source, Spec};

include!(concat!(env!("OUT_DIR"), "/random_specs.rs"));

/// Frames per spec.
pub(crate) const FRAMES: usize = 300;

/// Random chunk sizes up to a frame and a half, zero included.
fn sizes<S: Spec>(rng: &mut Rng) -> Vec<usize> {
    (0..8)
        .map(|_| rng.below((S::MAX_FRAME_LEN + S::MAX_FRAME_LEN / 2 + 1) as u64) as usize)
        .collect()
}

/// Every check on one spec; the number of frames compared.
pub(crate) fn check<S: Spec>(seed: u64) -> usize {
    let model = model::<S>();
    let mut rng = Rng(seed ^ 0x5EED);
    let mut sent = Vec::new();
    for _ in 0..FRAMES {
        let frame = model.pick(&mut rng).canonical_here(&mut rng);
        support::fuzz::interp::<S>(&frame);
        let mut flipped = frame.clone();
        let bit = rng.below(frame.len() as u64 * 8) as usize;
        flipped[bit / 8] ^= 1 << (bit % 8);
        support::fuzz::interp::<S>(&flipped);
        let mode = rng.byte();
        support::fuzz::stream::<S>(&[&[mode][..], &frame].concat());
        sent.push(frame);
    }
    let stream = sent.concat();
    let got = run::<S>(&stream, &sizes::<S>(&mut rng));
    let got: Vec<&[u8]> = got.frames.iter().map(|(_, f)| f.as_slice()).collect();
    // The decoder yields a frame as `Packet::from_frame` reads it: unescaped.
    let want: Vec<Vec<u8>> = sent
        .iter()
        .map(|f| support::unescaped(S::layouts()[S::format_of(f)], f))
        .collect();
    let want: Vec<&[u8]> = want.iter().map(Vec::as_slice).collect();
    assert!(
        got == want,
        "{}: the frames sent back to back are not the frames decoded",
        S::NAME
    );
    let faulty = build(model, &mut rng, FRAMES, 4);
    run::<S>(&faulty.bytes, &sizes::<S>(&mut rng));
    run::<S>(&faulty.bytes, &[1]);
    sent.len()
}

#[test]
fn random_specs_agree_in_generated_rust_and_the_run_time_codec() {
    let (first, count) = BATCH;
    eprintln!(
        "random specs: seeds {first}..{} ({count} specs)",
        first + count
    );
    let (mut specs, mut frames) = (0, 0);
    macro_rules! one {
        ($name:ident, link) => {
            one!(@ $name, $name::AnyPacket)
        };
        ($name:ident $(, $given:tt)*) => {
            one!(@ $name, $name::Packet)
        };
        (@ $name:ident, $packet:ty) => {{
            let seed: u64 = stringify!($name)["rand_".len()..].parse().expect("a seed");
            let outcome = std::panic::catch_unwind(|| check::<$packet>(seed));
            specs += 1;
            match outcome {
                Ok(n) => frames += n,
                Err(panic) => {
                    eprintln!(
                        "seed {seed}: generated Rust and the run-time codec disagree on:\n{}\n\
                         Shrink it where the C peer disagrees too: RANDOM_SPECS_SEED={seed} \
                         RANDOM_SPECS=1 RANDOM_SPECS_KEEP=1 cargo test -p protocol-cli --test \
                         it -- c_peer::random_specs; check a smaller spec here with \
                         RANDOM_SPEC_FILE=/absolute/path/rand_{seed}.toml cargo test -p \
                         protocol-tests --test it -- random_specs::",
                        <$packet as Spec>::TEXT
                    );
                    std::panic::resume_unwind(panic);
                }
            }
        }};
    }
    for_each_random_spec!(one);
    // Besides the batch, the build script adds a later seed with what the batch lacks (an
    // escaped format).
    eprintln!(
        "random specs: {specs} specs ({count} of the batch), {frames} random frames (each also with a bit flipped)"
    );
    assert!(specs >= count as usize);
    assert_eq!(frames, specs * FRAMES);
}
