//! Frames a link's reference implementation wrote (`tests/vectors/NAME_PEER.json`, each frame
//! with its direction, command, the peer's decoded values and the scale of every scaled field),
//! checked against the generated code and the run-time codec of a spec whose directions are
//! given to the decoder; and the noisy stream every such link is decoded from. The per-link
//! files (`vesc_pyvesc`, `feetech_scservo`, `lx16a_pylx16a`) expand [`directed_link`] for their
//! spec and call what it writes.

use protocol_dynamic::{Codec, Interpreter, Item};
use protocol_tests::{F, hex, load_vectors};
use serde_json::{Map, Value, json};
use std::collections::BTreeSet;

/// One frame of a peer's vectors.
pub struct PeerFrame {
    pub name: String,
    pub direction: String,
    /// None for a direction that carries one struct in place of a command.
    pub command: Option<String>,
    pub header: Value,
    pub payload: Value,
    pub scales: Map<String, Value>,
    pub bytes: Vec<u8>,
}

/// Every frame of `file`.
pub fn frames(file: &str) -> Vec<PeerFrame> {
    let v = load_vectors(file);
    v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .map(|f| PeerFrame {
            name: f["name"].as_str().expect("a name").to_owned(),
            direction: f["direction"].as_str().expect("a direction").to_owned(),
            command: f["command"].as_str().map(str::to_owned),
            header: f.get("header").cloned().unwrap_or_else(|| json!({})),
            payload: f["payload"].clone(),
            scales: f["scales"].as_object().expect("scales").clone(),
            bytes: hex(f["hex"].as_str().expect("hex")),
        })
        .collect()
}

/// A JSON value through its text, as a decoder prints it (an `f32` keeps its shortest form).
pub fn shown(value: &impl serde::Serialize) -> Value {
    serde_json::from_str(&serde_json::to_string(value).expect("JSON")).expect("JSON")
}

/// `ours` is the peer's `theirs`: the same shape, the same keys, numbers equal or, for a field
/// the scales name, within half its scale.
pub fn assert_agrees(
    ours: &Value,
    theirs: &Value,
    path: &str,
    scales: &Map<String, Value>,
    at: &str,
) {
    match (ours, theirs) {
        (Value::Object(o), Value::Object(t)) => {
            let ok: BTreeSet<_> = o.keys().collect();
            let tk: BTreeSet<_> = t.keys().collect();
            assert_eq!(ok, tk, "{at}: the fields of `{path}`");
            for (k, v) in t {
                let inner = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                assert_agrees(&o[k], v, &inner, scales, at);
            }
        }
        (Value::Array(o), Value::Array(t)) => {
            assert_eq!(o.len(), t.len(), "{at}: the length of `{path}`");
            for (o, t) in o.iter().zip(t) {
                assert_agrees(o, t, path, scales, at);
            }
        }
        (Value::Number(o), Value::Number(t)) => match scales.get(path).and_then(Value::as_f64) {
            Some(scale) => {
                let (o, t) = (o.as_f64().expect("a number"), t.as_f64().expect("a number"));
                let within = scale / 2.0 + t.abs() * 1e-12;
                assert!(
                    (o - t).abs() <= within,
                    "{at}: `{path}` is {o}, the peer's {t}"
                );
            }
            None => assert_eq!(o, t, "{at}: `{path}`"),
        },
        _ => assert_eq!(ours, theirs, "{at}: `{path}`"),
    }
}

/// The frame object of a peer frame's values, as `protocol encode` reads it.
pub fn object(frame: &PeerFrame) -> Value {
    // In the order a packet serializes: the command before the payload it types (the packet's
    // deserializer reads the payload by the command it has already seen).
    let mut object = Map::new();
    if let Some(command) = &frame.command {
        object.insert("command".into(), Value::from(command.as_str()));
    }
    object.insert("direction".into(), Value::from(frame.direction.as_str()));
    object.insert("header".into(), frame.header.clone());
    object.insert("payload".into(), frame.payload.clone());
    Value::Object(object)
}

/// The run-time codec, given the frame's direction, decodes it to the peer's values and encodes
/// the peer's values to its bytes.
pub fn check_codec(interp: &Interpreter, frame: &PeerFrame) {
    let at = format!("{} (codec)", frame.name);
    let codec = interp.codec();
    let di = codec
        .direction_index(&frame.direction)
        .expect("a direction");
    let codec = codec.with_direction(Some(di));
    let decoded = codec
        .parse(0, &frame.bytes)
        .unwrap_or_else(|e| panic!("{at}: the codec does not decode it: {e:?}"));
    let by_codec = shown(&codec.frame_value(&decoded, 0, &frame.bytes));
    assert_eq!(
        by_codec.get("command").and_then(Value::as_str),
        frame.command.as_deref(),
        "{at}: command"
    );
    assert_eq!(by_codec["header"], frame.header, "{at}: header");
    assert_eq!(
        by_codec["direction"],
        frame.direction.as_str(),
        "{at}: direction"
    );
    assert_agrees(&by_codec["payload"], &frame.payload, "", &frame.scales, &at);
    let value: protocol_dynamic::Value =
        serde_json::from_value(object(frame)).expect("a frame object");
    let encoded = interp
        .codec()
        .encode(&value)
        .unwrap_or_else(|e| panic!("{at}: the codec does not encode it: {e}"));
    assert_eq!(F(&encoded.bytes), F(&frame.bytes), "{at}: encoded bytes");
}

/// The generated code decodes the frame (by `decode`, in the frame's direction) to the peer's
/// values, and the packet read from the peer's values encodes (by `encode`) to its bytes.
pub fn check_generated<P, E>(
    frame: &PeerFrame,
    decode: impl Fn(&[u8], &str) -> Result<P, E>,
    encode: impl Fn(&P) -> Vec<u8>,
) where
    P: serde::Serialize + serde::de::DeserializeOwned,
    E: core::fmt::Debug,
{
    let at = format!("{} (Rust)", frame.name);
    let packet = decode(&frame.bytes, &frame.direction)
        .unwrap_or_else(|e| panic!("{at}: does not decode: {e:?}"));
    let by_rust = shown(&packet);
    assert_eq!(
        by_rust.get("command").and_then(Value::as_str),
        frame.command.as_deref(),
        "{at}: command"
    );
    assert_eq!(by_rust["header"], frame.header, "{at}: header");
    assert_agrees(&by_rust["payload"], &frame.payload, "", &frame.scales, &at);
    let read: P = serde_json::from_value(object(frame)).unwrap_or_else(|e| panic!("{at}: {e}"));
    assert_eq!(F(&encode(&read)), F(&frame.bytes), "{at}: encoded bytes");
    assert_eq!(
        F(&encode(&packet)),
        F(&frame.bytes),
        "{at}: re-encoded bytes"
    );
}

/// A peer's values (`object`, a frame object as `protocol encode` reads it) are the frame's
/// `bytes` again, encoded by the run-time codec and, read into a packet, by the generated
/// code's `encode`.
pub fn assert_encodes_back<P: serde::de::DeserializeOwned>(
    codec: &Codec<'_>,
    object: Value,
    bytes: &[u8],
    at: &str,
    encode: impl Fn(&P) -> Vec<u8>,
) {
    let value: protocol_dynamic::Value =
        serde_json::from_value(object.clone()).expect("a frame object");
    let encoded = codec
        .encode(&value)
        .unwrap_or_else(|e| panic!("{at}: the codec does not encode it: {e}"));
    assert_eq!(F(&encoded.bytes), F(bytes), "{at}: the codec's bytes");
    let packet: P = serde_json::from_value(object).unwrap_or_else(|e| panic!("{at}: {e}"));
    assert_eq!(
        F(&encode(&packet)),
        F(bytes),
        "{at}: the generated code's bytes"
    );
}

/// Bytes a link never starts a frame with at this place: noise between the frames.
const NOISE: [&[u8]; 3] = [
    &[0x00, 0x13, 0x37],
    &[0xA5],
    &[0x7E, 0x00, 0x11, 0x22, 0x33],
];

/// `frames` concatenated with noise between them and, before every third frame, a copy of it
/// whose last-but-one byte is flipped (a damaged check or end byte); the stream and the good
/// frames at their offsets.
pub fn noisy_stream(frames: &[&[u8]]) -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let mut stream = Vec::new();
    let mut expected = Vec::new();
    for (i, frame) in frames.iter().enumerate() {
        stream.extend_from_slice(NOISE[i % NOISE.len()]);
        if i % 3 == 1 {
            let mut bad = frame.to_vec();
            let k = bad.len() - 2;
            bad[k] ^= 0x40;
            stream.extend_from_slice(&bad);
        }
        expected.push((stream.len() as u64, frame.to_vec()));
        stream.extend_from_slice(frame);
    }
    stream.extend_from_slice(NOISE[0]);
    (stream, expected)
}

/// The run-time codec's stream decoder, given `direction`, yields exactly `expected` from
/// `stream` at every chunk size, each frame decoded.
pub fn codec_stream(
    interp: &Interpreter,
    direction: &str,
    stream: &[u8],
    expected: &[(u64, Vec<u8>)],
) {
    let codec = interp.codec();
    let di = codec.direction_index(direction);
    let codec = codec.with_direction(di);
    for chunk in 1..=stream.len() {
        let mut s = codec.stream(0).expect("a frame format");
        let mut got = Vec::new();
        for part in stream.chunks(chunk) {
            let mut input = part;
            while let Some(item) = s.next_item(&mut input) {
                if let Item::Frame {
                    offset,
                    bytes,
                    decoded,
                } = item
                {
                    assert!(decoded.is_ok(), "chunk {chunk}: {decoded:?}");
                    got.push((offset, bytes.to_vec()));
                }
            }
        }
        assert_eq!(got, expected, "{direction}: chunk size {chunk}");
    }
}

/// The generated module of a link whose directions are given to the decoder, `$link` expanded
/// from the spec at `$spec`, with what every peer test of such a link runs on the peer's
/// frames: `decode` (by direction) and `encode`, `check_every_frame` (the codec and the
/// generated code on each frame; the commands covered and the count of frames that carry no
/// command), `all_commands`, and `check_noisy_streams` (per direction, the generated decoder
/// and the codec's at every chunk size). A macro, as the generated types differ per link.
macro_rules! directed_link {
    ($link:ident, $spec:tt) => {
        mod generated {
            protocol_kit::protocol!($spec, derive(serde));
        }

        use generated::$link;

        fn decode(
            bytes: &[u8],
            direction: &str,
        ) -> Result<$link::Packet, protocol_kit::DecodeError> {
            match direction {
                "request" => $link::Packet::decode_request(bytes),
                "response" => $link::Packet::decode_response(bytes),
                other => panic!("no direction {other}"),
            }
        }

        fn encode(packet: &$link::Packet) -> Vec<u8> {
            let mut buf = [0u8; $link::MAX_FRAME_LEN];
            let n = packet.encode(&mut buf).expect("encodes");
            buf[..n].to_vec()
        }

        fn check_every_frame(
            frames: &[$crate::peer_frames::PeerFrame],
        ) -> (std::collections::BTreeSet<String>, usize) {
            let interp = $crate::golden::interpreter(stringify!($link));
            let mut covered = std::collections::BTreeSet::new();
            let mut without_command = 0;
            for frame in frames {
                $crate::peer_frames::check_codec(&interp, frame);
                $crate::peer_frames::check_generated(frame, decode, encode);
                match &frame.command {
                    Some(command) => {
                        covered.insert(command.clone());
                    }
                    None => without_command += 1,
                }
            }
            (covered, without_command)
        }

        fn all_commands() -> std::collections::BTreeSet<String> {
            $link::Command::ALL
                .iter()
                .map(|(_, name)| (*name).to_owned())
                .collect()
        }

        fn check_noisy_streams(frames: &[$crate::peer_frames::PeerFrame]) {
            let interp = $crate::golden::interpreter(stringify!($link));
            for direction in ["request", "response"] {
                let ours: Vec<&[u8]> = frames
                    .iter()
                    .filter(|f| f.direction == direction)
                    .map(|f| f.bytes.as_slice())
                    .collect();
                let (stream, expected) = $crate::peer_frames::noisy_stream(&ours);
                protocol_tests::assert_stream_at_every_chunk_size::<{ $link::DECODER_BUFFER_LEN }>(
                    &$link::LAYOUT,
                    &stream,
                    &expected,
                    |f| {
                        decode(f, direction).unwrap_or_else(|e| panic!("{direction}: {e}"));
                    },
                );
                $crate::peer_frames::codec_stream(&interp, direction, &stream, &expected);
            }
        }
    };
}

pub(crate) use directed_link;
