//! A frame format whose decoder buffer no object of a target can hold is refused on that target
//! with a `compile_error!` behind a `cfg` of its pointer width, naming the spec line of the
//! payload; a buffer that fits gets no refusal. (The refusal fires only in a build for such a
//! target, `thumbv7em-none-eabihf` in `.ci/run`; here the expansion is read.)

use protocol_codegen::codegen::{RuntimePath, expand_pretty};
use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

/// The expansion of `text`, shown as `path`.
fn expand(path: &str, text: &str) -> String {
    let source = SpecSource::new(path, text);
    let protocol = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    expand_pretty(&protocol, &RuntimePath::default())
}

/// A spec whose one frame format carries payloads of up to `max` bytes behind a `u32le` length.
fn spec(max: u64) -> String {
    format!(
        r#"[protocol]
name = "demo"

[frames.main]
layout = [
  {{ sync = [0xAA, 0x55] }},
  {{ field = "length", type = "u32le", length_of = "payload" }},
  {{ field = "command", type = "u8" }},
  {{ payload = {{ max = {max} }} }},
  {{ check = "crc-16-ccitt-false", over = "frame" }},
]
dispatch = ["command"]

[commands]
PING = {{ id = 1 }}
"#
    )
}

/// The message of the refusal behind `cfg(target_pointer_width = "BITS")`, if there is one.
fn refusal(expansion: &str, bits: u32) -> Option<String> {
    let guard = format!("#[cfg(target_pointer_width = \"{bits}\")]");
    let after = &expansion[expansion.find(&guard)? + guard.len()..];
    let call = after
        .trim_start()
        .strip_prefix("::core::compile_error!(")?
        .trim_start()
        .strip_prefix('"')?;
    Some(call[..call.find('"')?].to_owned())
}

#[test]
fn a_buffer_no_32_bit_target_can_hold_is_refused_there_naming_the_spec_line() {
    let expansion = expand("specs/huge.toml", &spec(4_000_000_000));
    let message = refusal(&expansion, 32).expect("a refusal on 32-bit targets");
    assert!(
        message.contains(
            "its payload is declared at specs/huge.toml:9:3: `{ payload = { max = 4000000000 } },`"
        ),
        "{message}"
    );
    assert!(
        message.contains(
            "needs a decoder buffer of 8000000192 bytes on a target with 32-bit pointers, \
             where no object exceeds 2147483647 bytes (largest frame 4000000009 bytes)"
        ),
        "{message}"
    );
    assert!(refusal(&expansion, 16).is_some(), "16-bit targets too");
}

/// 20,000-byte payloads: a 40 KB buffer exists on 32-bit targets, not on 16-bit ones.
#[test]
fn a_buffer_only_16_bit_targets_cannot_hold_is_refused_there_alone() {
    let expansion = expand("specs/big.toml", &spec(20_000));
    assert_eq!(refusal(&expansion, 32), None);
    let message = refusal(&expansion, 16).expect("a refusal on 16-bit targets");
    assert!(
        message.contains("where no object exceeds 32767 bytes"),
        "{message}"
    );
    assert!(message.contains("specs/big.toml:9:3"), "{message}");
}

#[test]
fn the_bundled_specs_are_refused_nowhere() {
    for name in ["hflink", "mavlink", "dynamixel", "ubx", "msp", "roborts"] {
        let path = format!("{}/../specs/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let text = std::fs::read_to_string(&path).expect("spec");
        let expansion = expand(&format!("specs/{name}.toml"), &text);
        assert!(!expansion.contains("compile_error!"), "{name}");
    }
}
