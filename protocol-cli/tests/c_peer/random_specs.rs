//! Random specs through the C peer: a batch of specs from the seeded generator
//! (`tests/tests/support/random_spec.rs`), each validated by the front end, then compared
//! C against the run-time codec as the bundled specs are (`check_spec`: random and edge frames
//! decoded and encoded again, a fault-injection stream per decoder at several chunk sizes).
//!
//! `RANDOM_SPECS` sets the batch size (default 6) and `RANDOM_SPECS_SEED` its first seed
//! (default 0, so that CI runs the same specs); the test prints both. A failing spec is printed
//! whole with its seed, then shrunk (`tests/tests/support/shrink.rs`) to a smaller valid spec
//! on which C and Rust still disagree, tried in at most `RANDOM_SPECS_SHRINK` candidates
//! (default 300), and printed; with `RANDOM_SPECS_KEEP=1` the shrunk spec is written into this
//! directory as `rand_SEED.toml`, where it is a fixture of every later run. The batch goes on
//! past a failing spec and fails at its end, naming every failing seed. `RANDOM_SPEC_FILE`
//! names one spec file (its protocol named `rand_SEED`) to compare alone instead.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;
use std::sync::Mutex;

use protocol_spec::diag::render_all;
use protocol_spec::source::SpecSource;

#[path = "../../../tests/tests/support/random_spec.rs"]
mod random_spec;
#[path = "../../../tests/tests/support/shrink.rs"]
mod shrink;

fn var(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().map_or(default, |v| {
        v.parse()
            .unwrap_or_else(|_| panic!("{name}={v}: not a number"))
    })
}

/// The batch: (first seed, count), from the environment or the defaults.
fn batch() -> (u64, u64) {
    (var("RANDOM_SPECS_SEED", 0), var("RANDOM_SPECS", 6))
}

/// Where the last panic of this thread was raised (`file:line`): a shrunk spec must fail
/// where the original did, not anywhere.
fn panic_site() -> &'static Mutex<Option<String>> {
    static SITE: Mutex<Option<String>> = Mutex::new(None);
    &SITE
}

/// Records each panic's site, then prints it as before unless `quiet`.
fn record_panics(quiet: bool) {
    let _ = std::panic::take_hook();
    let print = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        if let Some(at) = info.location() {
            *panic_site().lock().unwrap_or_else(|e| e.into_inner()) =
                Some(format!("{}:{}{}", at.file(), at.line(), warnings(info)));
        }
        if !quiet {
            print(info);
        }
    }));
}

/// The C compiler's warning flags a panic's message names (`[-Werror=type-limits]`), sorted:
/// one site fails to compile for many reasons, and a shrunk spec keeps the original's.
fn warnings(info: &std::panic::PanicHookInfo<'_>) -> String {
    let payload = info.payload();
    let text = payload
        .downcast_ref::<String>()
        .map(String::as_str)
        .or_else(|| payload.downcast_ref::<&str>().copied())
        .unwrap_or("");
    let mut flags: Vec<&str> = text
        .match_indices("[-W")
        .filter_map(|(i, _)| Some(&text[i..i + text[i..].find(']')? + 1]))
        .collect();
    flags.sort_unstable();
    flags.dedup();
    flags.concat()
}

/// `check_spec` on the valid spec `text` (written to `path`): what it compared, or the site
/// where it panicked (`None` for a spec the front end refuses).
fn run(text: &str, path: &Path) -> Result<String, Option<String>> {
    let source = SpecSource::new("shrunk.toml", text.to_string());
    protocol_spec::compile(&source).map_err(|_| None)?;
    std::fs::write(path, text).expect("write the spec");
    *panic_site().lock().unwrap_or_else(|e| e.into_inner()) = None;
    match catch_unwind(AssertUnwindSafe(|| super::check_spec(path, 1000))) {
        Ok((_, what)) => Ok(what),
        Err(_) => Err(panic_site()
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .clone()),
    }
}

/// The failing spec `text` of `seed` shrunk to a smaller one that fails at the same site,
/// printed, and kept as a fixture with `RANDOM_SPECS_KEEP=1`.
fn shrink_failure(seed: u64, text: &str, site: &str, dir: &Path) {
    let budget = var("RANDOM_SPECS_SHRINK", 300) as usize;
    if budget == 0 {
        return;
    }
    let path = dir.join(format!("rand_{seed}.toml"));
    // The candidates' panics are expected: their messages would bury the result.
    record_panics(true);
    let shrunk = shrink::shrink(text, budget, |t| {
        run(t, &path).err().flatten().as_deref() == Some(site)
    });
    record_panics(false);
    eprintln!(
        "seed {seed}: shrunk from {} to {} lines, still failing at {site}:\n{shrunk}",
        text.lines().count(),
        shrunk.lines().count()
    );
    if var("RANDOM_SPECS_KEEP", 0) == 1 {
        let fixture = super::root().join(format!("protocol-cli/tests/c_peer/rand_{seed}.toml"));
        std::fs::write(&fixture, &shrunk).expect("write the fixture");
        eprintln!("seed {seed}: kept as {}", fixture.display());
    }
}

/// The random frames a comparison's summary counts (`..., 2000 random frames (...`).
fn random_frames(what: &str) -> usize {
    what.find(" random frames")
        .and_then(|end| what[..end].rsplit(' ').next()?.parse().ok())
        .unwrap_or(0)
}

/// The specs to compare: the batch's, or the one of `RANDOM_SPEC_FILE` (its protocol named
/// `rand_SEED`), to check a shrunk or kept spec by hand.
fn specs() -> Vec<(u64, String)> {
    if let Ok(path) = std::env::var("RANDOM_SPEC_FILE") {
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let seed = text
            .lines()
            .find_map(|l| {
                l.strip_prefix("name = \"rand_")?
                    .strip_suffix('"')?
                    .parse()
                    .ok()
            })
            .unwrap_or_else(|| panic!("{path}: its protocol is not named `rand_SEED`"));
        return vec![(seed, text)];
    }
    let (first, count) = batch();
    eprintln!(
        "random specs: seeds {first}..{} ({count} specs)",
        first + count
    );
    (first..first + count)
        .map(|seed| (seed, random_spec::spec(seed, &format!("rand_{seed}"))))
        .collect()
}

#[test]
fn random_specs_agree_in_c_and_rust() {
    let specs = specs();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let (mut refused, mut frames) = (0, 0);
    let mut failed = Vec::new();
    record_panics(false);
    for (seed, text) in &specs {
        let name = format!("rand_{seed}");
        let source = SpecSource::new(format!("{name}.toml"), text.clone());
        if let Err(diagnostics) = protocol_spec::compile(&source) {
            panic!(
                "seed {seed}: the generator wrote a spec the front end refuses:\n{text}\n{}",
                render_all(&diagnostics, &source)
            );
        }
        let path = dir.path().join(format!("{name}.toml"));
        match run(text, &path) {
            Ok(what) => {
                if what.starts_with("refused") {
                    refused += 1;
                }
                frames += random_frames(&what);
                eprintln!("seed {seed}: {what}");
            }
            Err(site) => {
                let site = site.unwrap_or_default();
                eprintln!("seed {seed}: C and Rust disagree (at {site}) on this spec:\n{text}");
                shrink_failure(*seed, text, &site, dir.path());
                failed.push(*seed);
            }
        }
    }
    let _ = std::panic::take_hook();
    eprintln!(
        "random specs: {} specs, {} refused by the C printer, {frames} random frames compared, {} failing: {failed:?}",
        specs.len(),
        refused,
        failed.len()
    );
    assert!(failed.is_empty(), "C and Rust disagree on seeds {failed:?}");
    // A batch the C printer refuses whole compares nothing.
    assert!(
        refused < specs.len(),
        "the C printer refuses all {} random specs",
        specs.len()
    );
}
