//! SBUS (`tests/vectors/sbus.json`) against `sbus-rs` 0.1 (AeroRust), and iBUS
//! (`tests/vectors/ibus.json`) against `parse_rc_ibus` 0.2.
//!
//! Every frame decodes in its peer to the recorded channels and flags. `sbus-rs` also has a
//! streaming parser, which is fed the SBUS stream; `parse_rc_ibus` decodes one aligned 32-byte
//! frame at a time (its README leaves finding frames to the caller), so it gets no stream.
//!
//! Random frames cross between each peer and the code generated from `specs/sbus.toml` and
//! `specs/ibus.toml`: both ways and as the same bytes for SBUS, and from here to the peer for
//! iBUS, whose peer has no writer.

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

// ---- Random messages: sbus-rs and parse_rc_ibus against the generated SBUS and iBUS codecs ----

mod ours {
    protocol_kit::protocol!("../../specs/sbus.toml");
    protocol_kit::protocol!("../../specs/ibus.toml");
}

use crate::encoded;
use ours::{ibus, sbus};
use proptest::prelude::*;
use protocol_peers::harness::{PeerAdapter, Tally, assert_every_message_crosses, cross_check};

const CASES: usize = 2000;

/// `sbus-rs` 0.1 against the generated SBUS codec.
///
/// The peer has no frame writer: it packs the 16 channels (`pack_channels`, the part of a frame
/// that takes a codec) and offers its header and footer constants; the adapter sets the flag
/// byte's four documented bits itself. Its `Flags` keeps those four bits only, so the messages
/// drawn leave the four reserved bits (`flags_reserved`, kept by this project so a frame
/// re-encodes to its bytes) at zero: a peer that drops them cannot return them.
struct SbusRs;

impl PeerAdapter for SbusRs {
    type Message = sbus::Channels;

    fn peer(&self) -> &'static str {
        "sbus-rs 0.1"
    }

    fn messages(&self) -> BoxedStrategy<sbus::Channels> {
        (prop::array::uniform16(0u16..=0x7FF), any::<[bool; 4]>())
            .prop_map(
                |(channels, [ch17, ch18, frame_lost, failsafe])| sbus::Channels {
                    channels,
                    ch17,
                    ch18,
                    frame_lost,
                    failsafe,
                    flags_reserved: 0,
                },
            )
            .boxed()
    }

    fn peer_write(&mut self, m: &sbus::Channels) -> Result<Option<Vec<u8>>, String> {
        let mut frame = [0u8; sbus_rs::SBUS_FRAME_LENGTH];
        sbus_rs::pack_channels(&mut frame, &m.channels);
        frame[0] = sbus_rs::SBUS_HEADER;
        frame[23] = u8::from(m.ch17)
            | u8::from(m.ch18) << 1
            | u8::from(m.frame_lost) << 2
            | u8::from(m.failsafe) << 3;
        frame[24] = sbus_rs::SBUS_FOOTER;
        Ok(Some(frame.to_vec()))
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &sbus::Channels,
    ) -> Result<Option<sbus::Channels>, String> {
        let bytes: [u8; 25] = frame.try_into().map_err(|_| "not 25 bytes")?;
        let p = SbusPacket::from_array(&bytes).map_err(|e| format!("{e:?}"))?;
        Ok(Some(sbus::Channels {
            channels: p.channels,
            ch17: p.flags.d1,
            ch18: p.flags.d2,
            frame_lost: p.flags.frame_lost,
            failsafe: p.flags.failsafe,
            flags_reserved: 0,
        }))
    }

    fn ours_write(&self, m: &sbus::Channels) -> Result<Vec<u8>, String> {
        let packet = sbus::Packet {
            header: sbus::Header {},
            payload: *m,
        };
        encoded(&packet)
    }

    fn ours_read(&self, frame: &[u8]) -> Result<sbus::Channels, String> {
        sbus::Packet::decode(frame)
            .map(|p| p.payload)
            .map_err(|e| e.to_string())
    }
}

#[test]
fn random_sbus_frames_cross_between_sbus_rs_and_the_generated_codec() {
    assert_every_message_crosses(&mut SbusRs, CASES, "sbus-rs");
}

/// `parse_rc_ibus` 0.2 against the generated iBUS codec. The peer only parses (it has no
/// writer), so only the frames written here cross, to the peer.
struct ParseRcIbus;

impl PeerAdapter for ParseRcIbus {
    type Message = ibus::Channels;

    fn peer(&self) -> &'static str {
        "parse_rc_ibus 0.2"
    }

    /// Any `u16` in every channel: iBUS does not limit the values, and neither does the peer.
    fn messages(&self) -> BoxedStrategy<ibus::Channels> {
        any::<[u16; 14]>()
            .prop_map(|channels| ibus::Channels { channels })
            .boxed()
    }

    fn peer_write(&mut self, _m: &ibus::Channels) -> Result<Option<Vec<u8>>, String> {
        Ok(None)
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &ibus::Channels,
    ) -> Result<Option<ibus::Channels>, String> {
        let bytes: [u8; 32] = frame.try_into().map_err(|_| "not 32 bytes")?;
        let p = IbusPacket::try_from_bytes(&bytes).map_err(|e| e.to_string())?;
        Ok(Some(ibus::Channels {
            channels: p.get_all_channels(),
        }))
    }

    fn ours_write(&self, m: &ibus::Channels) -> Result<Vec<u8>, String> {
        let packet = ibus::Packet {
            header: ibus::Header {},
            message: ibus::Message::Channels(*m),
        };
        encoded(&packet)
    }

    fn ours_read(&self, frame: &[u8]) -> Result<ibus::Channels, String> {
        match ibus::Packet::decode(frame)
            .map_err(|e| e.to_string())?
            .message
        {
            ibus::Message::Channels(c) => Ok(c),
        }
    }
}

#[test]
fn random_ibus_frames_written_here_decode_in_parse_rc_ibus() {
    let tally = cross_check(&mut ParseRcIbus, CASES).unwrap_or_else(|e| panic!("{e}"));
    println!("parse_rc_ibus: {tally:?}");
    assert_eq!(
        tally,
        Tally {
            messages: CASES,
            peer_to_ours: 0,
            ours_to_peer: CASES,
            same_bytes: 0,
        },
        "every frame written here decodes in the peer; the peer writes none"
    );
}
