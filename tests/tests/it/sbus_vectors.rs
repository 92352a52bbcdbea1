//! SBUS golden vectors (`tests/vectors/sbus.json`, from the tests of zklapow/sbus, ArduPilot,
//! sbus-rs and radio-controllers): every SBUS frame decodes to its recorded channels and flags
//! and those values encode to the exact bytes, by generated code and by the run-time codec; the
//! stream yields its expected frames at every chunk size, in both.
//!
//! The one SBUS2 vector (footer 0x14) is not expressible: the spec's frame format ends in the
//! constant footer 0x00, and accepting a set of footers is a framing feature the spec format
//! lacks. The tests assert that it is rejected as a bad trailer, and leave it out of the stream's
//! expected frames, by name.

use crate::golden;

use protocol_kit::{DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/sbus.toml");

use sbus::*;

/// The vector that needs the SBUS2 footers.
const SBUS2: &str = "sbus2_footer";

fn flag(fields: &Value, k: &str) -> bool {
    fields[k]
        .as_bool()
        .unwrap_or_else(|| panic!("flag {k} missing"))
}

/// The payload a vector records, built from its JSON fields (not from the bytes).
fn expected(frame: &Value) -> Channels {
    let fields = &frame["fields"];
    let list = fields["channels"].as_array().expect("channels");
    let mut channels = [0u16; 16];
    assert_eq!(list.len(), channels.len(), "16 channels");
    for (c, v) in channels.iter_mut().zip(list) {
        *c = u16::try_from(v.as_u64().expect("a number")).expect("a u16");
    }
    let flags = frame["flags"].as_u64().expect("flags") as u8;
    Channels {
        channels,
        ch17: flag(fields, "ch17"),
        ch18: flag(fields, "ch18"),
        frame_lost: flag(fields, "frame_lost"),
        failsafe: flag(fields, "failsafe"),
        flags_reserved: flags >> 4,
    }
}

/// The payload as the run-time codec shows it: the recorded fields and the kept flag bits.
fn expected_json(frame: &Value) -> Value {
    let mut payload = frame["fields"].clone();
    payload["flags_reserved"] = Value::from(frame["flags"].as_u64().expect("flags") >> 4);
    payload
}

#[test]
fn every_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("sbus.json");
    let interp = golden::interpreter("sbus");
    let (mut n, mut sbus2) = (0, 0);
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        assert_eq!(
            frame["footer"].as_u64(),
            Some(u64::from(bytes[24])),
            "{name}"
        );
        if name == SBUS2 {
            // Not expressible: an SBUS2 footer is refused, by both codecs.
            assert_eq!(
                Packet::decode(&bytes),
                Err(DecodeError::Frame(Reject::BadTrailer)),
                "{name}"
            );
            assert!(interp.codec().parse(0, &bytes).is_err(), "{name}");
            sbus2 += 1;
            continue;
        }
        let packet = Packet {
            header: Header {},
            payload: expected(frame),
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..len]), F(&bytes), "{name}: encode");
        golden::frame(&interp, name, &bytes, None, &expected_json(frame));
        n += 1;
    }
    assert_eq!((n, sbus2), (7, 1), "every vector was checked");
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("sbus.json");
    let stream = &v["streams"][0];
    let (bytes, all) = stream_vector(stream);
    // The SBUS2 frame is rejected (see the module docs): it is the one expected frame left out.
    let names: Vec<&str> = stream["expected_frames"]
        .as_array()
        .expect("expected_frames")
        .iter()
        .map(|f| f["frame"].as_str().unwrap_or(""))
        .collect();
    let expected: Vec<(u64, Vec<u8>)> = all
        .into_iter()
        .zip(&names)
        .filter(|(_, name)| **name != SBUS2)
        .map(|(f, _)| f)
        .collect();
    assert_eq!(expected.len() + 1, names.len(), "one SBUS2 frame left out");
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::from_frame(f).is_ok(), "{:?}", F(f));
    });
    golden::stream(&golden::interpreter("sbus"), &bytes, &expected);
}
