//! The rule catalogue: `tests/invalid/` holds one small spec per validation rule, each with
//! exactly the mistake its file name says. `diagnostics.rs` snapshots their rendering; this test
//! checks the catalogue itself: its size, that every fixture has its snapshot (and no snapshot
//! outlives its fixture), that every error is located in the fixture (path, line, column, the
//! quoted line), that one mistake gives one error, and that a spec with several mistakes gets
//! all of them reported.

use std::path::{Path, PathBuf};

use protocol_codegen::diag::Diagnostic;
use protocol_codegen::source::SpecSource;

/// Fixtures that hold several mistakes on purpose, with the number of errors each must get;
/// every other fixture holds exactly one mistake.
const SEVERAL: &[(&str, usize)] = &[
    ("several_errors.toml", 2),
    ("many_errors_at_once.toml", 5),
    // A broken frame and a badly named command: the frame's error does not hide the command's.
    ("frame_error_hides_command_errors.toml", 2),
    ("several_errors_across_sections.toml", 7),
    // `u48`, `f16` and `u12be`: three widths the wire does not have.
    ("type_width_not_on_the_wire.toml", 3),
    // A misspelled key in the frame layout, a command, a struct, an enum and a checksum: no
    // table's error hides another's, and none of them cascades.
    ("every_table_reports_at_once.toml", 5),
];

/// The least number of fixtures the catalogue may hold: it grows, it never shrinks below this.
const MIN_FIXTURES: usize = 45;

const SNAPSHOT_PREFIX: &str = "it__diagnostics__invalid_specs_render_located_diagnostics@";

fn dir(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(name)
}

/// Every fixture: (file name, text), sorted by name.
fn fixtures() -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(dir("invalid"))
        .expect("tests/invalid")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .map(|p| {
            let name = p.file_name().and_then(|n| n.to_str()).expect("utf-8 name");
            (
                name.to_string(),
                std::fs::read_to_string(&p).expect("fixture"),
            )
        })
        .collect();
    out.sort();
    out
}

fn diagnose(name: &str, text: &str) -> (SpecSource, Vec<Diagnostic>) {
    let source = SpecSource::new(format!("tests/invalid/{name}"), text);
    match protocol_codegen::compile(&source) {
        Ok(_) => panic!("tests/invalid/{name} compiles, but it is an invalid fixture"),
        Err(diags) => (source, diags),
    }
}

/// The `--> path:line:col` of a rendered diagnostic, and the quoted line after `N | `.
fn location(rendered: &str, path: &str) -> Option<(usize, usize, String)> {
    let marker = format!("--> {path}:");
    let rest = rendered
        .lines()
        .find_map(|l| l.trim().strip_prefix(&marker))?;
    let (line, col) = rest.split_once(':')?;
    let line: usize = line.parse().ok()?;
    let col: usize = col.parse().ok()?;
    let gutter = format!("{line} | ");
    let quoted = rendered
        .lines()
        .find_map(|l| l.strip_prefix(&gutter))
        .unwrap_or_default()
        .to_string();
    Some((line, col, quoted))
}

#[test]
fn the_catalogue_has_a_fixture_per_rule_and_a_snapshot_per_fixture() {
    let names: Vec<String> = fixtures().into_iter().map(|(n, _)| n).collect();
    assert!(
        names.len() >= MIN_FIXTURES,
        "{} fixtures in tests/invalid/, the catalogue needs at least {MIN_FIXTURES}",
        names.len()
    );
    for (several, _) in SEVERAL {
        assert!(
            names.iter().any(|n| n == several),
            "missing fixture {several}"
        );
    }
    let snapshots: Vec<String> = std::fs::read_dir(dir("it/snapshots"))
        .expect("tests/it/snapshots")
        .filter_map(|e| e.expect("entry").file_name().into_string().ok())
        .filter_map(|n| {
            n.strip_prefix(SNAPSHOT_PREFIX)
                .and_then(|n| n.strip_suffix(".snap"))
                .map(str::to_string)
        })
        .collect();
    for name in &names {
        assert!(
            snapshots.contains(name),
            "tests/invalid/{name} has no snapshot; run `INSTA_UPDATE=always cargo test -p protocol-codegen --test it -- diagnostics::` and review it"
        );
    }
    for snap in &snapshots {
        assert!(
            names.contains(snap),
            "snapshot of `{snap}` has no fixture in tests/invalid/; delete it"
        );
    }
}

#[test]
fn every_error_points_at_a_line_and_column_of_its_fixture() {
    for (name, text) in fixtures() {
        let (source, diags) = diagnose(&name, &text);
        assert!(!diags.is_empty(), "{name}: no error");
        let lines: Vec<&str> = text.lines().collect();
        for d in &diags {
            let rendered = d.render(&source);
            let (line, col, quoted) = location(&rendered, &source.path)
                .unwrap_or_else(|| panic!("{name}: no `--> {}:L:C` in\n{rendered}", source.path));
            assert!(
                (1..=lines.len().max(1)).contains(&line),
                "{name}: line {line} is outside the file\n{rendered}"
            );
            let text_line = lines.get(line - 1).copied().unwrap_or("");
            assert!(
                col >= 1 && col <= text_line.chars().count() + 1,
                "{name}: column {col} is outside line {line}\n{rendered}"
            );
            assert_eq!(
                quoted, text_line,
                "{name}: the quoted line is not line {line} of the fixture\n{rendered}"
            );
            assert!(
                d.help.as_deref().is_some_and(|h| !h.trim().is_empty()),
                "{name}: an error without help\n{rendered}"
            );
        }
    }
}

#[test]
fn one_mistake_gives_one_error() {
    for (name, text) in fixtures() {
        if SEVERAL.iter().any(|(n, _)| *n == name) {
            continue;
        }
        let (source, diags) = diagnose(&name, &text);
        let rendered: Vec<String> = diags.iter().map(|d| d.render(&source)).collect();
        assert_eq!(
            diags.len(),
            1,
            "{name} holds one mistake but gets {} errors:\n{}",
            diags.len(),
            rendered.join("\n")
        );
    }
}

#[test]
fn several_mistakes_are_all_reported() {
    let all = fixtures();
    for (name, planted) in SEVERAL {
        let (_, text) = all
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("missing fixture {name}"));
        let (source, diags) = diagnose(name, text);
        assert_eq!(
            diags.len(),
            *planted,
            "{name}: {planted} mistakes, {} errors",
            diags.len()
        );
        // Each error points at its own mistake: no two share a position.
        let mut starts: Vec<(usize, usize)> = diags
            .iter()
            .map(|d| source.line_col(d.span.start))
            .collect();
        starts.dedup();
        assert_eq!(starts.len(), *planted, "{name}: two errors at one position");
    }
}
