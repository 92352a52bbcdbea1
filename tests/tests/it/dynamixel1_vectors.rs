//! Dynamixel Protocol 1.0 golden vectors (`tests/vectors/dynamixel_protocol1.json`, made by
//! running the ROBOTIS SDK's Python protocol 1.0 handler on a fake port; the READ and status
//! examples are also the e-Manual's): every packet decodes in its direction to its recorded
//! values and encodes to the exact bytes, by generated code and by the run-time codec; the status
//! stream yields exactly its expected packets at every chunk size, in both. Instruction and
//! status packets share one layout, so each is decoded in the direction it was recorded in; a
//! packet decoded in the other direction is an error or the other direction's message, never a
//! panic.
//!
//! Every vector is expressible: all 15 frames are checked (none is left out).

use crate::golden;

use protocol_dynamic::{Item, Value};
use protocol_kit::{Bytes, DecodeError, Group, PacketDecoder, PacketEvent};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};

protocol_kit::protocol!("../specs/dynamixel1.toml");

use dynamixel1::*;

type Json = serde_json::Value;

fn u(v: &Json, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn byte_list(v: &Json) -> Vec<u8> {
    v.as_array()
        .expect("a byte list")
        .iter()
        .map(|b| u8::try_from(b.as_u64().expect("a number")).expect("a byte"))
        .collect()
}

fn bytes<const N: usize>(v: &Json) -> Bytes<N> {
    Bytes::from_slice(&byte_list(v)).expect("fits")
}

fn status(error: u8, params: &Json) -> Status {
    let bit = |n: u8| error & (1 << n) != 0;
    Status {
        input_voltage: bit(0),
        angle_limit: bit(1),
        overheating: bit(2),
        range: bit(3),
        checksum: bit(4),
        overload: bit(5),
        instruction: bit(6),
        error_reserved: error >> 7,
        params: bytes(params),
    }
}

/// The spec's command name of an instruction byte, for the run-time codec's frame objects.
fn command_name(instruction: u64) -> &'static str {
    match instruction {
        0x01 => "PING",
        0x02 => "READ",
        0x03 => "WRITE",
        0x04 => "REG_WRITE",
        0x05 => "ACTION",
        0x06 => "FACTORY_RESET",
        0x83 => "SYNC_WRITE",
        0x92 => "BULK_READ",
        other => panic!("vector not covered: instruction {other:#x}"),
    }
}

/// The request a vector's fields describe.
fn request(frame: &Json) -> Request {
    let v = &frame["fields"];
    let write = || Write {
        address: u(v, "address") as u8,
        data: bytes(&v["data"]),
    };
    match u(frame, "instruction") {
        0x01 => Request::Ping,
        0x02 => Request::Read(Read {
            address: u(v, "address") as u8,
            length: u(v, "length") as u8,
        }),
        0x03 => Request::Write(write()),
        0x04 => Request::RegWrite(write()),
        0x05 => Request::Action,
        0x06 => Request::FactoryReset,
        0x83 => {
            let mut servos = Group::new();
            for s in v["servos"].as_array().expect("servos") {
                servos
                    .push(SyncWriteServo {
                        id: u(s, "id") as u8,
                        data: bytes(&s["data"]),
                    })
                    .expect("room");
            }
            Request::SyncWrite(SyncWrite {
                start_address: u(v, "start_address") as u8,
                data_length: u(v, "data_length") as u8,
                servos,
            })
        }
        0x92 => {
            let mut reads = Group::new();
            for r in v["reads"].as_array().expect("reads") {
                reads
                    .push(BulkReadEntry {
                        length: u(r, "length") as u8,
                        id: u(r, "id") as u8,
                        address: u(r, "address") as u8,
                    })
                    .expect("room");
            }
            Request::BulkRead(BulkRead {
                reserved: u(v, "reserved") as u8,
                reads,
            })
        }
        other => panic!("vector not covered: instruction {other:#x}"),
    }
}

/// The packet a vector describes, and whether it is a status packet (a response).
fn expected(frame: &Json) -> (Packet, bool) {
    let header = Header {
        id: u(frame, "id") as u8,
    };
    match frame["packet"].as_str().expect("packet") {
        "instruction" => (
            Packet {
                header,
                message: Message::Request(request(frame)),
            },
            false,
        ),
        "status" => (
            Packet {
                header,
                message: Message::Response(status(
                    u(frame, "error") as u8,
                    &frame["fields"]["params"],
                )),
            },
            true,
        ),
        other => panic!("unknown packet kind {other}"),
    }
}

#[test]
fn every_packet_decodes_in_its_direction_and_encodes_to_its_bytes() {
    let v = load_vectors("dynamixel_protocol1.json");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let wire = hex(frame["hex"].as_str().expect("hex"));
        assert_eq!(u64::from(wire[3]), u(frame, "length"), "{name}: LEN");
        assert_eq!(
            u64::from(wire[wire.len() - 1]),
            u(frame, "checksum"),
            "{name}: checksum"
        );
        let (packet, is_status) = expected(frame);
        let decoded = if is_status {
            Packet::decode_response(&wire)
        } else {
            Packet::decode_request(&wire)
        };
        assert_eq!(decoded, Ok(packet), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let len = packet
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(F(&buf[..len]), F(&wire), "{name}: encode");
        assert_eq!(packet.encoded_len(), len, "{name}: encoded_len");
        let mut bad = wire.clone();
        bad[2] ^= 0x01;
        let rejected = if is_status {
            Packet::decode_response(&bad)
        } else {
            Packet::decode_request(&bad)
        };
        assert_eq!(
            rejected,
            Err(DecodeError::Frame(protocol_kit::Reject::BadChecksum)),
            "{name}: a flipped id bit"
        );
        n += 1;
    }
    assert_eq!(n, 15, "every vector was checked");
}

#[test]
fn a_packet_decoded_in_the_other_direction_is_an_error_or_the_other_message() {
    let v = load_vectors("dynamixel_protocol1.json");
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let wire = hex(frame["hex"].as_str().expect("hex"));
        let (_, is_status) = expected(frame);
        if is_status {
            // The error byte read as an instruction: 0x00 and 0x24 are no instruction.
            assert_eq!(
                Packet::decode_request(&wire),
                Err(DecodeError::UnknownCommand {
                    key: u(frame, "error")
                }),
                "{name}"
            );
        } else {
            // A status packet takes any bytes: the instruction reads as its error byte.
            let got = Packet::decode_response(&wire).unwrap_or_else(|e| panic!("{name}: {e}"));
            let Message::Response(s) = got.message else {
                panic!("{name}: a response")
            };
            assert_eq!(s.params.as_slice(), &wire[5..wire.len() - 1], "{name}");
            // It encodes back to the same bytes: nothing was lost.
            let mut buf = [0u8; MAX_FRAME_LEN];
            let len = got.encode(&mut buf).expect("encodes");
            assert_eq!(F(&buf[..len]), F(&wire), "{name}");
        }
    }
}

/// The value `protocol decode` prints for a vector's payload: byte lists as hex, a status
/// packet's error byte as its bits.
fn payload_value(frame: &Json) -> Json {
    fn hexed(v: &Json) -> Json {
        match v {
            Json::Object(m) => Json::Object(
                m.iter()
                    .map(|(k, x)| {
                        let x = match k.as_str() {
                            "data" | "params" => Json::from(format!("{:?}", F(&byte_list(x)))),
                            _ => hexed(x),
                        };
                        (k.clone(), x)
                    })
                    .collect(),
            ),
            Json::Array(a) => Json::Array(a.iter().map(hexed).collect()),
            other => other.clone(),
        }
    }
    let mut p = hexed(&frame["fields"]);
    if frame["packet"] == "status" {
        let error = u(frame, "error");
        let names = [
            "input_voltage",
            "angle_limit",
            "overheating",
            "range",
            "checksum",
            "overload",
            "instruction",
        ];
        let mut o = serde_json::Map::new();
        for (i, n) in names.iter().enumerate() {
            o.insert((*n).into(), Json::from(error & (1 << i) != 0));
        }
        o.insert("error_reserved".into(), Json::from(error >> 7));
        o.insert("params".into(), p["params"].take());
        p = Json::Object(o);
    }
    p
}

#[test]
fn the_run_time_codec_decodes_and_encodes_every_packet_in_its_direction() {
    let v = load_vectors("dynamixel_protocol1.json");
    let interp = golden::interpreter("dynamixel1");
    let mut n = 0;
    for frame in v["frames"].as_array().expect("frames") {
        let name = frame["name"].as_str().unwrap_or("?");
        let wire = hex(frame["hex"].as_str().expect("hex"));
        let (_, is_status) = expected(frame);
        let direction = if is_status { "response" } else { "request" };
        let codec = interp.codec();
        let di = codec.direction_index(direction).expect("direction");
        // Without a direction, the codec cannot decode a frame of this spec.
        assert!(
            matches!(
                codec.parse(0, &wire),
                Err(protocol_dynamic::DecodeIssue::DirectionNotGiven { .. })
            ),
            "{name}"
        );
        let codec = codec.with_direction(Some(di));
        let decoded = codec
            .parse(0, &wire)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let shown = serde_json::to_value(codec.frame_value(&decoded, 0, &wire)).expect("JSON");
        assert_eq!(shown["direction"], direction, "{name}");
        assert_eq!(shown["header"], serde_json::json!({ "id": u(frame, "id") }));
        assert_eq!(shown["payload"], payload_value(frame), "{name}: payload");
        let mut object = serde_json::json!({
            "direction": direction,
            "header": { "id": u(frame, "id") },
            "payload": payload_value(frame),
        });
        if is_status {
            assert!(shown.get("command").is_none(), "{name}: no command");
        } else {
            let command = command_name(u(frame, "instruction"));
            assert_eq!(shown["command"], command, "{name}");
            object["command"] = Json::from(command);
        }
        // A codec given no direction encodes the object by the direction it names.
        let object: Value = serde_json::from_value(object).expect("a frame object");
        let encoded = interp.codec().encode(&object).expect("encodes");
        assert_eq!(F(&encoded.bytes), F(&wire), "{name}: encode");
        n += 1;
    }
    assert_eq!(n, 15);
}

#[test]
fn the_status_stream_yields_its_packets_at_every_chunk_size() {
    let v = load_vectors("dynamixel_protocol1.json");
    let (stream, expected) = stream_vector(&v["streams"][0]);
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &stream, &expected, |f| {
        assert!(
            matches!(
                Packet::from_response_frame(f),
                Ok(Packet {
                    message: Message::Response(_),
                    ..
                })
            ),
            "{:?}",
            F(f)
        );
    });
    // A `PacketDecoder` of the side that reads status packets.
    let want: Vec<(u64, Packet)> = expected
        .iter()
        .map(|(o, f)| (*o, Packet::decode_response(f).expect("decodes")))
        .collect();
    for chunk in 1..=stream.len() {
        let mut decoder = PacketDecoder::<ResponseLayout, DECODER_BUFFER_LEN>::new(ResponseLayout);
        let mut got = Vec::new();
        for part in stream.chunks(chunk) {
            got.extend(decoder.packets(part).filter_map(|e| match e {
                PacketEvent::Packet { offset, packet, .. } => Some((offset, packet)),
                _ => None,
            }));
        }
        while let Some(e) = decoder.flush_packet() {
            if let PacketEvent::Packet { offset, packet, .. } = e {
                got.push((offset, packet));
            }
        }
        assert_eq!(got, want, "chunk size {chunk}");
    }
    // The run-time codec, given the direction.
    let interp = golden::interpreter("dynamixel1");
    let codec = interp.codec();
    let response = codec.direction_index("response");
    let codec = codec.with_direction(response);
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
        assert_eq!(got, expected, "chunk size {chunk}");
    }
}
