//! A header field after the payload in a format whose frames may end with optional bytes
//! (`protocol-codegen/tests/c_regressions/optional_after_payload.toml`): generated code and the
//! run-time codec read it, and write it, at its place back from the end of the frame without
//! the optional bytes, where the check keeps its place too.

use protocol_dynamic::{Interpreter, Value};

use crate::support::unhex;

protocol_kit::protocol!("../protocol-codegen/tests/c_regressions/optional_after_payload.toml");

/// PING with `after` = 0x21, its sum8 over the five bytes before it, then the two optional
/// bytes its flag announces; and the same frame without them.
const SIGNED: &str = "c101020021e5ba92";
const UNSIGNED: &str = "c100020021e4";

fn interpreter() -> Interpreter {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../protocol-codegen/tests/c_regressions/optional_after_payload.toml"
    );
    Interpreter::load(path).expect("the fixture loads")
}

#[test]
fn generated_code_reads_and_writes_the_field_before_the_optional_bytes() {
    for (frame, sig) in [(SIGNED, Some([0xBA, 0x92])), (UNSIGNED, None)] {
        let bytes = unhex(frame);
        let packet = optional_after_payload::Packet::decode(&bytes).expect("a valid frame");
        assert_eq!(
            (packet.header.after, packet.header.sig),
            (0x21, sig),
            "{frame}"
        );
        let mut buf = [0u8; optional_after_payload::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("it encodes again");
        assert_eq!(&buf[..n], bytes.as_slice(), "{frame}");
    }
}

#[test]
fn the_run_time_codec_reads_and_writes_the_field_before_the_optional_bytes() {
    let interp = interpreter();
    let codec = interp.codec();
    for frame in [SIGNED, UNSIGNED] {
        let bytes = unhex(frame);
        let decoded = codec.decode_frame(0, &bytes).expect("a valid frame");
        assert_eq!(
            decoded.header.get("after"),
            Some(&Value::UInt(0x21)),
            "{frame}"
        );
        let value = codec.frame_value(&decoded, 0, &bytes);
        let again = codec.encode(&value).expect("it encodes again");
        assert_eq!(again.bytes, bytes, "{frame}");
    }
}
