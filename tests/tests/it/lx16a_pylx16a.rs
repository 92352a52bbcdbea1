//! LX-16A packets from pylx16a (`tests/vectors/lx16a_pylx16a.json`, made by
//! `scripts/lx16a_pylx16a_vectors.py`): the commands pylx16a writes for random calls of its
//! methods, every command of `specs/lx16a.toml`, and the servo's answers to its read commands,
//! as pylx16a reads them.
//!
//! The generated code and the run-time codec, each given the packet's direction, decode every
//! packet to pylx16a's values (an angle within half a unit of 0.24°, every other value equal)
//! and encode them back to the packet's bytes; a stream of the packets with noise and damaged
//! packets between them yields exactly the good packets, in both.

use crate::{golden, peer_frames};

use protocol_tests::assert_stream_at_every_chunk_size;
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/lx16a.toml", derive(serde));
}

use generated::lx16a;

fn decode(bytes: &[u8], direction: &str) -> Result<lx16a::Packet, protocol_kit::DecodeError> {
    match direction {
        "request" => lx16a::Packet::decode_request(bytes),
        "response" => lx16a::Packet::decode_response(bytes),
        other => panic!("no direction {other}"),
    }
}

fn encode(packet: &lx16a::Packet) -> Vec<u8> {
    let mut buf = [0u8; lx16a::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

#[test]
fn every_pylx16a_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("lx16a_pylx16a.json");
    let interp = golden::interpreter("lx16a");
    let mut covered = BTreeSet::new();
    for frame in &frames {
        peer_frames::check_codec(&interp, frame);
        peer_frames::check_generated(frame, decode, encode);
        covered.extend(frame.command.clone());
    }
    let all: BTreeSet<String> = lx16a::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(
        covered, all,
        "every command of the spec has pylx16a packets"
    );
    assert_eq!(frames.len(), 144, "every vector was checked");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_packets() {
    let frames = peer_frames::frames("lx16a_pylx16a.json");
    let interp = golden::interpreter("lx16a");
    for direction in ["request", "response"] {
        let ours: Vec<&[u8]> = frames
            .iter()
            .filter(|f| f.direction == direction)
            .map(|f| f.bytes.as_slice())
            .collect();
        let (stream, expected) = peer_frames::noisy_stream(&ours);
        assert_stream_at_every_chunk_size::<{ lx16a::DECODER_BUFFER_LEN }>(
            &lx16a::LAYOUT,
            &stream,
            &expected,
            |f| {
                decode(f, direction).unwrap_or_else(|e| panic!("{direction}: {e}"));
            },
        );
        peer_frames::codec_stream(&interp, direction, &stream, &expected);
    }
}
