//! Writes the batch of random specs the `random_specs` test expands with `protocol!`: the
//! specs of the seeded generator (`tests/support/random_spec.rs`) as files in `OUT_DIR`, and a
//! Rust file that expands each and lists them. `RANDOM_SPECS` sets the batch size (default 12)
//! and `RANDOM_SPECS_SEED` its first seed (default 0); both are printed by the test.
//! `RANDOM_SPEC_FILE` names one spec file (its protocol named `rand_SEED`) to expand alone
//! instead: a shrunk failure or a kept fixture, checked by hand.
//!
//! It also writes `for_each_spec!`, the robustness suites' list of bundled specs, from the
//! registry `catalogue.toml` (`catalogue.rs` reads it; the fuzz crate's build script writes
//! the same macro).

use std::fmt::Write as _;
use std::path::{Component, Path, PathBuf};

#[path = "catalogue.rs"]
mod catalogue;
#[path = "tests/support/random_spec.rs"]
mod random_spec;

/// `to` relative to `from` (both absolute): the macro reads spec paths relative to the
/// crate's manifest directory.
fn relative(from: &Path, to: &Path) -> PathBuf {
    let from: Vec<Component<'_>> = from.components().collect();
    let to: Vec<Component<'_>> = to.components().collect();
    let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..from.len() {
        out.push("..");
    }
    for c in &to[common..] {
        out.push(c);
    }
    out
}

fn number(name: &str, default: u64) -> u64 {
    println!("cargo:rerun-if-env-changed={name}");
    std::env::var(name).map_or(default, |v| {
        v.parse()
            .unwrap_or_else(|_| panic!("{name}={v}: not a number"))
    })
}

/// The spec of `RANDOM_SPEC_FILE`, when set, with the seed its protocol's name `rand_SEED`
/// gives: a shrunk or kept random spec, expanded alone in place of the batch.
fn one_file() -> Option<(u64, String)> {
    println!("cargo:rerun-if-env-changed=RANDOM_SPEC_FILE");
    let path = std::env::var("RANDOM_SPEC_FILE").ok()?;
    println!("cargo:rerun-if-changed={path}");
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
    Some((seed, text))
}

fn main() {
    println!("cargo:rerun-if-changed=tests/support/random_spec.rs");
    println!("cargo:rerun-if-changed=tests/support/random_spec");
    println!("cargo:rerun-if-changed=catalogue.rs");
    println!("cargo:rerun-if-changed=catalogue.toml");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR"));
    let specs = catalogue::load().for_each_spec_macro("../");
    std::fs::write(out.join("for_each_spec.rs"), specs).expect("write for_each_spec.rs");
    let first = number("RANDOM_SPECS_SEED", 0);
    let count = number("RANDOM_SPECS", 12);
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").expect("manifest dir"));
    let dir = out.join("random_specs");
    std::fs::create_dir_all(&dir).expect("create the random spec directory");
    let file = one_file();
    let (first, count) = match &file {
        Some((seed, _)) => (*seed, 1),
        None => (first, count),
    };
    let mut code = String::new();
    let mut names = Vec::new();
    let mut sessions = Vec::new();
    // Specs expanded besides the batch (checked with it, not counted in its size).
    let mut extra = Vec::new();
    let mut escaped = false;
    let mut answers = false;
    for seed in first..first + count {
        let name = format!("rand_{seed}");
        let path = dir.join(format!("{name}.toml"));
        let (text, link, given) = match &file {
            Some((_, text)) => (
                text.clone(),
                text.contains("commands = true"),
                text.contains("given = true"),
            ),
            None => {
                let spec = random_spec::generate(seed, &name);
                escaped |= spec.features.contains(&"escape");
                answers |= several_answers(&spec);
                (spec.text, spec.link, spec.given)
            }
        };
        std::fs::write(&path, &text).expect("write a random spec");
        let rel = relative(&manifest, &path);
        let rel = rel.to_str().expect("a UTF-8 path");
        let how = how(link, given);
        writeln!(code, "expand_spec!({name}, {rel:?}{how});").unwrap();
        names.push(format!("{name}{how}"));
        if text.contains("\n[session]") {
            sessions.push(format!("{name}{how}"));
        }
    }
    // A batch without a session (the default twelve may have none) would leave the session
    // comparison nothing to compare, one without a request answered by several devices its
    // several-answer paths, and one without an escaped format would leave the unescaping paths
    // untested: the first later seed whose spec has what the batch lacks is expanded too, for
    // the random spec comparisons (not counted in the batch's size).
    if file.is_none() {
        let later = || {
            (first + count..first + count + 1000)
                .map(|seed| (seed, random_spec::generate(seed, &format!("rand_{seed}"))))
        };
        let mut session_seed = None;
        if sessions.is_empty()
            && let Some((seed, spec)) = later().find(|(_, s)| s.text.contains("\n[session]"))
        {
            sessions.push(write_spec(&dir, &manifest, seed, &spec, &mut code));
            session_seed = Some(seed);
        }
        // Likewise a session with a request answered by several devices (`answers`), rarer:
        // the first of the next few thousand seeds that has one.
        let mut answers_seed = None;
        if !answers
            && let Some((seed, spec)) = (first + count..first + count + 5000)
                .map(|seed| (seed, random_spec::generate(seed, &format!("rand_{seed}"))))
                .find(|(_, s)| several_answers(s))
        {
            if session_seed != Some(seed) {
                sessions.push(write_spec(&dir, &manifest, seed, &spec, &mut code));
            }
            answers_seed = Some((seed, sessions.last().cloned().unwrap_or_default()));
        }
        if !escaped
            && let Some((seed, spec)) = later().find(|(_, s)| s.features.contains(&"escape"))
        {
            extra.push(if session_seed == Some(seed) {
                sessions[0].clone()
            } else if let Some((_, listed)) = answers_seed.clone().filter(|(s, _)| *s == seed) {
                listed
            } else {
                write_spec(&dir, &manifest, seed, &spec, &mut code)
            });
        }
    }
    writeln!(code, "/// The batch: first seed and count.").unwrap();
    writeln!(code, "const BATCH: (u64, u64) = ({first}, {count});").unwrap();
    writeln!(
        code,
        "/// Calls `$callback!(module, ...)` for every random spec, with what `expand_spec!` took after its path.\nmacro_rules! for_each_random_spec {{ ($callback:ident) => {{ {} }}; }}",
        names
            .iter()
            .chain(&extra)
            .map(|n| format!("$callback!({n});"))
            .collect::<String>()
    )
    .unwrap();
    writeln!(
        code,
        "/// `for_each_random_spec!` over the random specs with a `[session]` table.\nmacro_rules! for_each_random_session {{ ($callback:ident) => {{ {} }}; }}",
        sessions
            .iter()
            .map(|n| format!("$callback!({n});"))
            .collect::<String>()
    )
    .unwrap();
    std::fs::write(out.join("random_specs.rs"), code).expect("write random_specs.rs");
}

/// Writes the random spec of `seed` into `dir` and its `expand_spec!` line into `code`;
/// returns what `for_each_random_spec!` lists for it.
fn write_spec(
    dir: &Path,
    manifest: &Path,
    seed: u64,
    spec: &random_spec::Generated,
    code: &mut String,
) -> String {
    let name = format!("rand_{seed}");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, &spec.text).expect("write a random spec");
    let rel = relative(manifest, &path);
    let rel = rel.to_str().expect("a UTF-8 path");
    let how = how(spec.link, spec.given);
    writeln!(code, "expand_spec!({name}, {rel:?}{how});").unwrap();
    format!("{name}{how}")
}

/// Whether `spec` has a request that several devices answer, each named by a whole byte (a
/// one-bit sender names two devices at most: the comparison would see few answers).
fn several_answers(spec: &random_spec::Generated) -> bool {
    spec.features.contains(&"session-answers") && !spec.text.contains("by = \"fuser\"")
}

/// What `expand_spec!` takes after a random spec's path: as `for_each_spec!` says of a link of
/// several formats and of given directions.
fn how(link: bool, given: bool) -> &'static str {
    if link {
        ", link"
    } else if given {
        ", \"request\", from_request_frame, decode_request"
    } else {
        ""
    }
}
