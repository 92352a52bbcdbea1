//! The C printer (`protocol_codegen::c`): snapshots of the C printed for HFLink, header and
//! source, reviewed like code; and the refusal of features it does not print yet. Whether the
//! printed C is right is tested against the Rust codec in `protocol-cli/tests/it/c_peer.rs`.

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
fn several_frame_formats_print_with_a_prefix_each() {
    let p = compile("specs/mavlink.toml");
    let files = protocol_codegen::c::generate(&p).expect("mavlink prints in C");
    for item in [
        // The first format's items carry the spec's prefix, the others the format's too.
        "typedef struct mavlink_packet {",
        "typedef struct mavlink_v1_packet {",
        "int mavlink_v1_decode(const uint8_t *bytes, size_t len, mavlink_v1_packet *out);",
        // The link's decoder of both command formats.
        "typedef struct mavlink_any_decoder {",
        // The MAVLink 2 signature, present when its flag is set.
        "    bool signature_present;",
        "    uint8_t signature[13];",
    ] {
        assert!(files.header.contains(item), "{item}");
    }
    // The shared structs once.
    assert_eq!(
        files
            .header
            .matches("typedef struct mavlink_heartbeat {")
            .count(),
        1
    );
}

/// A CAN format whose frames' command does not follow from the CAN id (the spec has
/// directions, which a CAN id does not tell).
const CAN_WITH_DIRECTIONS: &str = r#"
[protocol]
name = "twoway"
doc = "A serial format whose header tells the direction, and a CAN format."

[frames.serial]
layout = [
  { sync = [0xAA] },
  { field = "direction", type = "u8" },
  { field = "command", type = "u8" },
  { payload = { min = 4, max = 4 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["command"]

[frames.can]
transport = "can"
can_id = "standard"
layout = [{ payload = { max = 8 } }]
dispatch = ["can_id"]

[directions]
request = { field = "direction", equals = 1 }
response = { field = "direction", equals = 2 }

[commands]
PING = { id = 1, can_id = 0x100 }
"#;

#[test]
fn unsupported_features_are_refused_not_printed() {
    let source = SpecSource::new("twoway.toml", CAN_WITH_DIRECTIONS);
    let p = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let refused = protocol_codegen::c::generate(&p).expect_err("a CAN format without packet");
    assert_eq!(
        refused,
        vec![
            "frame `can`: CAN transport in a format whose frames' command does not follow from the CAN id"
                .to_string()
        ]
    );
    assert_eq!(refused, protocol_codegen::c::unsupported(&p));
}

/// Byte stuffing in a format after the first, which carries one struct: the C printer prints
/// stuffing in the first format only, and only around a command's payload.
const STUFFED_SECOND: &str = r#"
[protocol]
name = "twostuff"
doc = "A plain command format, and a stuffed format of one message."

[frames.plain]
layout = [
  { sync = [0xAA] },
  { field = "command", type = "u8" },
  { payload = { min = 1, max = 1 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["command"]

[frames.stuffed]
layout = [
  { sync = [0xFF, 0xFD] },
  { field = "length", type = "u8", length_of = "payload" },
  { payload = { max = 16 } },
  { check = "sum8", over = "frame" },
]
message = "Reading"
stuffing = { after = [0xFF], insert = 0x00 }

[structs.Reading]
fields = [{ name = "value", type = "u8" }]

[structs.Level]
fields = [{ name = "value", type = "u8" }]

[commands]
SET = { id = 1, payload = "Level" }
"#;

#[test]
fn stuffing_outside_the_first_format_is_refused_not_printed() {
    let source = SpecSource::new("twostuff.toml", STUFFED_SECOND);
    let p = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let refused = protocol_codegen::c::generate(&p).expect_err("stuffing in a second format");
    assert_eq!(
        refused,
        vec![
            "frame `stuffed`: byte stuffing in a format without dispatch key or with a direction's message"
                .to_string(),
            "frame `stuffed`: byte stuffing in a format after the first".to_string(),
        ]
    );
}

/// A command format whose spec declares no command (the random spec of seed 3, shrunk): its
/// command tables would be empty arrays, so the C printer refuses it rather than print C that
/// does not compile.
const NO_COMMANDS: &str = r#"
[protocol]
name = "nocommands"

[frames.main]
layout = [
  { sync = [0x44] },
  { field = "len", type = "u16", bits = [{ name = "n", bits = 12, length_of = "frame" }, { name = "lver", bits = 4, value = 0 }] },
  { field = "cmd", type = "u8" },
  { payload = { max = 11 } },
]
dispatch = ["cmd"]
"#;

#[test]
fn a_dispatch_key_without_commands_is_refused_not_printed() {
    let source = SpecSource::new("nocommands.toml", NO_COMMANDS);
    let p = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let refused = protocol_codegen::c::generate(&p).expect_err("no commands");
    assert_eq!(
        refused,
        vec!["frame `main`: a dispatch key without commands".to_string()]
    );
}

/// A CAN format that no command has a CAN id for (the random spec of seed 67, shrunk): the C
/// printer refuses it rather than print an encoder that writes nothing.
const CAN_WITHOUT_COMMANDS: &str = r#"
[protocol]
name = "idlecan"

[frames.main]
layout = [
  { sync = [0xAA] },
  { field = "len", type = "u8", length_of = "payload" },
  { field = "cmd", type = "u8" },
  { payload = { max = 8 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["cmd"]

[frames.can]
transport = "can"
can_id = "extended"
layout = [
  { payload = { min = 0, max = 6 } },
  { field = "cnt", type = "u8" },
  { check = "crc-8-smbus", over = "frame" },
]
dispatch = ["can_id"]

[commands]
SET = { id = 1, payload = "Level" }

[structs.Level]
fields = [{ name = "value", type = "u32" }, { name = "more", type = "u32" }]
"#;

#[test]
fn a_can_format_without_commands_is_refused_not_printed() {
    let source = SpecSource::new("idlecan.toml", CAN_WITHOUT_COMMANDS);
    let p = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let refused = protocol_codegen::c::generate(&p).expect_err("no command has a CAN id");
    assert_eq!(
        refused,
        vec!["frame `can`: a CAN format that carries no command (none has a `can_id`)".to_string()]
    );
}

/// Struct names that are names of the generated code: `Step` (a helper of the stream
/// decoder), `ReadAll` (the family of struct readers) and `AuxPacket` (the packet type of
/// format `aux`).
const CLASHING_NAMES: &str = r#"
[protocol]
name = "clash"
doc = "Struct names the generated code takes for itself."

[frames.main]
layout = [
  { sync = [0xAA] },
  { field = "command", type = "u8" },
  { payload = { min = 1, max = 1 } },
  { check = "sum8", over = "frame" },
]
dispatch = ["command"]

[frames.aux]
layout = [
  { sync = [0x55] },
  { payload = { min = 1, max = 1 } },
  { check = "sum8", over = "frame" },
]
message = "AuxPacket"

[structs.AuxPacket]
fields = [{ name = "value", type = "u8" }]

[structs.Step]
fields = [{ name = "value", type = "u8" }]

[structs.ReadAll]
fields = [{ name = "first", type = "u8" }]

[commands]
STEP = { id = 1, payload = "Step" }
READ_ALL = { id = 2, payload = "ReadAll" }
"#;

#[test]
fn a_struct_named_like_the_generated_code_gets_t() {
    let source = SpecSource::new("clash.toml", CLASHING_NAMES);
    let p = protocol_codegen::compile(&source)
        .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
    let files = protocol_codegen::c::generate(&p).expect("clash prints in C");
    for item in [
        "} clash_step_t;",
        "} clash_read_all_t;",
        "} clash_aux_packet_t;",
        // The format's own packet keeps its name.
        "} clash_aux_packet;",
    ] {
        assert!(files.header.contains(item), "{item} in\n{}", files.header);
    }
}

/// Every runtime error names an `ERR_` code the printed header defines: the C conformance
/// test and the QEMU check compare the C's refusals with the Rust codec's by these names.
#[test]
fn every_runtime_error_names_a_printed_error_code() {
    use protocol_runtime::error::Place;
    use protocol_runtime::{DecodeError, Reject};
    let p = compile("specs/hflink.toml");
    let header = protocol_codegen::c::generate(&p)
        .expect("hflink prints in C")
        .header;
    let errors = [
        DecodeError::Truncated {
            needed: 8,
            available: 2,
        },
        DecodeError::PayloadLength {
            expected: 12,
            actual: 11,
        },
        DecodeError::UnknownCommand { key: 0xff },
        DecodeError::UnknownDirection,
        DecodeError::InvalidEnum {
            value: 9,
            place: Place::NONE,
        },
        DecodeError::Frame(Reject::BadChecksum),
        DecodeError::InvalidStuffing,
        DecodeError::ValueOutOfRange { place: Place::NONE },
        DecodeError::SizeMismatch { place: Place::NONE },
        DecodeError::Unterminated { place: Place::NONE },
        DecodeError::PayloadCheck { place: Place::NONE },
    ];
    let mut names: Vec<&str> = errors.iter().map(protocol_codegen::c::error_name).collect();
    for name in &names {
        let define = format!("#define HFLINK_ERR_{} (", name.to_uppercase());
        assert!(header.contains(&define), "{define} missing from the header");
    }
    names.sort_unstable();
    names.dedup();
    // Two errors share `frame` (truncated bytes and a rejected frame are both "not exactly one
    // valid frame"); every other error has its own code.
    assert_eq!(names.len(), errors.len() - 1, "{names:?}");
}

/// The body of the printed `decode_frame` of `p` (from its signature to its closing brace).
fn decode_frame(p: &Protocol) -> String {
    let files = protocol_codegen::c::generate(p).expect("prints in C");
    let start = files
        .source
        .find(&format!("int {}_decode_frame(", p.name))
        .expect("a decode_frame");
    let body = &files.source[start..];
    body[..body.find("\n}\n").expect("its end")].to_string()
}

/// Where `needle` is in `text`, which must hold it.
fn at(text: &str, needle: &str) -> usize {
    text.find(needle)
        .unwrap_or_else(|| panic!("`{needle}` is not in:\n{text}"))
}

#[test]
fn an_address_range_from_zero_has_no_lower_test() {
    // gcc -Wtype-limits refuses an unsigned comparison with 0 that is always true.
    let p = compile("protocol-codegen/tests/c_regressions/address_from_zero.toml");
    let body = decode_frame(&p);
    at(
        &body,
        "<= UINT64_C(0x7f)) out->direction = ADDRESS_FROM_ZERO_REQUEST",
    );
    assert!(!body.contains(">= UINT64_C(0x0)"), "{body}");
}

#[test]
fn a_payload_is_unstuffed_before_its_direction_is_read() {
    // The runtime's rules refuse a frame with both faults for its stuffing.
    let p = compile("protocol-codegen/tests/c_regressions/stuffed_directions.toml");
    let body = decode_frame(&p);
    assert!(
        at(&body, "ERR_INVALID_STUFFING") < at(&body, "ERR_UNKNOWN_DIRECTION"),
        "{body}"
    );
}

#[test]
fn a_short_frame_is_refused_after_its_key() {
    // The runtime's rules read the key before the payload: a bare header whose key is no
    // command is an unknown command.
    let p = compile("protocol-codegen/tests/c_regressions/bare_command.toml");
    let body = decode_frame(&p);
    assert!(
        at(&body, "ERR_UNKNOWN_COMMAND") < at(&body, "if (end < start)"),
        "{body}"
    );
}

#[test]
fn a_bare_header_is_a_frame_once_its_bytes_have_come() {
    // The length is known after three bytes, the bare header is five: a stream decoder that
    // took the header for a frame before its last bytes came would hand out bytes it never
    // received.
    let p = compile("protocol-codegen/tests/c_regressions/bare_command.toml");
    let files = protocol_codegen::c::generate(&p).expect("prints in C");
    let start = at(&files.source, "static int bare_command_probe_synced(");
    let body = &files.source[start..];
    let body = &body[..at(body, "\n}\n")];
    at(
        body,
        "if (total == 5u && 5u >= span && 5u > 0 && total <= limit) {\n        *n = total;\n        return avail < total ? BARE_COMMAND_PROBE_NEED : BARE_COMMAND_PROBE_FRAME;",
    );
}

#[test]
fn a_field_after_the_payload_is_read_before_the_optional_bytes() {
    // The optional bytes are left out of the frame first; the field lies back from the end
    // of what remains, as the checks do.
    let p = compile("protocol-codegen/tests/c_regressions/optional_after_payload.toml");
    let body = decode_frame(&p);
    let field =
        "optional_after_payload_field(bytes, end + OPTIONAL_AFTER_PAYLOAD_TRAILER_LEN, 1, 2u,";
    assert!(
        at(&body, "out->header.sig_present = 1;") < at(&body, field),
        "{body}"
    );
}

#[test]
fn a_flag_after_the_length_is_within_the_probe_span() {
    // The flag adds the optional bytes to the frame's length: the probe reads it with the
    // length, before it decides how many bytes the frame has.
    let p = compile("protocol-codegen/tests/c_regressions/optional_flag_after_length.toml");
    let files = protocol_codegen::c::generate(&p).expect("prints in C");
    let start = at(
        &files.source,
        "static int optional_flag_after_length_probe_synced(",
    );
    let body = &files.source[start..];
    let body = &body[..at(body, "\n}\n")];
    at(body, "const size_t span = 4u;");
    at(
        body,
        "if (optional_flag_after_length_field(b, span, 0, 3u, 1u, 0, 0u, 1u, &raw) && raw != 0) {",
    );
}
