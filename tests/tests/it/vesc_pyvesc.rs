//! VESC packets written and decoded by pyvesc (`tests/vectors/vesc_pyvesc.json`, made by
//! `scripts/vesc_pyvesc_vectors.py`): random messages of every command of `specs/vesc.toml`,
//! in the directions that carry them.
//!
//! The generated code and the run-time codec, each given the frame's direction, decode every
//! packet to pyvesc's values (a scaled field within half its scale, every other value equal)
//! and encode pyvesc's values back to the packet's bytes; a stream of the packets with noise
//! and damaged packets between them yields exactly the good packets, in both.

use crate::{golden, peer_frames};

use protocol_tests::assert_stream_at_every_chunk_size;
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/vesc.toml", derive(serde));
}

use generated::vesc;

fn decode(bytes: &[u8], direction: &str) -> Result<vesc::Packet, protocol_kit::DecodeError> {
    match direction {
        "request" => vesc::Packet::decode_request(bytes),
        "response" => vesc::Packet::decode_response(bytes),
        other => panic!("no direction {other}"),
    }
}

fn encode(packet: &vesc::Packet) -> Vec<u8> {
    let mut buf = [0u8; vesc::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

#[test]
fn every_pyvesc_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("vesc_pyvesc.json");
    let interp = golden::interpreter("vesc");
    let mut covered = BTreeSet::new();
    for frame in &frames {
        peer_frames::check_codec(&interp, frame);
        peer_frames::check_generated(frame, decode, encode);
        covered.extend(frame.command.clone());
    }
    let all: BTreeSet<String> = vesc::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(covered, all, "every command of the spec has pyvesc packets");
    assert_eq!(frames.len(), 72, "every vector was checked");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_packets() {
    let frames = peer_frames::frames("vesc_pyvesc.json");
    let interp = golden::interpreter("vesc");
    for direction in ["request", "response"] {
        let ours: Vec<&[u8]> = frames
            .iter()
            .filter(|f| f.direction == direction)
            .map(|f| f.bytes.as_slice())
            .collect();
        let (stream, expected) = peer_frames::noisy_stream(&ours);
        assert_stream_at_every_chunk_size::<{ vesc::DECODER_BUFFER_LEN }>(
            &vesc::LAYOUT,
            &stream,
            &expected,
            |f| {
                decode(f, direction).unwrap_or_else(|e| panic!("{direction}: {e}"));
            },
        );
        peer_frames::codec_stream(&interp, direction, &stream, &expected);
    }
}
