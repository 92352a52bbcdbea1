//! Feetech SCS/STS packets from Feetech's Python SDK (`tests/vectors/feetech_scservo.json`,
//! made by `scripts/feetech_scservo_vectors.py`): the instruction packets its packet handler
//! writes for random calls, one or more of every command of `specs/feetech.toml`, and the status
//! packets it reads as their answers.
//!
//! The generated code and the run-time codec, each given the packet's direction, decode every
//! packet to the SDK's values and encode them back to the packet's bytes; a stream of the
//! packets with noise and damaged packets between them yields exactly the good packets, in
//! both; the answer to the model-number READ is typed by the STS3215's registers.

use crate::peer_frames;

peer_frames::directed_link!(feetech, "../specs/feetech.toml");

#[test]
fn every_sdk_packet_decodes_to_its_values_and_encodes_to_its_bytes() {
    let frames = peer_frames::frames("feetech_scservo.json");
    let (covered, statuses) = check_every_frame(&frames);
    assert_eq!(
        covered,
        all_commands(),
        "every command of the spec has SDK packets"
    );
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
    check_noisy_streams(&peer_frames::frames("feetech_scservo.json"));
}
