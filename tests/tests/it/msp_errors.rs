//! MSP error replies (`tests/vectors/msp_errors.json`): the `!` frame of every command of
//! `specs/msp.toml`, v1 and v2, as cu-msp-lib writes an `Unsupported` packet without data. The
//! spec's `error` direction (`empty = true`) reads each as the command alone.
//!
//! The generated code and the run-time codec each decode every frame to its command in the
//! error direction, show it with an empty payload, and encode it back to the frame's bytes; an
//! error frame that carries a byte is refused by both.

use crate::golden;
use crate::msp_yamspy::{generated::msp, shown};

use protocol_kit::DecodeError;
use protocol_tests::{F, hex, load_vectors};
use serde_json::{Value, json};

fn frames() -> Vec<Value> {
    load_vectors("msp_errors.json")["frames"]
        .as_array()
        .expect("frames")
        .clone()
}

/// The command a vector names, by its name in the spec.
fn command(frame: &Value) -> msp::Command {
    let name = frame["message"].as_str().expect("message");
    msp::Command::ALL
        .into_iter()
        .find(|(_, n)| *n == name)
        .map(|(c, _)| c)
        .unwrap_or_else(|| panic!("no command {name}"))
}

/// The generated packet of `bytes`, its message and its encoding, in the vector's format.
fn generated(v2: bool, bytes: &[u8]) -> Result<(msp::Message, Value, Vec<u8>), DecodeError> {
    let mut buf = [0u8; msp::V2_MAX_FRAME_LEN + msp::MAX_FRAME_LEN];
    let (message, shown, n) = if v2 {
        let p = msp::V2Packet::decode(bytes)?;
        (p.message, shown(&p), p.encode(&mut buf).expect("encode"))
    } else {
        let p = msp::Packet::decode(bytes)?;
        (p.message, shown(&p), p.encode(&mut buf).expect("encode"))
    };
    Ok((message, shown, buf[..n].to_vec()))
}

#[test]
fn every_error_frame_is_its_command_alone_in_generated_code() {
    let all = frames();
    for frame in &all {
        let at = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let (message, shown, encoded) =
            generated(frame["version"] == "v2", &bytes).unwrap_or_else(|e| panic!("{at}: {e:?}"));
        assert_eq!(message, msp::Message::Error(command(frame)), "{at}");
        assert_eq!(message.command(), command(frame), "{at}");
        assert_eq!(u64::from(message.command().id()), frame["id"], "{at}");
        assert_eq!(shown["command"], frame["message"], "{at}: {shown}");
        assert_eq!(shown["header"]["direction"], b'!', "{at}: {shown}");
        assert_eq!(shown["payload"], json!({}), "{at}: {shown}");
        assert_eq!(F(&encoded), F(&bytes), "{at}: the generated code's bytes");
    }
    // Every command in v2, those with an id below 255 in v1 too.
    let v2 = all.iter().filter(|f| f["version"] == "v2").count();
    assert_eq!(v2, msp::Command::ALL.len());
    assert!(all.len() > v2 + 20, "{} frames", all.len());
}

#[test]
fn every_error_frame_is_its_command_alone_in_the_run_time_codec() {
    let interp = golden::interpreter("msp");
    let codec = interp.codec();
    for frame in frames() {
        let at = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let format = usize::from(frame["version"] == "v2");
        let decoded = codec
            .parse(format, &bytes)
            .unwrap_or_else(|e| panic!("{at}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let by_codec = shown(&value);
        assert_eq!(by_codec["command"], frame["message"], "{at}: {by_codec}");
        assert_eq!(by_codec["header"]["direction"], b'!', "{at}: {by_codec}");
        assert_eq!(by_codec["payload"], json!({}), "{at}: {by_codec}");
        let encoded = codec.encode(&value).unwrap_or_else(|e| panic!("{at}: {e}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{at}: the codec's bytes");
    }
}

/// An error reply whose payload holds a byte (its checks sealed): both refuse its length.
#[test]
fn an_error_frame_with_a_payload_is_refused_by_both() {
    let interp = golden::interpreter("msp");
    let codec = interp.codec();
    // `$M!`, one byte, API_VERSION, 0x07, the XOR of size, command and payload sealed.
    let mut v1 = hex("244d2101010700");
    msp::LAYOUT.seal(&mut v1).expect("seal");
    // `$X!`, flag 0, API_VERSION, one byte, 0x07, CRC-8/DVB-S2 sealed.
    let mut v2 = hex("24582100010001000700");
    msp::V2_LAYOUT.seal(&mut v2).expect("seal");
    for (format, bytes) in [(0, &v1), (1, &v2)] {
        let refused = generated(format == 1, bytes).map(|(m, _, _)| m);
        assert_eq!(
            refused,
            Err(DecodeError::PayloadLength {
                expected: 0,
                actual: 1
            }),
            "{format}"
        );
        assert!(codec.parse(format, bytes).is_err(), "{format}");
    }
}

/// A message of the error direction is written only under a header that says `!`.
#[test]
fn an_error_message_is_not_encoded_under_another_direction() {
    let mut buf = [0u8; msp::MAX_FRAME_LEN];
    for direction in [b'<', b'>'] {
        let packet = msp::Packet {
            header: msp::Header { direction },
            message: msp::Message::Error(msp::Command::Status),
        };
        assert!(packet.encode(&mut buf).is_err(), "{direction}");
    }
    let packet = msp::Packet {
        header: msp::Header { direction: b'!' },
        message: msp::Message::Error(msp::Command::Status),
    };
    let n = packet.encode(&mut buf).expect("encode");
    assert_eq!(F(&buf[..n]), F(&hex("244d21006565")));
}
