//! Optional bytes at the end of a frame (`optional = ...`), in generated code and the run-time
//! codec, on two fixtures of `protocol-codegen/tests/c_regressions`:
//! `optional_after_payload.toml`, whose header field after the payload lies back from the end
//! of the frame without the optional bytes (where its check lies too), read and written there;
//! and `optional_flag_after_length.toml`, whose flag lies after the length field and is read
//! before a frame's length is known, since it adds the optional bytes to it.

use protocol_dynamic::{Interpreter, Value};
use protocol_kit::Event;

use crate::support::unhex;

protocol_kit::protocol!("../protocol-codegen/tests/c_regressions/optional_after_payload.toml");
protocol_kit::protocol!("../protocol-codegen/tests/c_regressions/optional_flag_after_length.toml");

/// PING with `after` = 0x21, its sum8 over the five bytes before it, then the two optional
/// bytes its flag announces; and the same frame without them.
const SIGNED: &str = "c101020021e5ba92";
const UNSIGNED: &str = "c100020021e4";

/// SET 0x1234 with the `user` flag and the three optional bytes.
const FLAGGED: &str = "ee0202033412aabbcc";

fn interpreter(name: &str) -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/c_regressions/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).expect("the fixture loads")
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
    let interp = interpreter("optional_after_payload");
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

#[test]
fn a_flag_after_the_length_counts_the_optional_bytes_in_the_frame() {
    let bytes = unhex(FLAGGED);
    // The layout's header span reaches the flag.
    assert_eq!(optional_flag_after_length::LAYOUT.header_span(), 4);
    for chunk in 1..=bytes.len() {
        let mut decoder = optional_flag_after_length::decoder();
        let mut frames = Vec::new();
        for mut input in bytes.chunks(chunk) {
            while let Some(e) = decoder.next_event(&mut input) {
                if let Event::Frame(f) = e {
                    frames.push(f.bytes.to_vec());
                }
            }
        }
        assert_eq!(frames, std::slice::from_ref(&bytes), "chunk {chunk}");
    }
    let packet = optional_flag_after_length::Packet::decode(&bytes).expect("a valid frame");
    assert_eq!(packet.header.sig, Some([0xAA, 0xBB, 0xCC]));
    let interp = interpreter("optional_flag_after_length");
    let decoded = interp
        .codec()
        .decode_frame(0, &bytes)
        .expect("a valid frame");
    assert_eq!(
        decoded.header.get("sig"),
        Some(&Value::Bytes(vec![0xAA, 0xBB, 0xCC]))
    );
}
