//! SBUS (`tests/vectors/sbus.json`) against `sbus-rs` 0.1 (AeroRust), and iBUS
//! (`tests/vectors/ibus.json`) against `parse_rc_ibus` 0.2.
//!
//! Every frame decodes in its peer to the recorded channels and flags. `sbus-rs` also has a
//! streaming parser, which is fed the SBUS stream; `parse_rc_ibus` decodes one aligned 32-byte
//! frame at a time (its README leaves finding frames to the caller), so it gets no stream.

use crate::values::{V, assert_fields};
use parse_rc_ibus::IbusPacket;
use protocol_peers::{expected_frames, frame_bytes, frames, hex, load_vectors, name};
use sbus_rs::{SbusPacket, StreamingParser};

fn sbus_fields(p: &SbusPacket) -> Vec<(&'static str, V)> {
    let flag = |b: bool| V::I(b.into());
    vec![
        (
            "channels",
            V::List(p.channels.iter().map(|&c| c.into()).collect()),
        ),
        ("ch17", flag(p.flags.d1)),
        ("ch18", flag(p.flags.d2)),
        ("frame_lost", flag(p.flags.frame_lost)),
        ("failsafe", flag(p.flags.failsafe)),
    ]
}

/// The vectors write the flags as JSON booleans; the peer's as 0 and 1.
fn sbus_recorded(frame: &serde_json::Value) -> serde_json::Value {
    let mut f = frame["fields"].clone();
    for key in ["ch17", "ch18", "frame_lost", "failsafe"] {
        let b = f[key].as_bool().expect("a flag");
        f[key] = u8::from(b).into();
    }
    f
}

#[test]
fn every_sbus_frame_decodes_in_sbus_rs() {
    let v = load_vectors("sbus.json");
    for frame in frames(&v) {
        let bytes: [u8; 25] = frame_bytes(frame).try_into().expect("25 bytes");
        let packet =
            SbusPacket::from_array(&bytes).unwrap_or_else(|e| panic!("{}: {e:?}", name(frame)));
        assert_fields(name(frame), &sbus_fields(&packet), &sbus_recorded(frame));
    }
    println!(
        "sbus-rs: {} frames decoded to their fields",
        frames(&v).len()
    );
}

/// `sbus-rs`'s streaming parser takes only the 0x00 footer, while its `SbusPacket::from_array`
/// (above) also takes the SBUS2 footers (low nibble 0x04): the streaming side drops the SBUS2
/// frame. Besides that, what it yields must be expected frames, in order.
#[test]
fn the_sbus_stream_yields_expected_frames_in_sbus_rs() {
    let v = load_vectors("sbus.json");
    for stream in v["streams"].as_array().expect("streams") {
        let bytes = hex(stream["hex"].as_str().expect("hex"));
        let mut parser = StreamingParser::new();
        let seen: Vec<[u16; 16]> = parser
            .push_bytes(&bytes)
            .filter_map(Result::ok)
            .map(|p| p.channels)
            .collect();
        let wanted: Vec<[u16; 16]> = expected_frames(stream)
            .iter()
            .map(|(_, b)| {
                SbusPacket::from_array(&b[..].try_into().expect("25"))
                    .expect("a frame")
                    .channels
            })
            .collect();
        let mut rest = wanted.iter();
        for s in &seen {
            assert!(rest.any(|w| w == s), "{}: {s:?} unexpected", stream["name"]);
        }
        println!(
            "sbus-rs: {} of {} expected frames",
            seen.len(),
            wanted.len()
        );
        assert!(seen.len() >= 3);
    }
}

#[test]
fn every_ibus_frame_decodes_in_parse_rc_ibus() {
    let v = load_vectors("ibus.json");
    for frame in frames(&v) {
        let bytes: [u8; 32] = frame_bytes(frame).try_into().expect("32 bytes");
        let packet =
            IbusPacket::try_from_bytes(&bytes).unwrap_or_else(|e| panic!("{}: {e}", name(frame)));
        let got = vec![(
            "channels",
            V::List(
                packet
                    .get_all_channels()
                    .iter()
                    .map(|&c| c.into())
                    .collect(),
            ),
        )];
        assert_fields(name(frame), &got, &frame["fields"]);
        let mut bad = bytes;
        bad[31] ^= 0x01;
        assert!(
            IbusPacket::try_from_bytes(&bad).is_err(),
            "{}: a wrong checksum passes",
            name(frame)
        );
    }
    println!(
        "parse_rc_ibus: {} frames decoded to their fields",
        frames(&v).len()
    );
}
