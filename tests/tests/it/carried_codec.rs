//! The run-time codec on a packet carried in a payload, compared with generated code on the
//! fixture `protocol-codegen/tests/features/nested_packets.toml` (MSP v2 in v1, its golden
//! frames in `tests/vectors/nested_packets.json`); `msp_vectors` reads `specs/msp.toml`'s
//! v2-over-v1 vector in both.
//!
//! The codec shows a carrying field as the packet it carries (`{"command", "payload"}`, read
//! in the direction of the frame around it) where generated code's `payload_<direction>()`
//! reads one, and as its bytes with an error naming the carrying field
//! (`{"bytes", "error"}`) where that accessor fails; either form goes through JSON and
//! encodes back to the frame's bytes, and the packet form is sealed (key and size set) as
//! `set_payload_<direction>` seals it. On random carriers, both codecs agree on which carried
//! packets read, on their commands, and on their bytes framed natively.

use protocol_dynamic::{Interpreter, Value};
use protocol_kit::{Bytes, DecodeError};
use protocol_tests::{F, hex};
use serde_json::{Value as Json, json};

use super::nested_packets::fixture::nested_packets::{
    Header, MAX_FRAME_LEN, Message, Packet, Request, Response, V2Header, V2InV1, V2Packet,
};
use crate::support::{Rng, Source};

fn fixture() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/nested_packets.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn vectors(name: &str) -> Json {
    let path = format!("{}/vectors/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("the vector file is JSON")
}

/// The codec's frame value of the frame of format `format` at the start of `bytes`, in JSON.
fn decode_json(interp: &Interpreter, format: usize, bytes: &[u8]) -> Json {
    let codec = interp.codec();
    let decoded = codec
        .parse(format, bytes)
        .unwrap_or_else(|e| panic!("the codec decodes {:?}: {e}", F(bytes)));
    serde_json::to_value(codec.frame_value(&decoded, 0, bytes)).expect("a JSON form")
}

/// The bytes the codec encodes a JSON frame value to.
fn encode_json(interp: &Interpreter, json: &Json) -> Result<Vec<u8>, String> {
    let value: Value = serde_json::from_value(json.clone()).expect("the JSON form reads back");
    let codec = interp.codec();
    codec
        .encode(&value)
        .map(|e| e.bytes)
        .map_err(|e| e.to_string())
}

/// The packet a decoded v1 frame of function 255 carries, read by generated code in the
/// direction of the frame.
fn generated_carried(message: &Message) -> Result<Message, DecodeError> {
    match message {
        Message::Request(Request::V2Frame(c)) => c.payload_request().map(Message::Request),
        Message::Response(Response::V2Frame(c)) => c.payload_response().map(Message::Response),
        other => panic!("not a carrier: {other:?}"),
    }
}

/// The v2 frame of the codec's carried packet `carried`, in a frame of direction byte
/// `direction` with `flag`: the carried packet framed natively.
fn native_frame(carried: &Json, direction: u64, flag: u64) -> Json {
    json!({
        "format": "v2",
        "command": carried["command"],
        "header": { "direction": direction, "flag": flag },
        "payload": carried["payload"],
    })
}

#[test]
fn the_codec_shows_the_carried_packet_generated_code_reads() {
    let interp = fixture();
    let mut seen = 0;
    for f in vectors("nested_packets.json")["frames"]
        .as_array()
        .expect("frames")
    {
        let Some(c) = f.get("carried") else { continue };
        let name = f["name"].as_str().expect("a name");
        let bytes = hex(f["hex"].as_str().expect("hex"));
        let native = hex(c["native_hex"].as_str().expect("hex"));
        let generated = generated_carried(&Packet::decode(&bytes).expect("decodes").message)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));

        let value = decode_json(&interp, 0, &bytes);
        let carried = &value["payload"]["payload"];
        assert_eq!(carried["command"], generated.command().name(), "{name}");
        // The carried packet is the message the native v2 frame holds, in the codec too.
        let natively = decode_json(&interp, 1, &native);
        assert_eq!(carried["payload"], natively["payload"], "{name}");
        // Framed natively, the codec's carried packet is the native frame's bytes, which
        // generated code decodes to the packet it read from the carrier.
        let direction = value["header"]["direction"].as_u64().expect("a direction");
        let framed = native_frame(carried, direction, c["flag"].as_u64().expect("flag"));
        let framed = encode_json(&interp, &framed).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&framed), F(&native), "{name}: framed natively");
        let again = V2Packet::decode(&framed).expect("generated code decodes it");
        assert_eq!(again.message, generated, "{name}");
        // Through JSON and back: the frame's bytes.
        let encoded = encode_json(&interp, &value).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&encoded), F(&bytes), "{name}: encoded from JSON");
        seen += 1;
    }
    assert_eq!(seen, 5);
}

#[test]
fn a_carried_packet_given_without_key_and_size_is_sealed_as_generated_code_seals_it() {
    let interp = fixture();
    for f in vectors("nested_packets.json")["frames"]
        .as_array()
        .expect("frames")
    {
        let Some(c) = f.get("carried") else { continue };
        let name = f["name"].as_str().expect("a name");
        let bytes = hex(f["hex"].as_str().expect("hex"));
        let natively = decode_json(&interp, 1, &hex(c["native_hex"].as_str().expect("hex")));
        let mut value = decode_json(&interp, 0, &bytes);
        // Only the flag and the packet: the command's id and the size are the seal's.
        value["payload"] = json!({
            "flag": c["flag"],
            "payload": { "command": natively["command"], "payload": natively["payload"] },
        });
        let encoded = encode_json(&interp, &value).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&encoded), F(&bytes), "{name}: sealed");
    }
}

#[test]
fn a_bad_carried_packet_keeps_its_bytes_and_names_the_carrying_field() {
    let interp = fixture();
    for f in vectors("nested_packets.json")["bad_carried"]
        .as_array()
        .expect("bad carried frames")
    {
        let name = f["name"].as_str().expect("a name");
        let bytes = hex(f["hex"].as_str().expect("hex"));
        let outer = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let err = generated_carried(&outer.message).expect_err(name);
        let value = decode_json(&interp, 0, &bytes);
        let shown = &value["payload"]["payload"];
        let carrier = match &outer.message {
            Message::Request(Request::V2Frame(c)) | Message::Response(Response::V2Frame(c)) => c,
            other => panic!("{other:?}"),
        };
        assert_eq!(
            hex(shown["bytes"].as_str().expect("bytes")),
            carrier.payload.as_slice(),
            "{name}"
        );
        let error = shown["error"].as_str().expect("an error");
        assert!(error.starts_with("`V2InV1.payload`: "), "{name}: {error}");
        let want = match err {
            DecodeError::UnknownCommand { key } => format!("unknown command id {key:#x}"),
            DecodeError::PayloadLength { actual, .. } => format!("payload of {actual} bytes"),
            other => panic!("{name}: {other:?}"),
        };
        assert!(error.contains(&want), "{name}: {error}, not {want}");
        let encoded = encode_json(&interp, &value).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&encoded), F(&bytes), "{name}: encoded from JSON");
    }
}

#[test]
fn the_codec_refuses_a_carried_packet_the_carrier_cannot_hold() {
    let interp = fixture();
    let frame = |carried: Json| {
        json!({
            "command": "V2_FRAME",
            "header": { "direction": 0x3E },
            "payload": { "flag": 0, "payload": carried },
        })
    };
    let refused = |carried: Json| encode_json(&interp, &frame(carried)).expect_err("refused");
    let e = refused(json!({ "command": "NOPE", "payload": {} }));
    assert!(
        e.contains("`payload.payload.command`: no command `NOPE`"),
        "{e}"
    );
    let e = refused(json!({ "command": "IDENT", "payload": { "x": 1 } }));
    assert!(
        e.contains("`payload.payload.payload`: IDENT carries no payload"),
        "{e}"
    );
    let e = refused(json!({ "command": "HELLO_WORLD", "payload": { "text": "x".repeat(65) } }));
    assert!(e.contains("`payload.payload.payload.text`"), "{e}");
    // A carrier in the carried packet is one level down: its bytes, 255 in all with its own
    // flag, command, size and CRC, do not fit the 249 the outer carrier holds.
    let inner = json!({ "flag": 0, "command": 1, "size": 249, "payload": "00".repeat(249) });
    let e = refused(json!({ "command": "V2_FRAME", "payload": inner }));
    assert!(
        e.contains("`payload.payload`: a carried payload of 255 bytes, at most 249"),
        "{e}"
    );
    let e = refused(json!({ "bytes": "00", "extra": 1 }));
    assert!(e.contains("`payload.payload.extra`"), "{e}");
    // The carried packet's own form, and the bytes alone, encode.
    let ok = |carried: Json| encode_json(&interp, &frame(carried)).expect("encodes");
    let sealed = ok(json!({ "command": "API_VERSION", "payload": {
        "protocol_version": 0, "api_version_major": 2, "api_version_minor": 5 } }));
    let raw = json!({ "flag": 0, "command": 1, "size": 3, "payload": "000205" });
    let mut as_bytes = frame(json!(null));
    as_bytes["payload"] = raw;
    assert_eq!(
        F(&sealed),
        F(&encode_json(&interp, &as_bytes).expect("encodes"))
    );
}

/// The bytes `encode` writes into a buffer of the largest frame.
fn encoded(encode: impl FnOnce(&mut [u8]) -> Result<usize, protocol_kit::EncodeError>) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = encode(&mut buf).expect("encodes");
    buf[..n].to_vec()
}

/// A random carrier in a v1 frame: a known or random command id, a payload of random bytes
/// (a known command's size among them), a random flag and direction.
fn random_carrier(rng: &mut Rng) -> Packet {
    let ids = [1u16, 100, 200, 255, 0x4242];
    let pick = rng.below(ids.len() as u64 + 1) as usize;
    let command = ids.get(pick).copied().unwrap_or(rng.next_u64() as u16);
    let len = match rng.below(4) {
        0 => 3,
        1 => 0,
        _ => rng.below(50) as usize,
    };
    let bytes: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
    let c = V2InV1 {
        flag: rng.next_u64() as u8,
        command,
        size: len as u16,
        payload: Bytes::from_slice(&bytes).expect("fits"),
    };
    let request = rng.below(2) == 0;
    let (direction, message) = if request {
        (0x3C, Message::Request(Request::V2Frame(c)))
    } else {
        (0x3E, Message::Response(Response::V2Frame(c)))
    };
    Packet {
        header: Header { direction },
        message,
    }
}

#[test]
fn on_random_carriers_both_codecs_read_the_same_carried_packets() {
    let interp = fixture();
    let mut rng = Rng(0x0041);
    let (mut read, mut refused) = (0, 0);
    for _ in 0..2000 {
        let packet = random_carrier(&mut rng);
        let bytes = encoded(|buf| packet.encode(buf));
        let value = decode_json(&interp, 0, &bytes);
        let shown = &value["payload"]["payload"];
        match generated_carried(&packet.message) {
            Ok(message) => {
                assert_eq!(shown["command"], message.command().name(), "{value}");
                let flag = value["payload"]["flag"].as_u64().expect("flag");
                let direction = value["header"]["direction"].as_u64().expect("direction");
                let framed = encode_json(&interp, &native_frame(shown, direction, flag))
                    .unwrap_or_else(|e| panic!("{value}: {e}"));
                let native = V2Packet {
                    header: V2Header {
                        direction: direction as u8,
                        flag: flag as u8,
                    },
                    message,
                };
                let native = encoded(|buf| native.encode(buf));
                assert_eq!(F(&framed), F(&native), "{value}");
                read += 1;
            }
            Err(_) => {
                assert!(shown["error"].is_string(), "{value}");
                refused += 1;
            }
        }
        let encoded = encode_json(&interp, &value).unwrap_or_else(|e| panic!("{value}: {e}"));
        assert_eq!(F(&encoded), F(&bytes), "{value}");
    }
    // Both outcomes are exercised.
    assert!(
        read > 200 && refused > 200,
        "{read} read, {refused} refused"
    );
}
