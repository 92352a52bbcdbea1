//! CRSF frames written and parsed by crsf-parser (`tests/vectors/crsf_parser.json`, made by
//! `scripts/crsf_parser_vectors.py`): random messages of the frame types it builds
//! (BATTERY_SENSOR, LINK_STATISTICS, RC_CHANNELS_PACKED).
//!
//! The generated code and the run-time codec each decode every frame to the recorded payload
//! and to crsf-parser's reading of the bytes, and encode the payload back to the frame's bytes.

use crate::golden;
use crate::msp_yamspy::{assert_peer_agrees, shown};

use protocol_tests::{F, hex, load_vectors};
use std::collections::BTreeSet;

mod generated {
    protocol_kit::protocol!("../specs/crsf.toml", derive(serde));
}

use generated::crsf;

#[test]
fn every_crsf_parser_frame_decodes_to_its_values_and_encodes_to_its_bytes() {
    let v = load_vectors("crsf_parser.json");
    let interp = golden::interpreter("crsf");
    let codec = interp.codec();
    let mut covered = BTreeSet::new();
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let at = frame["name"].as_str().expect("a name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let command = frame["message"].as_str().expect("the command");
        let expected = &frame["payload"];

        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let by_codec = shown(&value);
        assert_eq!(by_codec["command"], command, "{at}: the codec's command");
        assert_eq!(&by_codec["payload"], expected, "{at}: the codec's payload");
        assert_peer_agrees(
            &by_codec["payload"],
            frame,
            "peer",
            &format!("{at} (codec)"),
        );
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{at}: the codec does not encode it: {e}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{at}: the codec's bytes");

        let packet = crsf::Packet::decode(&bytes).unwrap_or_else(|e| panic!("{at}: {e}"));
        let mut buf = [0u8; crsf::MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encode");
        assert_eq!(F(&buf[..n]), F(&bytes), "{at}: the generated code's bytes");
        let by_rust = shown(&packet);
        assert_eq!(by_rust["command"], command, "{at}: the generated command");
        assert_eq!(&by_rust["payload"], expected, "{at}: the generated payload");
        assert_peer_agrees(&by_rust["payload"], frame, "peer", &format!("{at} (Rust)"));
        covered.insert(command.to_owned());
    }
    let want: BTreeSet<String> = ["BATTERY_SENSOR", "LINK_STATISTICS", "RC_CHANNELS_PACKED"]
        .map(String::from)
        .into();
    assert_eq!(covered, want, "the frame types crsf-parser builds");
    assert!(frames.len() >= 24, "{} frames", frames.len());
}
