//! Every lint fixture in `tests/lints/` compiles (a lint never fails the macro) and renders its
//! warnings into an insta snapshot; the reference specs give none, but SBUS (which has no check)
//! gets its one.

use protocol_codegen::diag::{Severity, render_all};
use protocol_codegen::lint::lint;
use protocol_codegen::source::SpecSource;

#[test]
fn lint_fixtures_compile_and_render_their_warnings() {
    insta::glob!("../lints", "*.toml", |path| {
        let text = std::fs::read_to_string(path).expect("fixture");
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("spec.toml");
        let source = SpecSource::new(format!("tests/lints/{name}"), text);
        if let Err(d) = protocol_codegen::compile(&source) {
            panic!("{name} must compile:\n{}", render_all(&d, &source));
        }
        let warnings = lint(&source);
        assert!(!warnings.is_empty(), "{name} gives no warning");
        assert!(warnings.iter().all(|w| w.severity == Severity::Warning));
        insta::assert_snapshot!(render_all(&warnings, &source));
    });
}

/// The registry of bundled specs (`tests/catalogue.toml`).
#[path = "../../../tests/catalogue.rs"]
mod catalogue;

/// Every bundled spec the registry holds to no warning (a spec that skips `lints` says why).
#[test]
fn the_reference_specs_give_no_warning() {
    let catalogue = catalogue::load();
    for name in catalogue.taking("lints").map(catalogue::Entry::stem) {
        let path = format!("{}/../specs/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("spec");
        let source = SpecSource::new(format!("specs/{name}.toml"), text);
        let warnings = lint(&source);
        assert!(warnings.is_empty(), "{}", render_all(&warnings, &source));
    }
}

/// SBUS carries no check: its spec gets exactly the warning about that, on its frame format.
#[test]
fn the_sbus_spec_gets_the_warning_for_a_frame_without_check() {
    let path = format!("{}/../specs/sbus.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("spec");
    let source = SpecSource::new("specs/sbus.toml", text);
    let warnings = lint(&source);
    let rendered = render_all(&warnings, &source);
    assert_eq!(warnings.len(), 1, "{rendered}");
    assert!(rendered.contains("frame `sbus` has no check"), "{rendered}");
}
