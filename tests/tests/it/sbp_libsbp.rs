//! SBP frames written and decoded by libsbp's Python package (`tests/vectors/sbp_libsbp.json`,
//! made by `scripts/sbp_libsbp_vectors.py`): random messages of every command of
//! `specs/sbp.toml`.
//!
//! The generated code and the run-time codec each decode every frame to libsbp's values (a
//! scaled field within half its scale of libsbp's, every other value equal, bit members,
//! enumerations, log texts and the sender id included), and encode libsbp's values back to the
//! frame's bytes. A stream of the frames with garbage and a damaged copy of each yields exactly
//! the good frames at every chunk size.

use crate::golden;
use crate::peer_frames::{assert_agrees, assert_encodes_back, shown};

use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::json;
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/sbp.toml", derive(serde));
}

use generated::sbp;

#[test]
fn every_libsbp_frame_decodes_to_its_values_and_encodes_to_its_bytes() {
    let v = load_vectors("sbp_libsbp.json");
    let interp = golden::interpreter("sbp");
    let codec = interp.codec();
    let mut covered = BTreeSet::new();
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let at = frame["name"].as_str().expect("a name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let command = frame["message"].as_str().expect("the command");
        let expected = &frame["payload"];
        let sender = &frame["header"]["sender"];
        let scales = frame["scales"].as_object().expect("scales");

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
        let by_codec = shown(&codec.frame_value(&decoded, 0, &bytes));
        assert_eq!(by_codec["command"], command, "{at}: the codec's command");
        assert_eq!(
            &by_codec["header"]["sender"], sender,
            "{at}: the codec's sender"
        );
        assert_agrees(
            &by_codec["payload"],
            expected,
            "",
            scales,
            &format!("{at} (codec)"),
        );

        let packet = sbp::Packet::decode(&bytes).unwrap_or_else(|e| panic!("{at}: {e}"));
        let by_rust = shown(&packet);
        assert_eq!(by_rust["command"], command, "{at}: the generated command");
        assert_eq!(
            &by_rust["header"]["sender"], sender,
            "{at}: the generated sender"
        );
        assert_agrees(
            &by_rust["payload"],
            expected,
            "",
            scales,
            &format!("{at} (Rust)"),
        );

        // libsbp's values, encoded by each, are the frame again.
        let object =
            json!({ "command": command, "header": { "sender": sender }, "payload": expected });
        assert_encodes_back(&codec, object, &bytes, at, |packet: &sbp::Packet| {
            let mut buf = [0u8; sbp::MAX_FRAME_LEN];
            let n = packet
                .encode(&mut buf)
                .unwrap_or_else(|e| panic!("{at}: {e}"));
            buf[..n].to_vec()
        });
        covered.insert(command.to_owned());
    }
    let all: BTreeSet<String> = sbp::Command::ALL
        .iter()
        .map(|(_, name)| (*name).to_owned())
        .collect();
    assert_eq!(covered, all, "every command of the spec has libsbp frames");
    assert!(frames.len() >= 4 * all.len(), "{} frames", frames.len());
}

#[test]
fn libsbp_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = load_vectors("sbp_libsbp.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    assert_eq!(expected.len(), 88);
    assert_stream_at_every_chunk_size::<{ sbp::DECODER_BUFFER_LEN }>(
        &sbp::LAYOUT,
        &bytes,
        &expected,
        |f| {
            assert!(sbp::Packet::decode(f).is_ok(), "{:?}", F(f));
        },
    );
}
