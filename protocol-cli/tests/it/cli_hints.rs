//! The hints of `protocol decode` and the Markdown of `protocol doc` say what applies: a hint
//! to input read as hex does not suggest `--hex`; a capture whose every candidate failed on its
//! length or its check is asked about those rules; a check's byte order is documented.

use crate::support;

use support::{protocol, root, text};

/// `specs/NAME.toml` edited by `edit`, in a temporary file.
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

/// The HFLink capture, as hex text.
fn hflink_capture_hex() -> Vec<u8> {
    let bytes = std::fs::read(root().join("examples/captures/hflink.bin")).expect("capture");
    let hex: Vec<String> = bytes.iter().map(|b| format!("{b:02x}")).collect();
    hex.join(" ").into_bytes()
}

#[test]
fn a_hint_to_hex_input_does_not_suggest_hex() {
    let hex = hflink_capture_hex();
    let out = protocol(
        &["decode", "specs/scout.toml", "--hex", "--format", "json"],
        &hex,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains("hint: 0 of 3706 bytes decoded as `uart` frames of scout: is this a capture of that link?"),
        "{err}"
    );
    assert!(!err.contains("--hex"), "{err}");

    // Binary input is still asked whether it is hex text.
    let out = protocol(
        &[
            "decode",
            "specs/scout.toml",
            "examples/captures/hflink.bin",
            "--format",
            "json",
        ],
        b"",
    );
    let err = text(&out.stderr);
    assert!(
        err.contains("is this a capture of that link, or hex text (`--hex`)?"),
        "{err}"
    );
}

/// The HFLink capture read with a spec whose check is a plain byte sum instead of HFLink's sum
/// modulo 255: every frame is found by its sync and fails its check.
#[test]
fn every_candidate_failing_its_length_or_check_is_asked_about_those_rules() {
    let spec = edited("hflink", |s| s.replacen("\"sum-mod-255\"", "\"sum8\"", 1));
    let spec_path = spec.path().to_str().expect("a UTF-8 path");
    let out = protocol(
        &[
            "decode",
            spec_path,
            "examples/captures/hflink.bin",
            "--format",
            "json",
            "--stats",
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let err = text(&out.stderr);
    assert!(
        err.contains(
            "hint: 0 of 3706 bytes decoded as `link` frames of hflink: every candidate failed on \
             its length (10) or its check (252): is the length or check rule right?"
        ),
        "{err}"
    );
    assert!(!err.contains("is this a capture"), "{err}");
    // The counts are the engine's, as `--stats` prints them.
    assert!(err.contains("checksum failures: 252"), "{err}");
    assert!(err.contains("length rejections: 10"), "{err}");
}

/// Two specs that differ only in their check's byte order document differently.
#[test]
fn doc_states_a_checks_byte_order() {
    let little = protocol(&["doc", "specs/ubx.toml"], b"");
    assert!(little.status.success(), "{}", text(&little.stderr));
    let big_spec = edited("ubx", |s| {
        s.replacen(
            "over = \"class..payload\", byte_order = \"little\"",
            "over = \"class..payload\", byte_order = \"big\"",
            1,
        )
    });
    let big = protocol(
        &["doc", big_spec.path().to_str().expect("a UTF-8 path")],
        b"",
    );
    assert!(big.status.success(), "{}", text(&big.stderr));
    let (little, big) = (text(&little.stdout), text(&big.stdout));
    assert!(
        little.contains("ck covers bytes 2 .. end - 2, stored little-endian\n"),
        "{little}"
    );
    assert!(
        big.contains("ck covers bytes 2 .. end - 2, stored big-endian\n"),
        "{big}"
    );
    assert_ne!(little, big);
}

/// A one-byte check has no byte order, and none is stated.
#[test]
fn doc_states_no_byte_order_for_a_one_byte_check() {
    let out = protocol(&["doc", "specs/hflink.toml"], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let doc = text(&out.stdout);
    assert!(doc.contains(" covers bytes 0 .. end - 1\n"), "{doc}");
    assert!(!doc.contains("stored"), "{doc}");
}
