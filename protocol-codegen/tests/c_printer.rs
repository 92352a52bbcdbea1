//! The C printer (`protocol_codegen::c`): snapshots of the C printed for HFLink, header and
//! source, reviewed like code; and the refusal of features it does not print yet. Whether the
//! printed C is right is tested against the Rust codec in `protocol-cli/tests/c_peer.rs`.

use protocol_codegen::diag::render_all;
use protocol_codegen::ir::Protocol;
use protocol_codegen::source::SpecSource;

fn compile(path: &str) -> Protocol {
    let full = format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(full).expect("spec");
    let source = SpecSource::new(path, text);
    protocol_codegen::compile(&source).unwrap_or_else(|d| panic!("{}", render_all(&d, &source)))
}

#[test]
fn hflink_c() {
    let p = compile("specs/hflink.toml");
    let files = protocol_codegen::c::generate(&p).expect("hflink prints in C");
    assert_eq!(
        protocol_codegen::c::generate(&p),
        Ok(files.clone()),
        "deterministic"
    );
    assert_eq!(
        (files.header_name.as_str(), files.source_name.as_str()),
        ("hflink.h", "hflink.c")
    );
    insta::assert_snapshot!("hflink_h", files.header);
    insta::assert_snapshot!("hflink_c", files.source);
}

#[test]
fn unsupported_features_are_refused_not_printed() {
    let p = compile("specs/scout.toml");
    let refused = protocol_codegen::c::generate(&p).expect_err("scout has a CAN frame");
    assert!(
        refused.iter().any(|r| r.contains("CAN transport")),
        "{refused:?}"
    );
    assert!(
        refused
            .iter()
            .any(|r| r == "2 frame formats: the C printer supports exactly one"),
        "{refused:?}"
    );
    assert_eq!(refused, protocol_codegen::c::unsupported(&p));
}

#[test]
fn a_flag_trailer_is_refused_not_printed() {
    let p = compile("specs/mavlink.toml");
    let refused = protocol_codegen::c::unsupported(&p);
    assert!(
        refused.iter().any(
            |r| r == "frame `v2`: optional bytes `signature` present when a header flag is set"
        ),
        "{refused:?}"
    );
}

#[test]
fn a_wider_length_is_refused_not_printed() {
    let p = compile("specs/msp.toml");
    let refused = protocol_codegen::c::unsupported(&p);
    assert!(
        refused
            .iter()
            .any(|r| r
                == "frame `v1`: a wider length announced by a marker value of the length field"),
        "{refused:?}"
    );
}
