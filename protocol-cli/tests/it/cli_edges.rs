//! The edges of `protocol decode` a new user meets first: hex text that is not hex, a capture
//! of another link, and statistics that add up to the events printed.

use crate::support;

use support::{json_lines, protocol, text};

#[test]
fn bad_hex_names_its_position() {
    let out = protocol(
        &["decode", "specs/hflink.toml", "--hex"],
        b"ff ff 01 11\n00 0d 0q",
    );
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.contains("stdin:2:8: `q` is not a hex digit"), "{err}");
    let out = protocol(&["decode", "specs/hflink.toml", "--hex"], b"ff ff 0");
    assert!(
        text(&out.stderr).contains("stdin:1:7: the last hex digit has no pair"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn a_capture_of_another_link_gets_a_hint() {
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
    assert!(out.status.success());
    let err = text(&out.stderr);
    assert!(
        err.contains("hint: 0 of 3706 bytes decoded as `uart` frames of scout")
            && !err.contains("--frame can"),
        "{err}"
    );
    // The right spec: no hint.
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "--format",
            "json",
        ],
        b"",
    );
    assert!(
        !text(&out.stderr).contains("hint:"),
        "{}",
        text(&out.stderr)
    );
}

#[test]
fn skipped_bytes_in_the_stats_add_up_to_the_events() {
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "--format",
            "json",
            "--stats",
        ],
        b"",
    );
    assert!(out.status.success());
    let lines = json_lines(&out.stdout);
    let event_bytes = |name: &str| -> u64 {
        lines
            .iter()
            .filter(|l| l["event"] == name)
            .map(|l| l["bytes"].as_u64().expect("bytes"))
            .sum()
    };
    let skipped = event_bytes("skipped");
    let rejected: u64 = [
        "bad_checksum",
        "bad_header_check",
        "bad_length",
        "bad_header",
        "bad_trailer",
        "truncated",
    ]
    .iter()
    .map(|n| event_bytes(n))
    .sum();
    let stats = text(&out.stderr);
    let want = format!(
        "bytes skipped: {} (6.4%): {skipped} in skipped events, {rejected} the first bytes of rejected candidates",
        skipped + rejected
    );
    assert!(stats.contains(&want), "`{want}` not in:\n{stats}");
}

#[test]
fn encode_refuses_a_value_its_field_cannot_carry() {
    let spec = "examples/tutorial/specs/rover.toml";
    let out = protocol(
        &["encode", spec, "--hex"],
        b"{\"command\":\"STATUS\",\"payload\":{\"battery\":1234.5,\"odometer\":0}}\n\
          {\"command\":\"STATUS\",\"payload\":{\"battery\":\"NaN\",\"odometer\":0}}\n\
          {\"command\":\"STATUS\",\"payload\":{\"battery\":12.5,\"odometer\":0}}\n",
    );
    assert_eq!(out.status.code(), Some(1), "a refused line fails the run");
    let err = text(&out.stderr);
    assert!(
        err.contains("stdin:1: `payload.battery`: 1234.5 does not fit the raw type u16")
            && err.contains("stdin:2: `payload.battery`: NaN does not fit the raw type u16"),
        "{err}"
    );
    // Only the valid line is written.
    assert_eq!(
        text(&out.stdout).lines().count(),
        1,
        "{}",
        text(&out.stdout)
    );
}
