//! Sensirion SHDLC frames of the SPS30's commands (`tests/vectors/shdlc_sensirion.json`, made by
//! `scripts/shdlc_sensirion_vectors.py`): the MOSI frames sensirion-shdlc-driver writes, with
//! random values, and MISO frames it reads back, every command of `specs/shdlc.toml` both ways.
//!
//! A MISO frame has a state byte that a MOSI frame has not (`direction = "response"` on the
//! layout element): the generated code and the run-time codec, each given the frame's
//! direction, decode every frame to the driver's values (a request's header without a state, a
//! response's with it) and encode them back to its bytes, stuffing included; a stream of each
//! direction's frames with noise and damaged frames between them yields exactly the good
//! frames, in both; and a header that does not fit its direction does not encode.

use crate::peer_frames::{self, PeerFrame};
use protocol_kit::EncodeError;

mod generated {
    protocol_kit::protocol!("../specs/shdlc.toml", derive(serde));
}

use generated::shdlc;

fn decode(bytes: &[u8], direction: &str) -> Result<shdlc::Packet, protocol_kit::DecodeError> {
    match direction {
        "request" => shdlc::Packet::decode_request(bytes),
        "response" => shdlc::Packet::decode_response(bytes),
        other => panic!("no direction {other}"),
    }
}

/// Escaping may double every byte between the flags.
const WIRE_LEN: usize = 2 * shdlc::RESPONSE_MAX_FRAME_LEN;

fn encode(packet: &shdlc::Packet) -> Vec<u8> {
    let mut buf = [0u8; WIRE_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

fn frames() -> Vec<PeerFrame> {
    peer_frames::frames("shdlc_sensirion.json")
}

#[test]
fn every_driver_frame_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = frames();
    let interp = crate::golden::interpreter("shdlc");
    let mut covered = std::collections::BTreeSet::new();
    for frame in &frames {
        peer_frames::check_codec(&interp, frame);
        peer_frames::check_generated(frame, decode, encode);
        covered.insert((
            frame.direction.clone(),
            frame.command.clone().expect("a command"),
        ));
    }
    for (_, name) in shdlc::Command::ALL {
        for direction in ["request", "response"] {
            assert!(
                covered.contains(&(direction.to_owned(), name.to_owned())),
                "no {direction} of {name}"
            );
        }
    }
    let stuffed = frames
        .iter()
        .filter(|f| f.bytes[1..f.bytes.len() - 1].contains(&0x7D))
        .count();
    assert!(stuffed > 30, "{stuffed} frames with stuffed bytes");
    assert_eq!(frames.len(), 150, "every vector was checked");
}

#[test]
fn the_state_byte_is_in_responses_only() {
    // READ_VERSION both ways: the request has no state byte, the response has one before L.
    let request = shdlc::Packet::decode_request(&[0x7E, 0x00, 0xD1, 0x00, 0x2E, 0x7E]).unwrap();
    assert_eq!(request.header.state, None);
    let response = [
        0x7E, 0x00, 0xD1, 0x80, 0x07, 2, 3, 0, 7, 0, 2, 0, 0x99, 0x7E,
    ];
    let packet = shdlc::Packet::decode_response(&response).unwrap();
    assert_eq!(packet.header.state, Some(0x80));
    assert_eq!(encode(&packet), response);
    // Read with the other direction's layout, the frames fail their length or checksum.
    assert!(shdlc::Packet::decode_request(&response).is_err());
    assert!(shdlc::Packet::decode_response(&[0x7E, 0x00, 0xD1, 0x00, 0x2E, 0x7E]).is_err());
    // A state where the direction has none, and none where it has one, do not encode.
    let mut buf = [0u8; WIRE_LEN];
    let mut with_state = request;
    with_state.header.state = Some(0);
    assert!(matches!(
        with_state.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange { .. })
    ));
    let mut without_state = packet;
    without_state.header.state = None;
    assert!(matches!(
        without_state.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange { .. })
    ));
}

#[test]
fn the_codec_refuses_a_header_of_the_other_direction() {
    let interp = crate::golden::interpreter("shdlc");
    let codec = interp.codec();
    let value = |json: serde_json::Value| -> protocol_dynamic::Value {
        serde_json::from_value(json).expect("a frame object")
    };
    let request_with_state = value(serde_json::json!({
        "direction": "request", "command": "READ_VERSION",
        "header": { "address": 0, "state": 0 }, "payload": {}
    }));
    let e = codec.encode(&request_with_state).unwrap_err();
    assert!(e.to_string().contains("header.state"), "{e}");
    let response_without_state = value(serde_json::json!({
        "direction": "response", "command": "DEVICE_RESET",
        "header": { "address": 0 }, "payload": {}
    }));
    let e = codec.encode(&response_without_state).unwrap_err();
    assert!(e.to_string().contains("header.state"), "{e}");
}

#[test]
fn a_noisy_stream_yields_exactly_the_good_frames() {
    let frames = frames();
    let interp = crate::golden::interpreter("shdlc");
    for (direction, layout) in [
        ("request", &shdlc::LAYOUT),
        ("response", &shdlc::RESPONSE_LAYOUT),
    ] {
        let ours: Vec<&[u8]> = frames
            .iter()
            .filter(|f| f.direction == direction)
            .map(|f| f.bytes.as_slice())
            .collect();
        let (stream, wire) = peer_frames::noisy_stream(&ours);
        // Decoders yield frames unescaped, at their offsets on the wire.
        let expected: Vec<(u64, Vec<u8>)> = wire
            .iter()
            .map(|(at, bytes)| {
                let mut buf = [0u8; shdlc::RESPONSE_MAX_FRAME_LEN];
                let frame = layout.parse_wire(bytes, &mut buf).expect("a frame");
                (*at, frame.to_vec())
            })
            .collect();
        protocol_tests::assert_stream_at_every_chunk_size::<{ shdlc::RESPONSE_DECODER_BUFFER_LEN }>(
            layout,
            &stream,
            &expected,
            |f| {
                let packet = match direction {
                    "request" => shdlc::Packet::from_request_frame(f),
                    _ => shdlc::Packet::from_response_frame(f),
                };
                packet.unwrap_or_else(|e| panic!("{direction}: {e}"));
            },
        );
        peer_frames::codec_stream(&interp, direction, &stream, &expected);
    }
}
