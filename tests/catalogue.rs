//! The registry of bundled specs (`tests/catalogue.toml`), read: its model, the rules that make
//! an entry well formed, and the lists the suites take from it (which specs a suite runs, which
//! vector files it reads, the options a capture is decoded with), including the
//! `for_each_spec!` macro that `tests/build.rs` and `fuzz/build.rs` write.
//!
//! Build scripts and test crates include this file by path (`#[path]`), so that they read one
//! list without a crate of its own; the registry's text is compiled in, so a change to it
//! rebuilds them. It does not check the registry against the files of the repository (that is
//! `tests/tests/it/catalogue.rs`).
#![allow(dead_code)]

use serde::Deserialize;

/// The registry's path, from the repository's root (for messages).
pub const PATH: &str = "tests/catalogue.toml";

/// The registry's text.
pub const TEXT: &str = include_str!("catalogue.toml");

/// The suites a spec's `skip` may name (the registry's header says what each is).
pub const SPEC_SUITES: &[&str] = &[
    "robustness",
    "no-std",
    "trybuild",
    "lints",
    "serde",
    "interp",
    "exports",
    "dissector",
    "c-peer",
    "python",
    "docs",
];

/// The suites that read vector files: a vector file's `skip` may name these.
pub const VECTOR_SUITES: &[&str] = &["interp", "exports", "dissector", "c-peer", "python"];

/// The registry.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Catalogue {
    /// The bundled specs, in the order the suites run them.
    pub spec: Vec<Entry>,
}

/// One bundled spec.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    /// The protocol's name: its generated module.
    pub name: String,
    /// The spec's file name in `specs/`.
    pub file: String,
    /// The directions given to its decoder (none when a header field tells them).
    #[serde(default)]
    pub directions: Vec<String>,
    /// Whether one decoder finds the link's several frame formats.
    #[serde(default)]
    pub link: bool,
    /// The suites that do not take it.
    #[serde(default)]
    pub skip: Vec<String>,
    /// Its golden-vector files.
    #[serde(default)]
    pub vectors: Vec<Vectors>,
    /// Its captures.
    #[serde(default)]
    pub captures: Vec<Capture>,
}

/// A golden-vector file of a spec.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Vectors {
    /// The file name in `tests/vectors/`.
    pub file: String,
    /// Whether the file's streams yield the spec's frames.
    #[serde(default = "yes")]
    pub streams: bool,
    /// The vector suites that do not read it.
    #[serde(default)]
    pub skip: Vec<String>,
}

/// A capture of a spec.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Capture {
    /// `examples/captures/NAME.bin`.
    pub name: String,
    /// The frame format to decode it with, when not the default.
    #[serde(default)]
    pub frame: Option<String>,
}

fn yes() -> bool {
    true
}

/// The registry, read and checked (a malformed registry panics with every mistake listed:
/// it is a file of the repository, read by tests and build scripts).
pub fn load() -> Catalogue {
    let catalogue: Catalogue =
        toml::from_str(TEXT).unwrap_or_else(|e| panic!("{PATH} does not parse:\n{e}"));
    let mistakes = catalogue.mistakes();
    assert!(mistakes.is_empty(), "{PATH}:\n{}", mistakes.join("\n"));
    catalogue
}

impl Catalogue {
    /// What is wrong with the entries: a suite name no suite has, a name or file given twice.
    fn mistakes(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (i, e) in self.spec.iter().enumerate() {
            for s in e.skip.iter().filter(|s| !SPEC_SUITES.contains(&s.as_str())) {
                out.push(format!("{}: `skip` names no suite: {s:?}", e.file));
            }
            for v in &e.vectors {
                for s in v
                    .skip
                    .iter()
                    .filter(|s| !VECTOR_SUITES.contains(&s.as_str()))
                {
                    out.push(format!(
                        "{} ({}): `skip` names no vector suite: {s:?}",
                        e.file, v.file
                    ));
                }
            }
            let earlier = &self.spec[..i];
            if earlier.iter().any(|o| o.name == e.name || o.file == e.file) {
                out.push(format!("{}: listed twice", e.file));
            }
        }
        out
    }

    /// The specs `suite` takes, in order.
    pub fn taking<'c>(&'c self, suite: &str) -> impl Iterator<Item = &'c Entry> {
        self.spec.iter().filter(move |e| e.takes(suite))
    }

    /// The vector files `suite` reads, each with its spec, in order.
    pub fn vectors<'c>(&'c self, suite: &str) -> impl Iterator<Item = (&'c Entry, &'c Vectors)> {
        self.taking(suite).flat_map(move |e| {
            e.vectors
                .iter()
                .filter(move |v| !v.skip.iter().any(|s| s == suite))
                .map(move |v| (e, v))
        })
    }

    /// The entry of the spec file `file` (`NAME.toml`).
    pub fn by_file(&self, file: &str) -> Option<&Entry> {
        self.spec.iter().find(|e| e.file == file)
    }

    /// The `for_each_spec!` macro of the robustness suites: a line per spec they take, with
    /// what `expand_spec!` takes after the path (the direction and its decoders for a spec
    /// whose directions are given, `link` for a link of several formats). `prefix` leads from
    /// the including crate's manifest directory to the repository's root.
    pub fn for_each_spec_macro(&self, prefix: &str) -> String {
        let lines: String = self
            .taking("robustness")
            .map(|e| {
                let how = match (e.link, e.directions.first()) {
                    (true, _) => ", link".to_string(),
                    (false, Some(d)) => format!(", {d:?}, from_{d}_frame, decode_{d}"),
                    (false, None) => String::new(),
                };
                format!(
                    "        $callback!({}, \"{prefix}specs/{}\"{how});\n",
                    e.name, e.file
                )
            })
            .collect();
        format!(
            "// @generated from {PATH} by the build script.\n\
             /// Calls `$callback!(module, \"path relative to the crate\")` for every spec the\n\
             /// robustness suites take ({PATH}; its header says what follows the path).\n\
             macro_rules! for_each_spec {{\n    ($callback:ident) => {{\n{lines}    }};\n}}\n"
        )
    }
}

impl Entry {
    /// Whether `suite` takes the spec.
    pub fn takes(&self, suite: &str) -> bool {
        !self.skip.iter().any(|s| s == suite)
    }

    /// The spec's path from the repository's root.
    pub fn path(&self) -> String {
        format!("specs/{}", self.file)
    }

    /// The spec file's stem (`mavlink-common` of `mavlink-common.toml`).
    pub fn stem(&self) -> &str {
        self.file.trim_end_matches(".toml")
    }

    /// The options `protocol decode` takes for a capture: its frame format, and the first
    /// direction of a spec whose directions are given.
    pub fn capture_options(&self, capture: &Capture) -> Vec<String> {
        let mut out = Vec::new();
        if let Some(frame) = &capture.frame {
            out.extend(["--frame".to_string(), frame.clone()]);
        }
        if let Some(d) = self.directions.first() {
            out.extend(["--direction".to_string(), d.clone()]);
        }
        out
    }
}
