//! Expansion snapshots: the prettyplease-formatted Rust generated for every spec in `specs/` and
//! for one small fixture per spec-language feature (`tests/features/`). Review a snapshot diff
//! as you would review code. Output must be deterministic: each spec is expanded twice.

use protocol_codegen::codegen::{Derives, RuntimePath, expand_pretty, expand_pretty_with};
use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

fn expand_file(path: &std::path::Path, shown: &str) -> String {
    let text = std::fs::read_to_string(path).expect("spec");
    let source = SpecSource::new(shown, text);
    let protocol = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let once = expand_pretty(&protocol, &RuntimePath::default());
    let twice = expand_pretty(&protocol, &RuntimePath::default());
    assert_eq!(once, twice, "expansion of {shown} is not deterministic");
    once
}

#[test]
fn every_bundled_spec() {
    insta::glob!("../../../specs", "*.toml", |path| {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("spec.toml");
        insta::assert_snapshot!(expand_file(path, &format!("specs/{name}")));
    });
}

#[test]
fn every_feature_fixture() {
    insta::glob!("../features", "*.toml", |path| {
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("spec.toml");
        insta::assert_snapshot!(expand_file(path, &format!("tests/features/{name}")));
    });
}

/// A spec expanded with `derive(serde, defmt)`: the attributes on its structs and enums, and
/// the serde impls of its enums, commands, messages and packets.
#[test]
fn derives_of_serde_and_defmt() {
    let path = "tests/derives/serde_defmt.toml";
    let text = std::fs::read_to_string(path).expect("spec");
    let source = SpecSource::new(path, text);
    let protocol = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let derives = Derives {
        serde: true,
        defmt: true,
    };
    let once = expand_pretty_with(&protocol, &RuntimePath::default(), derives);
    let twice = expand_pretty_with(&protocol, &RuntimePath::default(), derives);
    assert_eq!(once, twice, "expansion of {path} is not deterministic");
    insta::assert_snapshot!(once);
}
