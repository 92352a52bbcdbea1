//! Every invalid fixture in `tests/invalid/` renders its diagnostics (file:line:col, the line,
//! a caret underline, help) into an insta snapshot. No rustc involved, so the snapshots do not
//! depend on the toolchain.

use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

#[test]
fn invalid_specs_render_located_diagnostics() {
    insta::glob!("../invalid", "*.toml", |path| {
        let text = std::fs::read_to_string(path).expect("fixture");
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("spec.toml");
        let source = SpecSource::new(format!("tests/invalid/{name}"), text);
        let diags =
            protocol_codegen::compile(&source).expect_err("an invalid fixture must not compile");
        assert!(!diags.is_empty());
        insta::assert_snapshot!(render_all(&diags, &source));
    });
}

#[test]
fn a_missing_spec_file_is_a_compile_error_naming_it() {
    let tokens =
        protocol_codegen::input::protocol_macro(quote::quote!("specs/does_not_exist.toml"));
    let text = tokens.to_string();
    assert!(text.contains("compile_error"), "{text}");
    assert!(
        text.contains("cannot read spec `specs/does_not_exist.toml`"),
        "{text}"
    );
}

#[test]
fn every_bundled_spec_is_valid() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../specs");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).expect("specs/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "toml") {
            let text = std::fs::read_to_string(&path).expect("spec");
            let source = SpecSource::new(
                format!(
                    "specs/{}",
                    path.file_name().and_then(|n| n.to_str()).unwrap_or("")
                ),
                text,
            );
            if let Err(d) = protocol_codegen::compile(&source) {
                panic!("{}", render_all(&d, &source));
            }
            n += 1;
        }
    }
    assert!(n >= 1);
}

/// The catalogue's renderings, fixture by fixture.
fn catalogue() -> Vec<(String, String)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/invalid");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("tests/invalid") {
        let path = entry.expect("entry").path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        let source = SpecSource::new(name, std::fs::read_to_string(&path).expect("fixture"));
        let diags = protocol_codegen::compile(&source).expect_err("invalid");
        out.push((name.to_string(), render_all(&diags, &source)));
    }
    out
}

#[test]
fn messages_say_what_the_spec_author_wrote_never_a_rust_type() {
    // serde's words for the value's Rust type, as a new user met them (`expected struct
    // CrcDef`, `integer ... as i128, expected i64`, `sequence, expected i64`).
    let rust_words = [
        "expected struct",
        "Def`",
        "as i128",
        "expected i64",
        "expected f64",
        "expected u8",
        "sequence",
        "wrong type of value",
        "invalid type",
        "invalid value",
    ];
    for (name, text) in catalogue() {
        for word in rust_words {
            let said = text
                .lines()
                .filter(|l| l.starts_with("error") || l.starts_with("  = help"))
                .any(|l| l.contains(word));
            assert!(!said, "{name} says `{word}`:\n{text}");
        }
    }
}

/// A spec whose first struct field has type `ty` and whose frame's check is `check`.
fn spec_with(check: &str, ty: &str) -> SpecSource {
    SpecSource::new(
        "spec.toml",
        format!(
            r#"[protocol]
name = "demo"

[frames.main]
layout = [
  {{ sync = [0xAA] }},
  {{ field = "length", type = "u8", length_of = "payload" }},
  {{ field = "command", type = "u8" }},
  {{ payload = {{ max = 16 }} }},
  {{ check = "{check}", over = "frame" }},
]
dispatch = ["command"]

[commands]
SET = {{ id = 2, payload = "Speed" }}

[structs.Speed]
fields = [{{ name = "left", type = "{ty}" }}]
"#
        ),
    )
}

fn first_help(source: &SpecSource) -> String {
    let diags = protocol_codegen::compile(source).expect_err("invalid");
    assert_eq!(diags.len(), 1, "{}", render_all(&diags, source));
    diags[0].help.clone().unwrap_or_default()
}

#[test]
fn names_users_know_resolve_and_near_misses_get_the_nearest_meaningful_name() {
    // Catalogue aliases and the 24- and 40-bit widths are names, not typos.
    for check in ["crc-32", "crc-16-ccitt", "CRC-16/CCITT-FALSE", "sum8"] {
        let source = spec_with(check, "u24be");
        if let Err(d) = protocol_codegen::compile(&source) {
            panic!("{check}: {}", render_all(&d, &source));
        }
    }
    // A near miss is answered with what the user most likely meant.
    for (check, meant) in [("crc-32b", "crc-32"), ("crc-16-ccit", "crc-16-ccitt")] {
        let help = first_help(&spec_with(check, "i16"));
        assert_eq!(help, format!("did you mean `{meant}`?"), "{check}");
    }
    for (ty, said) in [
        // Transposed digits: a typo of that type.
        ("u42be", "did you mean `u24be`?"),
        ("i61", "did you mean `i16`?"),
        // A width the wire lacks: the narrowest width that holds it, not the nearest spelling
        // (`u8`, `u16`), which is a different type.
        ("u36", "`u40` holds 36 bits"),
        ("u12be", "`u16be` holds 12 bits"),
        ("f24", "floats are `f16`, `f32`, `f64`"),
    ] {
        let help = first_help(&spec_with("sum8", ty));
        assert!(help.contains(said), "{ty}: {help}");
    }
}
