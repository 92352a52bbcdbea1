//! The random spec generator (`tests/tests/support/random_spec.rs`) against the front end:
//! every spec of a large batch is accepted, the batch uses every language feature the
//! generator lists, and the shrinker (`tests/tests/support/shrink.rs`) reduces a spec to one
//! from which no line can be removed without losing what it keeps.
//!
//! `RANDOM_SPECS` sets the batch size (default 2,000) and `RANDOM_SPECS_SEED` its first seed
//! (default 0); both are printed, with how many specs used each feature.

use std::collections::BTreeMap;

use protocol_spec::diag::render_all;
use protocol_spec::source::SpecSource;

#[path = "../../tests/tests/support/random_spec.rs"]
mod random_spec;
#[path = "../../tests/tests/support/shrink.rs"]
mod shrink;

fn var(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().map_or(default, |v| {
        v.parse()
            .unwrap_or_else(|_| panic!("{name}={v}: not a number"))
    })
}

/// Whether the front end accepts `text`.
fn valid(text: &str) -> bool {
    protocol_spec::compile(&SpecSource::new("shrunk.toml", text.to_string())).is_ok()
}

#[test]
fn every_random_spec_is_valid_and_the_batch_uses_every_feature() {
    let (first, count) = (var("RANDOM_SPECS_SEED", 0), var("RANDOM_SPECS", 2000));
    eprintln!(
        "random specs: seeds {first}..{} ({count} specs)",
        first + count
    );
    let mut used: BTreeMap<&str, usize> = BTreeMap::new();
    for seed in first..first + count {
        let name = format!("rand_{seed}");
        let spec = random_spec::generate(seed, &name);
        let source = SpecSource::new(format!("{name}.toml"), spec.text.clone());
        if let Err(diagnostics) = protocol_spec::compile(&source) {
            panic!(
                "seed {seed}: the generator wrote a spec the front end refuses:\n{}\n{}",
                spec.text,
                render_all(&diagnostics, &source)
            );
        }
        for f in spec.features {
            *used.entry(f).or_default() += 1;
        }
    }
    for (feature, n) in &used {
        eprintln!("  {feature}: {n} specs");
    }
    let unused: Vec<&str> = random_spec::FEATURES
        .iter()
        .copied()
        .filter(|f| !used.contains_key(f))
        .collect();
    // A small batch may miss the rarest; the default batch uses them all.
    if count >= 2000 {
        assert!(unused.is_empty(), "features no spec used: {unused:?}");
    }
}

#[test]
fn a_spec_shrinks_to_one_from_which_no_line_can_go() {
    // What the shrinking keeps: a valid spec with a bit-packed array in a frame with stuffing.
    let keeps =
        |text: &str| text.contains("packed = {") && text.contains("stuffing") && valid(text);
    let (seed, text) = (0..)
        .map(|seed| (seed, random_spec::spec(seed, "shrink")))
        .find(|(_, text)| keeps(text))
        .expect("a spec with both");
    let mut calls = 0;
    let shrunk = shrink::shrink(&text, 5000, |t| {
        calls += 1;
        keeps(t)
    });
    eprintln!(
        "seed {seed}: {} lines shrunk to {} in {calls} tries:\n{shrunk}",
        text.lines().count(),
        shrunk.lines().count()
    );
    assert!(keeps(&shrunk), "the shrunk spec lost what it keeps");
    assert_eq!(shrunk.matches("[structs.").count(), 1, "{shrunk}");
    assert_eq!(shrunk.matches("[frames.").count(), 1, "{shrunk}");
    assert!(!shrunk.contains("[enums."), "{shrunk}");
    // One-minimal: removing any line that is not a table header or an array's bracket
    // loses what it keeps (or makes the spec invalid).
    let lines: Vec<&str> = shrunk.lines().collect();
    for i in 0..lines.len() {
        let l = lines[i].trim();
        if l.starts_with('[') || l.ends_with('[') || l == "]" || l.is_empty() || l.starts_with('#')
        {
            continue;
        }
        let without: Vec<&str> = [&lines[..i], &lines[i + 1..]].concat();
        assert!(
            !keeps(&(without.join("\n") + "\n")),
            "line {i} ({l}) can go from:\n{shrunk}"
        );
    }
    // A field's extra keys go too: the packed field keeps only what it must.
    let packed = lines
        .iter()
        .find(|l| l.contains("packed = {"))
        .expect("the packed field");
    assert_eq!(shrink::top_level_parts(packed).len(), 3, "{packed}");
}
