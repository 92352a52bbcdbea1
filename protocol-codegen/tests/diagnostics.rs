//! Every invalid fixture in `tests/invalid/` renders its diagnostics (file:line:col, the line,
//! a caret underline, help) into an insta snapshot. No rustc involved, so the snapshots do not
//! depend on the toolchain.

use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

#[test]
fn invalid_specs_render_located_diagnostics() {
    insta::glob!("invalid/*.toml", |path| {
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
