//! The committed fuzz corpus (`fuzz/corpus/TARGET/`), replayed on stable: every file goes
//! through the entry point its `cargo fuzz` target calls (`support::fuzz`), so a finding that
//! was fixed stays fixed, and CI covers what the fuzzers reached without nightly.

use std::path::{Path, PathBuf};

/// The corpus directory of a target.
fn corpus(target: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/corpus")
        .join(target)
}

/// Every file of a target's corpus, sorted (there must be some).
fn inputs(target: &str) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = corpus(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("corpus entry").path())
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    assert!(!files.is_empty(), "{}: empty corpus", dir.display());
    files
        .into_iter()
        .map(|p| {
            let data = std::fs::read(&p).expect("corpus file");
            (p, data)
        })
        .collect()
}

/// Runs `f` on every input. Each file is named before it runs: the test harness shows the
/// captured output of a failing test, so the last name printed is the input that failed.
fn replay(target: &str, f: impl Fn(&[u8])) {
    for (path, data) in inputs(target) {
        eprintln!("{}", path.display());
        f(&data);
    }
}

macro_rules! stream_corpus {
    ($name:ident, $path:literal $(, $given:tt)*) => {
        #[test]
        fn $name() {
            replay(
                concat!("stream_", stringify!($name)),
                crate::support::fuzz::stream::<crate::support::packet!($name $(, $given)*)>,
            );
        }
    };
}

mod stream {
    use super::*;

    crate::support::for_each_spec!(stream_corpus);
}

#[test]
fn spec() {
    replay("spec", crate::support::fuzz::spec);
}

#[test]
fn interp() {
    replay("interp", crate::support::fuzz::interp_any);
}

/// Every corpus directory belongs to a target this test replays.
#[test]
fn every_corpus_is_replayed() {
    let mut known = vec!["spec".to_string(), "interp".to_string()];
    macro_rules! name {
        ($name:ident, $path:literal $(, $given:tt)*) => {
            known.push(concat!("stream_", stringify!($name)).to_string());
        };
    }
    crate::support::for_each_spec!(name);
    let root = corpus("");
    for entry in std::fs::read_dir(&root).expect("fuzz/corpus") {
        let name = entry
            .expect("entry")
            .file_name()
            .to_string_lossy()
            .into_owned();
        assert!(
            known.contains(&name),
            "fuzz/corpus/{name} is replayed by no test"
        );
    }
}
