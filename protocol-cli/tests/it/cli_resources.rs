//! `protocol check` states what a decoder of each frame format takes, and those are the sizes
//! generated code allocates on this host; a spec above the bound gets a located warning and
//! still checks.

use crate::support;

use support::{protocol, text};

protocol_kit::protocol!("../specs/hflink.toml");

#[test]
fn check_states_the_sizes_generated_code_allocates() {
    let out = protocol(&["check", "specs/hflink.toml"], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let state = size_of::<hflink::Decoder>() - hflink::DECODER_BUFFER_LEN;
    assert_eq!(state, 112, "a 64-bit host's decoder state");
    let expected = format!(
        "  frame `link`: largest frame {} bytes; decoder buffer {} bytes (64-bit hosts) or 384 \
         bytes (32-bit microcontrollers), plus {state} or 104 bytes of state\n",
        hflink::MAX_FRAME_LEN,
        hflink::DECODER_BUFFER_LEN,
    );
    assert!(stdout.contains(&expected), "{stdout}");
}

#[test]
fn a_spec_above_the_bound_is_warned_at_its_payload_and_still_checks() {
    const HUGE: &str = "protocol-cli/tests/fixtures/huge_payload.toml";
    let out = protocol(&["check", HUGE], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("largest frame 4000000009 bytes; decoder buffer 8000000192 bytes"),
        "{stdout}"
    );
    let stderr = text(&out.stderr);
    assert!(
        stderr.contains(
            "warning: frame `main` needs more than 64 KiB of decoder buffer on a microcontroller"
        ),
        "{stderr}"
    );
    assert!(stderr.contains(&format!("--> {HUGE}:10:3\n")), "{stderr}");
}

/// The bundled specs stay under the bound: no warning.
#[test]
fn the_bundled_specs_need_less_than_the_bound() {
    let out = protocol(
        &[
            "check",
            "specs/hflink.toml",
            "specs/ubx.toml",
            "specs/msp.toml",
        ],
        b"",
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        !text(&out.stderr).contains("warning"),
        "{}",
        text(&out.stderr)
    );
}
