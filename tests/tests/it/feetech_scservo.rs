//! Feetech SCS/STS packets from Feetech's Python SDK (`tests/vectors/feetech_scservo.json`,
//! made by `scripts/feetech_scservo_vectors.py`): the instruction packets its packet handler
//! writes for random calls, one or more of every command of `specs/feetech.toml`, and the status
//! packets it reads as their answers.
//!
//! The generated code and the run-time codec, each given the packet's direction, decode every
//! packet to the SDK's values and encode them back to the packet's bytes; a stream of the
//! packets with noise and damaged packets between them yields exactly the good packets, in
//! both; the answer to the model-number READ is typed by the STS3215's registers.

use crate::{golden, peer_frames};

use protocol_tests::assert_stream_at_every_chunk_size;
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/feetech.toml", derive(serde));
}

use generated::feetech;

fn decode(bytes: &[u8], direction: &str) -> Result<feetech::Packet, protocol_kit::DecodeError> {
    match direction {
        "request" => feetech::Packet::decode_request(bytes),
        "response" => feetech::Packet::decode_response(bytes),
        other => panic!("no direction {other}"),
    }
}

fn encode(packet: &feetech::Packet) -> Vec<u8> {
    let mut buf = [0u8; feetech::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

#[test]
fn every_sdk_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("feetech_scservo.json");
    let interp = golden::interpreter("feetech");
    let mut covered = BTreeSet::new();
    let mut statuses = 0;
    for frame in &frames {
        peer_frames::check_codec(&interp, frame);
        peer_frames::check_generated(frame, decode, encode);
        match &frame.command {
            Some(command) => {
                covered.insert(command.clone());
            }
            None => statuses += 1,
        }
    }
    let all: BTreeSet<String> = feetech::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(covered, all, "every command of the spec has SDK packets");
    assert_eq!(statuses, 28, "status packets");
    assert_eq!(frames.len(), 80, "every vector was checked");
}

#[test]
fn the_model_number_read_is_typed_by_the_sts3215_registers() {
    let frames = peer_frames::frames("feetech_scservo.json");
    let mut n = 0;
    for pair in frames.windows(2) {
        if !pair[0].name.starts_with("read_model_") || pair[0].name.contains("status") {
            continue;
        }
        let feetech::Message::Request(feetech::Request::Read(read)) =
            decode(&pair[0].bytes, "request").expect("a READ").message
        else {
            panic!("{}: a READ", pair[0].name)
        };
        let feetech::Message::Response(status) = decode(&pair[1].bytes, "response")
            .expect("a status")
            .message
        else {
            panic!("{}: a status packet", pair[1].name)
        };
        let window = feetech::registers::read_answer(&read, &status);
        let params = status.params.as_slice();
        assert_eq!(
            feetech::registers::MODEL_NUMBER.read(window),
            Some(u16::from_le_bytes([params[0], params[1]])),
            "{}",
            pair[1].name
        );
        n += 1;
    }
    assert_eq!(n, 4, "every model-number read");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_packets() {
    let frames = peer_frames::frames("feetech_scservo.json");
    let interp = golden::interpreter("feetech");
    for direction in ["request", "response"] {
        let ours: Vec<&[u8]> = frames
            .iter()
            .filter(|f| f.direction == direction)
            .map(|f| f.bytes.as_slice())
            .collect();
        let (stream, expected) = peer_frames::noisy_stream(&ours);
        assert_stream_at_every_chunk_size::<{ feetech::DECODER_BUFFER_LEN }>(
            &feetech::LAYOUT,
            &stream,
            &expected,
            |f| {
                decode(f, direction).unwrap_or_else(|e| panic!("{direction}: {e}"));
            },
        );
        peer_frames::codec_stream(&interp, direction, &stream, &expected);
    }
}
