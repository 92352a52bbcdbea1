//! iBUS golden vectors (`tests/vectors/ibus.json`, from the tests of parse_rc_ibus, ArduPilot,
//! radio-controllers and ADV-RCProtocols): every servo frame decodes to its recorded channels and
//! those channels encode to the exact bytes, by generated code and by the run-time codec; the
//! stream yields exactly its expected frames at every chunk size, in both.

use crate::golden;

use protocol_kit::{DecodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::Value;

protocol_kit::protocol!("../specs/ibus.toml");

use ibus::*;

fn channels(frame: &Value) -> [u16; 14] {
    let list = frame["fields"]["channels"].as_array().expect("channels");
    let mut out = [0u16; 14];
    assert_eq!(list.len(), out.len(), "14 channels");
    for (c, v) in out.iter_mut().zip(list) {
        *c = u16::try_from(v.as_u64().expect("a number")).expect("a u16");
    }
    out
}

#[test]
fn every_frame_decodes_to_its_channels_and_encodes_to_its_bytes() {
    let v = load_vectors("ibus.json");
    let interp = golden::interpreter("ibus");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        assert_eq!(frame["length"].as_u64(), Some(bytes.len() as u64), "{name}");
        assert_eq!(
            frame["command"].as_u64(),
            Some(u64::from(bytes[1])),
            "{name}"
        );
        let packet = Packet {
            header: Header {},
            message: Message::Channels(Channels {
                channels: channels(frame),
            }),
        };
        assert_eq!(Packet::decode(&bytes), Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..len]), F(&bytes), "{name}: encode");
        let recorded = frame["checksum"].as_u64().expect("checksum");
        assert_eq!(
            u64::from(u16::from_le_bytes([bytes[30], bytes[31]])),
            recorded
        );
        let mut bad = bytes.clone();
        bad[4] ^= 0x01;
        assert_eq!(
            Packet::decode(&bad),
            Err(DecodeError::Frame(Reject::BadChecksum)),
            "{name}: a flipped bit"
        );
        golden::frame(&interp, name, &bytes, Some("CHANNELS"), &frame["fields"]);
        n += 1;
    }
    assert_eq!(n, 8, "every vector was checked");
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("ibus.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        assert!(Packet::from_frame(f).is_ok(), "{:?}", F(f));
    });
    golden::stream(&golden::interpreter("ibus"), &bytes, &expected);
}
