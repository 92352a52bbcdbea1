//! The registry of bundled specs (`tests/catalogue.toml`) against the repository: it lists every
//! spec of `specs/` under the spec's own name, the files it names exist, and every list that
//! must stay a literal (a `protocol!` line takes a path literal; a fuzz target is a file of its
//! own; documents are prose) names every spec the registry gives it. Each test reports all the
//! mistakes it finds at once, each naming the file to edit.

use std::path::{Path, PathBuf};

use crate::registry as catalogue;
use catalogue::{Catalogue, Entry};

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The text of a file of the repository (`path` from the root).
fn read(path: &str) -> String {
    std::fs::read_to_string(root().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Fails with every mistake, one per line, after `what`.
fn report(what: &str, mistakes: &[String]) {
    assert!(
        mistakes.is_empty(),
        "{what}:\n{}",
        mistakes
            .iter()
            .map(|m| format!("  {m}"))
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// The files of a directory (from the root) whose names end with `ext`, sorted.
fn files_in(dir: &str, ext: &str) -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(root().join(dir))
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(ext))
        .collect();
    out.sort();
    out
}

/// The protocol name a spec's text gives (`[protocol] name`).
fn spec_name(text: &str) -> Option<String> {
    let table: toml::Table = text.parse().ok()?;
    Some(table.get("protocol")?.get("name")?.as_str()?.to_string())
}

/// Every spec of `specs/` has one entry, under the name its `[protocol]` table gives; every
/// entry's spec exists.
#[test]
fn every_spec_is_registered_under_its_name() {
    let catalogue = catalogue::load();
    let mut mistakes = Vec::new();
    let found = files_in("specs", ".toml");
    for file in &found {
        if catalogue.by_file(file).is_none() {
            mistakes.push(format!(
                "specs/{file}: no `[[spec]]` entry in {}",
                catalogue::PATH
            ));
        }
    }
    for e in &catalogue.spec {
        if !found.contains(&e.file) {
            mistakes.push(format!(
                "{}: {} names no file of specs/",
                catalogue::PATH,
                e.file
            ));
            continue;
        }
        let name = spec_name(&read(&e.path()));
        if name.as_deref() != Some(e.name.as_str()) {
            mistakes.push(format!(
                "{}: the entry of {} says `name = {:?}`, the spec {:?}",
                catalogue::PATH,
                e.file,
                e.name,
                name
            ));
        }
    }
    report("the registry and specs/ disagree", &mistakes);
}

/// Every vector file and capture the registry names exists.
#[test]
fn registered_vectors_and_captures_exist() {
    let catalogue = catalogue::load();
    let mut mistakes = Vec::new();
    for e in &catalogue.spec {
        for v in &e.vectors {
            let path = format!("tests/vectors/{}", v.file);
            if !root().join(&path).is_file() {
                mistakes.push(format!(
                    "{path} (of {} in {}): no such file",
                    e.file,
                    catalogue::PATH
                ));
            }
        }
        for c in &e.captures {
            for path in [
                format!("examples/captures/{}.bin", c.name),
                format!("examples/captures/{}.truth.jsonl", c.name),
            ] {
                if !root().join(&path).is_file() {
                    mistakes.push(format!(
                        "{path} (of {} in {}): no such file; `cargo run -p protocol-cli \
                         --example make_captures` writes the captures",
                        e.file,
                        catalogue::PATH
                    ));
                }
            }
        }
    }
    report("the registry names missing files", &mistakes);
}

/// For each spec `suite` takes, `file` (from the root) holds `line(entry)`.
fn literal_names(
    catalogue: &Catalogue,
    suite: &str,
    file: &str,
    line: impl Fn(&Entry) -> String,
    mistakes: &mut Vec<String>,
) {
    let text = read(file);
    for e in catalogue.taking(suite) {
        let wanted = line(e);
        if !text.contains(&wanted) {
            mistakes.push(format!(
                "{file}: no `{wanted}` (or `skip = [\"{suite}\"]` in the entry of {} in {})",
                e.file,
                catalogue::PATH
            ));
        }
    }
}

/// The `protocol!` lines that need a path literal expand every spec their suite takes.
#[test]
fn literal_spec_lists_name_every_registered_spec() {
    let catalogue = catalogue::load();
    let mut mistakes = Vec::new();
    let path = |prefix: &'static str, after: &'static str| {
        move |e: &Entry| {
            format!(
                "protocol_kit::protocol!(\"{prefix}specs/{}\"{after})",
                e.file
            )
        }
    };
    literal_names(
        &catalogue,
        "trybuild",
        "tests/trybuild/ui/pass/every_spec.rs",
        path("", ""),
        &mut mistakes,
    );
    literal_names(
        &catalogue,
        "interp",
        "protocol-dynamic/tests/it/interp_differential.rs",
        path("../", ""),
        &mut mistakes,
    );
    literal_names(
        &catalogue,
        "serde",
        "protocol-dynamic/tests/it/serde_agreement.rs",
        path("../", ", derive(serde)"),
        &mut mistakes,
    );
    report(
        "a literal list of specs misses a registered spec",
        &mistakes,
    );
}

/// Every spec of the robustness suites has its `cargo fuzz` target: a file that fuzzes its
/// decoder and a `[[bin]]` of the fuzz crate (its corpus is checked by `fuzz_corpus`).
#[test]
fn every_robustness_spec_has_a_fuzz_target() {
    let catalogue = catalogue::load();
    let manifest = read("fuzz/Cargo.toml");
    let mut mistakes = Vec::new();
    for e in catalogue.taking("robustness") {
        let target = format!("stream_{}", e.name);
        let file = format!("fuzz/fuzz_targets/{target}.rs");
        let packet = if e.link { "AnyPacket" } else { "Packet" };
        let call = format!("support::{}::{packet}", e.name);
        match std::fs::read_to_string(root().join(&file)) {
            Ok(text) if text.contains(&call) => {}
            Ok(_) => mistakes.push(format!("{file}: does not fuzz `{call}`")),
            Err(_) => mistakes.push(format!(
                "{file}: missing (a copy of another `stream_*.rs` naming `{call}`)"
            )),
        }
        if !manifest.contains(&format!("name = \"{target}\"")) {
            mistakes.push(format!("fuzz/Cargo.toml: no `[[bin]]` named {target:?}"));
        }
    }
    report("a fuzz target is missing", &mistakes);
}

/// The documents that describe every bundled spec name each: the overview's table of specs and
/// the spec format's list (unless the spec skips `docs`), the vector files' table, the
/// captures' table.
#[test]
fn documents_name_every_registered_spec() {
    let catalogue = catalogue::load();
    let mut mistakes = Vec::new();
    literal_names(
        &catalogue,
        "docs",
        "docs/overview.md",
        |e| format!("`{}`", e.path()),
        &mut mistakes,
    );
    literal_names(
        &catalogue,
        "docs",
        "docs/spec-format.md",
        |e| format!("(../{})", e.path()),
        &mut mistakes,
    );
    let vectors = read("tests/vectors/README.md");
    let captures = read("examples/captures/README.md");
    for e in &catalogue.spec {
        for v in &e.vectors {
            if !vectors.contains(&format!("| `{}` |", v.file)) {
                mistakes.push(format!("tests/vectors/README.md: no row of `{}`", v.file));
            }
        }
        for c in &e.captures {
            let row = format!("| `{}.bin` | `{}`", c.name, e.path());
            if !captures.contains(&row) {
                mistakes.push(format!("examples/captures/README.md: no row `{row} ...`"));
            }
        }
    }
    report("a document misses a registered spec", &mistakes);
}
