//! A packet carried inside another's payload on the fixture
//! `protocol-codegen/tests/features/nested_packets.toml`: MSP v2 messages carried by MSP v1
//! frames of function 255 (`carries = "command"` on the carrying struct's bytes).
//!
//! The golden frames (`tests/vectors/nested_packets.json`, written by
//! `tests/vectors/nested_packets.py` from the layout of INAV's MSP V2 description, whose own
//! example frames the script reproduces byte for byte) decode in generated code and in the
//! run-time codec and encode back to their bytes. Each carried frame names the same message
//! framed natively as v2: the carried packet read from the carrying struct is that message,
//! and sealing the native message into a carrying struct gives the carried frame's bytes. A
//! well framed carrier of a packet the link does not know, or of a payload that is not its
//! command's, decodes (its bytes are the carrier's) and its carried packet is an error naming
//! the carrying field; a carried CRC that is wrong fails the carrier's own decoding. A stream
//! of the frames with garbage and damaged copies yields exactly the good frames at every chunk
//! size, each carried packet readable.

use protocol_dynamic::Interpreter;
use protocol_kit::{DecodeError, EncodeError};
use protocol_tests::{F, assert_link_stream_at_every_chunk_size, hex};

pub(crate) mod fixture {
    protocol_kit::protocol!("../protocol-codegen/tests/features/nested_packets.toml");
}
use fixture::nested_packets::{
    ANY_DECODER_BUFFER_LEN, AnyLayout, AnyPacket, MAX_FRAME_LEN, Message, Packet, Request,
    Response, V2InV1, V2Packet,
};

fn vectors() -> serde_json::Value {
    let path = format!("{}/vectors/nested_packets.json", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("the vector file is JSON")
}

fn interpreter() -> Interpreter {
    let path = format!(
        "{}/../protocol-codegen/tests/features/nested_packets.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    Interpreter::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The carrying struct of a v1 frame of function 255, and the message it sits in.
fn carrier(message: &Message) -> &V2InV1 {
    match message {
        Message::Request(Request::V2Frame(c)) | Message::Response(Response::V2Frame(c)) => c,
        other => panic!("not a carrier: {other:?}"),
    }
}

/// The packet `c` carries, read in the direction of the message around it.
fn carried(message: &Message, c: &V2InV1) -> Result<Message, DecodeError> {
    match message {
        Message::Request(_) => c.payload_request().map(Message::Request),
        Message::Response(_) => c.payload_response().map(Message::Response),
    }
}

#[test]
fn golden_frames_decode_and_encode_back_in_both_codecs() {
    let interp = interpreter();
    let codec = interp.codec();
    let v = vectors();
    let frames = v["frames"].as_array().expect("frames");
    assert_eq!(frames.len(), 8);
    for f in frames {
        let name = f["name"].as_str().expect("a name");
        let bytes = hex(f["hex"].as_str().expect("hex"));
        let format = usize::from(bytes[1] == b'X');
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = if format == 0 {
            let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
            packet.encode(&mut buf).expect("encodes")
        } else {
            let packet = V2Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
            packet.encode(&mut buf).expect("encodes")
        };
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: generated encode");

        let decoded = codec.parse(format, &bytes).expect("the codec decodes");
        let value = codec.frame_value(&decoded, 0, &bytes);
        let encoded = codec.encode(&value).expect("the codec encodes");
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: codec encode");
    }
}

#[test]
fn a_carried_packet_is_the_message_framed_natively_and_seals_back() {
    let v = vectors();
    let mut seen = 0;
    for f in v["frames"].as_array().expect("frames") {
        let Some(c) = f.get("carried") else { continue };
        let name = f["name"].as_str().expect("a name");
        let outer = Packet::decode(&hex(f["hex"].as_str().expect("hex"))).expect("decodes");
        let native = V2Packet::decode(&hex(c["native_hex"].as_str().expect("hex")))
            .unwrap_or_else(|e| panic!("{name}: native {e:?}"));
        let inner = carrier(&outer.message);
        assert_eq!(u64::from(inner.command), c["command"].as_u64().expect("id"));
        let got = carried(&outer.message, inner).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(got, native.message, "{name}: carried packet");

        // The native message sealed into an empty carrier, framed in v1: the same bytes.
        let mut sealed = V2InV1 {
            flag: u8::try_from(c["flag"].as_u64().expect("flag")).expect("a byte"),
            ..V2InV1::default()
        };
        let message = match &native.message {
            Message::Request(m) => {
                sealed.set_payload_request(m).expect("seals");
                Message::Request(Request::V2Frame(sealed))
            }
            Message::Response(m) => {
                sealed.set_payload_response(m).expect("seals");
                Message::Response(Response::V2Frame(sealed))
            }
        };
        let packet = Packet {
            header: outer.header,
            message,
        };
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encodes");
        assert_eq!(
            F(&buf[..n]),
            F(&hex(f["hex"].as_str().expect("hex"))),
            "{name}: sealed"
        );
        seen += 1;
    }
    assert_eq!(seen, 5);
}

#[test]
fn a_bad_carried_packet_is_an_error_naming_the_carrying_field() {
    let v = vectors();
    for f in v["bad_carried"].as_array().expect("bad carried frames") {
        let name = f["name"].as_str().expect("a name");
        let outer = Packet::decode(&hex(f["hex"].as_str().expect("hex")))
            .unwrap_or_else(|e| panic!("{name}: the carrier decodes, {e:?}"));
        let err = carried(&outer.message, carrier(&outer.message)).expect_err(name);
        match (f["error"].as_str().expect("an error"), err) {
            ("UnknownCommand", DecodeError::UnknownCommand { key }) => assert_eq!(key, 0x7777),
            ("PayloadLength", DecodeError::PayloadLength { .. }) => {}
            (want, got) => panic!("{name}: {want} but {got:?}"),
        }
    }
    // A wrong carried CRC: the carrier's own check fails, in both codecs.
    let bytes = hex(v["bad_carried_crc"].as_str().expect("hex"));
    let got = Packet::decode(&bytes);
    assert!(
        matches!(got, Err(DecodeError::PayloadCheck { .. })),
        "{got:?}"
    );
    let interp = interpreter();
    assert!(interp.codec().parse(0, &bytes).is_err());
}

#[test]
fn sealing_refuses_what_the_carrier_cannot_hold() {
    let mut c = V2InV1::default();
    // A payload of 64 bytes of text fits the 249 carried bytes; the id 0x4242 fits `command`.
    let hello = Response::HelloWorld(fixture::nested_packets::HelloWorld {
        text: protocol_kit::Str::from_text(&"x".repeat(64)).expect("fits"),
    });
    c.set_payload_response(&hello).expect("seals");
    assert_eq!((c.command, c.size), (0x4242, 64));
    assert_eq!(c.payload_response(), Ok(hello));
    // A carrier that carries a carrier: sealed as bytes, read back one level at a time.
    let outer = Response::V2Frame(c);
    let mut twice = V2InV1::default();
    twice.set_payload_response(&outer).expect("seals");
    assert_eq!(twice.payload_response(), Ok(outer));
    // Each carrier adds the six bytes of flag, command, size and CRC: the 64 bytes of text
    // under 31 carriers are 250 bytes, one more than the 249 a 32nd carrier holds.
    let mut inner = hello;
    for level in 1..=32 {
        let mut c = V2InV1::default();
        let sealed = c.set_payload_response(&inner);
        if level < 32 {
            sealed.unwrap_or_else(|e| panic!("level {level}: {e:?}"));
            assert_eq!(usize::from(c.size), 64 + 6 * (level - 1));
            inner = Response::V2Frame(c);
        } else {
            let err = sealed.expect_err("250 bytes in 249");
            assert!(
                matches!(err, EncodeError::ValueOutOfRange { .. }),
                "{err:?}"
            );
            assert_eq!(err.place().map(|p| p.field()), Some("V2InV1.payload"));
        }
    }
}

#[test]
fn golden_stream_yields_exactly_the_good_frames_at_every_chunk_size() {
    let v = vectors();
    let stream = &v["streams"][0];
    let bytes = hex(stream["hex"].as_str().expect("hex"));
    let expected: Vec<(u64, Vec<u8>)> = stream["expected_frames"]
        .as_array()
        .expect("expected frames")
        .iter()
        .map(|f| {
            let offset = f["offset"].as_u64().expect("offset");
            (offset, hex(f["hex"].as_str().expect("hex")))
        })
        .collect();
    assert_eq!(expected.len(), 8);
    assert_link_stream_at_every_chunk_size::<_, ANY_DECODER_BUFFER_LEN>(
        AnyLayout,
        &bytes,
        &expected,
        |f| {
            let packet = AnyPacket::from_frame(f).expect("decodes");
            if let AnyPacket::V1(p) = packet
                && p.message.command() == fixture::nested_packets::Command::V2Frame
            {
                carried(&p.message, carrier(&p.message)).expect("a carried packet");
            }
        },
    );
}
