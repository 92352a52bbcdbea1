//! What the C printer prints for byte escaping between flags and for a CAN-only link: the
//! items each adds, and that a spec without them prints none of them. Whether the printed C is
//! right is tested against the Rust codec in `protocol-cli/tests/it/c_peer.rs`.

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
fn an_escaped_format_unescapes_decodes_and_escapes_encodes() {
    let p = compile("protocol-codegen/tests/features/escaped_slip.toml");
    let files = protocol_codegen::c::generate(&p).expect("escaped formats print in C");
    for item in [
        // The frame unescaped for the caller, and the size of an escaped frame: every byte
        // between the two flags may go as two (a largest frame of 69 bytes).
        "int escaped_slip_unescape(const uint8_t *wire, size_t len, uint8_t *out, size_t cap);",
        "#define ESCAPED_SLIP_MAX_FRAME_LEN 69u",
        "#define ESCAPED_SLIP_MAX_WIRE_LEN 136u",
        // The stream decoder's reason for an escape byte without substitute, and its state.
        "ESCAPED_SLIP_REJECT_BAD_ESCAPE,",
        "    uint64_t owner;",
    ] {
        assert!(files.header.contains(item), "{item}");
    }
    for item in [
        // The table of pairs, both ways.
        "    case 0xc0: return 0xdc;\n    case 0xdb: return 0xdd;\n",
        "    case 0xdc: return 0xc0;\n    case 0xdd: return 0xdb;\n",
        // `decode` unescapes first; every encoder escapes last.
        "int m = escaped_slip_unescape_from(bytes, len, frame, sizeof frame, &used);",
        "return escaped_slip_escape(buf, cap, escaped_slip_seal(",
        // The stream decoder's escaped path, and the name of its rejection.
        "static int escaped_slip_escaped_step(",
        "case ESCAPED_SLIP_REJECT_BAD_ESCAPE: return \"bad escape\";",
        "case ESCAPED_SLIP_REJECT_BAD_ESCAPE: s->bad_header++; break;",
    ] {
        assert!(files.source.contains(item), "{item}");
    }
    assert!(!files.source.contains("escaped_slip_find_candidate"));
}

#[test]
fn a_format_that_does_not_escape_prints_no_escaping() {
    let p = compile("specs/hflink.toml");
    let files = protocol_codegen::c::generate(&p).expect("hflink prints in C");
    for text in [&files.header, &files.source] {
        for item in ["escape", "ESCAPE", "MAX_WIRE_LEN", "owner"] {
            assert!(!text.contains(item), "{item}");
        }
    }
}

#[test]
fn a_can_only_link_has_can_frame_functions_and_no_stream_decoder() {
    let p = compile("specs/dronecan.toml");
    assert_eq!(protocol_codegen::c::unsupported(&p), Vec::<String>::new());
    let files = protocol_codegen::c::generate(&p).expect("a CAN-only link prints in C");
    for item in [
        "int dronecan_decode_can(uint32_t id, bool extended, const uint8_t *data, size_t len, dronecan_packet *out);",
        "int dronecan_encode_can(const dronecan_packet *packet, uint32_t *id, uint8_t data[8]);",
        "#define DRONECAN_CAN_EXTENDED 1",
        // The members of the identifier the sender sets are header values.
        "source_node_id;",
        "priority;",
    ] {
        assert!(files.header.contains(item), "{item}");
    }
    assert!(!files.header.contains("dronecan_decoder_next"));
}
