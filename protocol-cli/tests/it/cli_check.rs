//! `protocol check`, `doc`, `expand` and `diff`, run as processes: located diagnostics of a bad
//! spec (text and JSON), the Markdown reference, the expansion, and the compatibility report's
//! exit status.

use crate::support;

use protocol_codegen::codegen::{RuntimePath, expand_pretty};
use serde_json::Value;
use support::{interpreter, protocol, root, text};

const BAD: &str = "protocol-cli/tests/fixtures/bad.toml";

/// Line and column (1-based) of the first `needle` in the bad fixture.
fn position_of(needle: &str) -> (usize, usize) {
    let source = std::fs::read_to_string(root().join(BAD)).expect("fixture");
    let at = source.find(needle).expect("needle in the fixture");
    let line = source[..at].matches('\n').count() + 1;
    let col = at - source[..at].rfind('\n').map_or(0, |i| i + 1) + 1;
    (line, col)
}

/// Where each mistake of the fixture is, and what its message says.
fn mistakes() -> Vec<((usize, usize), &'static str)> {
    vec![
        (
            position_of("1 }\nMOVE"),
            "command `PONG` reuses the id of `PING`",
        ),
        (position_of("\"Moov\""), "unknown struct `Moov`"),
        (position_of("\"flaot\""), "unknown type `flaot`"),
    ]
}

#[test]
fn good_specs_check_and_bad_ones_fail_with_located_diagnostics() {
    let good = protocol(&["check", "specs/hflink.toml", "specs/referee.toml"], b"");
    assert!(good.status.success(), "{}", text(&good.stderr));
    assert!(text(&good.stdout).contains("specs/hflink.toml: ok (27 commands"));

    let bad = protocol(&["check", "specs/hflink.toml", BAD], b"");
    assert_eq!(bad.status.code(), Some(1));
    let stderr = text(&bad.stderr);
    for ((line, col), message) in mistakes() {
        assert!(stderr.contains(message), "{stderr}");
        assert!(
            stderr.contains(&format!("--> {BAD}:{line}:{col}\n")),
            "{message} at {line}:{col}:\n{stderr}"
        );
    }
    // The spec line is quoted, the span underlined, the help given.
    assert!(
        stderr.contains("18 | MOVE = { id = 2, payload = \"Moov\" }"),
        "{stderr}"
    );
    assert!(
        stderr.contains("help: declare it as `[structs.NAME]`"),
        "{stderr}"
    );
    assert!(
        stderr.contains(&format!("3 errors in spec {BAD}\n")),
        "{stderr}"
    );
    // The good spec of the same run is still checked.
    assert!(text(&bad.stdout).contains("specs/hflink.toml: ok"));
}

#[test]
fn json_diagnostics_for_editors_and_ci() {
    let out = protocol(
        &[
            "check",
            "--json",
            BAD,
            "specs/hflink.toml",
            "specs/missing.toml",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1));
    let all: Vec<Value> = serde_json::from_slice(&out.stdout).expect("one JSON array");
    assert_eq!(all.len(), 4, "three mistakes and a missing file: {all:?}");
    for (d, ((line, col), message)) in all.iter().zip(mistakes()) {
        assert_eq!(d["file"], BAD);
        assert_eq!(
            (d["line"].as_u64(), d["column"].as_u64()),
            (Some(line as u64), Some(col as u64)),
            "{d}"
        );
        assert_eq!(d["message"], message);
        assert_eq!(d["severity"], "error");
        assert!(d["help"].is_string(), "{d}");
        assert!(d["end_column"].as_u64() > d["column"].as_u64(), "{d}");
    }
    assert_eq!(all[3]["file"], "specs/missing.toml");
    assert!(
        all[3]["message"]
            .as_str()
            .is_some_and(|m| m.contains("cannot read spec"))
    );
    let clean = protocol(&["check", "--json", "specs/scout.toml"], b"");
    assert!(clean.status.success());
    assert_eq!(text(&clean.stdout).trim(), "[]");
}

#[test]
fn commands_that_need_a_valid_spec_refuse_a_bad_one() {
    for args in [
        vec!["doc", BAD],
        vec!["expand", BAD],
        vec!["decode", BAD, "-"],
        vec!["encode", BAD],
    ] {
        let out = protocol(&args, b"");
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = text(&out.stderr);
        assert!(
            stderr.contains("unknown struct `Moov`") && stderr.contains(&format!("{BAD}:")),
            "{args:?}: {stderr}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

#[test]
fn doc_renders_every_section_and_every_struct() {
    for spec in ["hflink", "referee", "scout"] {
        let path = format!("specs/{spec}.toml");
        let out = protocol(&["doc", &path], b"");
        assert!(out.status.success(), "{}", text(&out.stderr));
        let md = text(&out.stdout);
        let interp = interpreter(spec);
        let p = interp.protocol();
        assert!(md.starts_with(&format!("# {}\n", p.name)), "{spec}");
        for section in [
            "## Frame formats",
            "## Commands",
            "## Structs",
            "| offset | size | element |",
        ] {
            assert!(md.contains(section), "{spec} lacks {section}");
        }
        for f in &p.frames {
            assert!(
                md.contains(&format!("### `{}`", f.name)),
                "{spec}: frame {}",
                f.name
            );
        }
        for c in &p.commands {
            assert!(
                md.contains(&format!("| `{}` |", c.name)),
                "{spec}: command {}",
                c.name
            );
        }
        for s in &p.structs {
            assert!(
                md.contains(&format!("### {}\n", s.name)),
                "{spec}: struct {}",
                s.name
            );
        }
        for e in &p.enums {
            assert!(
                md.contains(&format!("### {}\n", e.name)),
                "{spec}: enum {}",
                e.name
            );
        }
        let file = tempfile::NamedTempFile::new().expect("temp file");
        let to_file = protocol(
            &[
                "doc",
                &path,
                "-o",
                file.path().to_str().expect("utf-8 path"),
            ],
            b"",
        );
        assert!(to_file.status.success() && to_file.stdout.is_empty());
        assert_eq!(std::fs::read_to_string(file.path()).expect("written"), md);
    }
}

#[test]
fn expand_prints_the_macro_expansion() {
    let out = protocol(&["expand", "specs/hflink.toml"], b"");
    assert!(out.status.success());
    let interp = interpreter("hflink");
    assert_eq!(
        text(&out.stdout),
        expand_pretty(interp.protocol(), &RuntimePath::default())
    );
    assert!(text(&out.stdout).contains("pub mod hflink {"));
}

/// Writes `specs/NAME.toml` edited by `edit` to a temporary file.
fn edited(name: &str, edit: impl Fn(&str) -> String) -> tempfile::NamedTempFile {
    let source = std::fs::read_to_string(root().join(format!("specs/{name}.toml"))).expect("spec");
    let edited = edit(&source);
    assert_ne!(edited, source, "the edit changes the spec");
    let file = tempfile::Builder::new()
        .suffix(".toml")
        .tempfile()
        .expect("temp file");
    std::fs::write(file.path(), edited).expect("written");
    file
}

#[test]
fn diff_exit_status_guards_a_ci() {
    let same = protocol(&["diff", "specs/hflink.toml", "specs/hflink.toml"], b"");
    assert!(same.status.success());
    assert!(
        text(&same.stdout)
            .contains("0 breaking, 0 source-breaking, 0 compatible: wire- and source-compatible"),
        "{}",
        text(&same.stdout)
    );

    let added = edited("hflink", |s| {
        s.replace(
            "[structs.ChassisCoord]",
            "READ_BATTERY = { id = 27, response = \"SystemInfo\" }\n\n[structs.ChassisCoord]",
        )
    });
    let out = protocol(
        &[
            "diff",
            "specs/hflink.toml",
            added.path().to_str().expect("path"),
        ],
        b"",
    );
    assert_eq!(
        out.status.code(),
        Some(1),
        "an added command breaks exhaustive matches: {}",
        text(&out.stdout)
    );
    assert!(
        text(&out.stdout).contains("source-breaking  command READ_BATTERY (id 0x1b): added"),
        "{}",
        text(&out.stdout)
    );
    let doc_only = edited("hflink", |s| {
        s.replacen(
            "doc = \"Read the GPS fix.\"",
            "doc = \"Read the latest GPS fix.\"",
            1,
        )
    });
    let out = protocol(
        &[
            "diff",
            "specs/hflink.toml",
            doc_only.path().to_str().expect("path"),
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    assert!(
        text(&out.stdout).contains("0 breaking, 0 source-breaking, 1 compatible"),
        "{}",
        text(&out.stdout)
    );

    let retyped = edited("hflink", |s| {
        s.replace(
            "{ name = \"cpu_usage\", type = \"f32\" }",
            "{ name = \"cpu_usage\", type = \"u32\" }",
        )
    });
    let out = protocol(
        &[
            "diff",
            "specs/hflink.toml",
            retyped.path().to_str().expect("path"),
            "--json",
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1));
    let report: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(report["wire_compatible"], false);
    assert_eq!(report["source_compatible"], false);
    let reasons: Vec<&str> = report["changes"]
        .as_array()
        .expect("changes")
        .iter()
        .filter_map(|c| c["reason"].as_str())
        .collect();
    assert!(
        reasons.iter().any(|r| r
            .contains("field `cpu_usage` (offset 8): f32 (little-endian) → u32 (little-endian)")),
        "{reasons:?}"
    );

    let renamed = edited("hflink", |s| {
        s.replace("{ name = \"cpu_usage\"", "{ name = \"cpu_load\"")
    });
    let out = protocol(
        &[
            "diff",
            "specs/hflink.toml",
            renamed.path().to_str().expect("path"),
        ],
        b"",
    );
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stdout));
    assert!(
        text(&out.stdout).contains("renamed from `cpu_usage`")
            && text(&out.stdout)
                .contains("0 breaking, 1 source-breaking, 0 compatible: wire-compatible, NOT source-compatible"),
        "a renamed field keeps the wire and breaks the source:\n{}",
        text(&out.stdout)
    );

    let invalid = protocol(&["diff", "specs/hflink.toml", BAD], b"");
    assert_eq!(
        invalid.status.code(),
        Some(2),
        "an invalid spec cannot be compared"
    );
    let unreadable = protocol(
        &["diff", "specs/hflink.toml", "specs/no-such-spec.toml"],
        b"",
    );
    assert_eq!(
        unreadable.status.code(),
        Some(2),
        "an unreadable spec cannot be compared: {}",
        text(&unreadable.stderr)
    );
    assert!(text(&unreadable.stderr).contains("no-such-spec.toml"));
}

#[test]
fn diff_help_states_the_exit_statuses() {
    let out = protocol(&["diff", "--help"], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let help = text(&out.stdout);
    for line in [
        "Exit status:",
        "  0  compatible at both levels",
        "  1  anything breaks",
        "  2  a spec cannot be read or is invalid",
    ] {
        assert!(help.contains(line), "`{line}` is not in:\n{help}");
    }
}

#[test]
fn a_frame_without_a_check_is_a_warning_not_an_error() {
    const UNCHECKED: &str = "protocol-cli/tests/fixtures/unchecked.toml";
    let out = protocol(&["check", UNCHECKED], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("frame `main` has no check"), "{stderr}");
    assert!(
        stderr.contains(&format!("--> {UNCHECKED}:4:9\n")),
        "{stderr}"
    );
    assert!(text(&out.stdout).contains(&format!("{UNCHECKED}: ok (1 command")));
    let json = protocol(&["check", "--json", UNCHECKED], b"");
    assert!(json.status.success());
    let v: Value = serde_json::from_str(&text(&json.stdout)).expect("JSON");
    let items = v.as_array().expect("an array");
    assert_eq!(items.len(), 1, "{v}");
    assert_eq!(items[0]["severity"], "warning");
    assert_eq!(items[0]["line"], 4);
}
