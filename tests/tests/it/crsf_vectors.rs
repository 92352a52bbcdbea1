//! CRSF golden vectors (`tests/vectors/crsf.json`, each frame's provenance recorded there) against
//! `specs/crsf.toml`, whose sync is a set of device addresses: every frame decodes to its
//! recorded values and encodes to its exact bytes, by generated code and by the run-time codec
//! (`protocol_dynamic`); the mixed stream yields exactly its expected frames at every chunk size,
//! through the generated decoder, a decoder on the layout value and the run-time codec.
//!
//! The vectors record the wire integers: a field the specification scales is the integer times
//! its scale plus its offset, in the spec's `f32` or `f64` (dividing by the integer whose
//! reciprocal the scale is, as the generated code does). The codec's JSON of each frame is the
//! serde JSON of the expected message (`derive(serde)`), through its text.
//!
//! The NUL-terminated names (FLIGHT_MODE, DEVICE_INFO) are texts; a COMMAND's inner CRC is no
//! field of its struct: decoding verifies it, encoding computes it, and the byte it writes is
//! the value the vector records.

use crate::golden;

use protocol_dynamic::Interpreter;
use protocol_kit::{DecodeError, EncodeError, Reject};
use protocol_tests::{F, assert_stream_at_every_chunk_size, hex, load_vectors, stream_vector};
use serde_json::{Value, json};

protocol_kit::protocol!("../specs/crsf.toml", derive(serde));

use crsf::*;

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn i(v: &Value, k: &str) -> i64 {
    v[k].as_i64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn ints(v: &Value, k: &str) -> Vec<i64> {
    v[k].as_array()
        .unwrap_or_else(|| panic!("field {k} missing"))
        .iter()
        .map(|x| x.as_i64().expect("an integer"))
        .collect()
}

/// A field of scale `1 / div` as an `f32`.
fn f32_per(v: &Value, k: &str, div: f32) -> f32 {
    i(v, k) as f32 / div
}

/// A field on the wire as dBm × -1 (scale -1), in dBm.
fn dbm(v: &Value, k: &str) -> f32 {
    i(v, k) as f32 / -1.0
}

/// A JSON value through its text, as a decoder prints it (an `f32` keeps its shortest form).
fn shown(value: &impl serde::Serialize) -> Value {
    serde_json::from_str(&serde_json::to_string(value).expect("JSON")).expect("JSON")
}

fn bytes<const N: usize>(b: &[u8]) -> protocol_kit::Bytes<N> {
    protocol_kit::Bytes::from_slice(b).expect("fits")
}

fn text<const N: usize>(f: &Value, k: &str) -> protocol_kit::NulStr<N> {
    protocol_kit::NulStr::from_text(f[k].as_str().expect("a text")).expect("fits")
}

/// The message a vector records, built from its JSON fields (not from its bytes).
fn expected_message(ty: u64, f: &Value) -> Message {
    match ty {
        0x02 => Message::Gps(Gps {
            latitude: i(f, "latitude") as f64 / 1e7,
            longitude: i(f, "longitude") as f64 / 1e7,
            groundspeed: f32_per(f, "groundspeed", 10.0),
            heading: f32_per(f, "heading", 100.0),
            altitude: u(f, "altitude") as f32 - 1000.0,
            satellites: u(f, "satellites") as u8,
        }),
        0x07 => Message::Vario(Vario {
            vertical_speed: i(f, "vertical_speed") as i16,
        }),
        0x08 => Message::BatterySensor(BatterySensor {
            voltage: f32_per(f, "voltage", 10.0),
            current: f32_per(f, "current", 10.0),
            capacity_used: u(f, "capacity_used") as u32,
            remaining: u(f, "remaining") as u8,
        }),
        0x09 => Message::BaroAltitude(BaroAltitude {
            altitude: (u(f, "altitude_packed") & 0x7FFF) as u16,
            altitude_in_meters: u(f, "altitude_packed") >> 15 == 1,
            vertical_speed_packed: i(f, "vertical_speed_packed") as i8,
        }),
        0x0A => Message::Airspeed(Airspeed {
            speed: f32_per(f, "speed", 10.0),
        }),
        0x0B => Message::Heartbeat(Heartbeat {
            origin_address: i(f, "origin_address") as i16,
        }),
        0x0C => {
            let values: Vec<i32> = ints(f, "rpm_value").iter().map(|&v| v as i32).collect();
            Message::Rpm(Rpm {
                rpm_source_id: u(f, "rpm_source_id") as u8,
                rpm_value: protocol_kit::Group::from_slice(&values).expect("fits"),
            })
        }
        0x0D => {
            let values: Vec<f32> = ints(f, "temperature")
                .iter()
                .map(|&v| v as f32 / 10.0)
                .collect();
            Message::Temperature(Temperature {
                temp_source_id: u(f, "temp_source_id") as u8,
                temperature: protocol_kit::Group::from_slice(&values).expect("fits"),
            })
        }
        0x14 => Message::LinkStatistics(LinkStatistics {
            up_rssi_ant1: dbm(f, "up_rssi_ant1"),
            up_rssi_ant2: dbm(f, "up_rssi_ant2"),
            up_link_quality: u(f, "up_link_quality") as u8,
            up_snr: i(f, "up_snr") as i8,
            active_antenna: u(f, "active_antenna") as u8,
            rf_profile: u(f, "rf_profile") as u8,
            up_rf_power: u(f, "up_rf_power") as u8,
            down_rssi: dbm(f, "down_rssi"),
            down_link_quality: u(f, "down_link_quality") as u8,
            down_snr: i(f, "down_snr") as i8,
        }),
        0x16 => {
            // The specification's TICKS_TO_US: (x - 992) * 5 / 8 + 1500.
            let channels: Vec<f32> = ints(f, "channels")
                .iter()
                .map(|&c| c as f32 * 0.625 + 880.0)
                .collect();
            Message::RcChannelsPacked(RcChannels {
                channels: channels.try_into().expect("16 channels"),
            })
        }
        0x1C => Message::LinkStatisticsRx(LinkStatisticsRx {
            rssi_db: dbm(f, "rssi_db"),
            rssi_percent: u(f, "rssi_percent") as u8,
            link_quality: u(f, "link_quality") as u8,
            snr: i(f, "snr") as i8,
            rf_power_db: u(f, "rf_power_db") as u8,
        }),
        0x1D => Message::LinkStatisticsTx(LinkStatisticsTx {
            rssi_db: dbm(f, "rssi_db"),
            rssi_percent: u(f, "rssi_percent") as u8,
            link_quality: u(f, "link_quality") as u8,
            snr: i(f, "snr") as i8,
            rf_power_db: u(f, "rf_power_db") as u8,
            fps: u(f, "fps") as f32 * 10.0,
        }),
        0x1E => Message::Attitude(Attitude {
            pitch: f32_per(f, "pitch", 1e4),
            roll: f32_per(f, "roll", 1e4),
            yaw: f32_per(f, "yaw", 1e4),
        }),
        0x21 => Message::FlightMode(FlightMode {
            flight_mode: text(f, "flight_mode"),
        }),
        0x28 => Message::DevicePing(DevicePing {
            destination: u(f, "destination") as u8,
            origin: u(f, "origin") as u8,
        }),
        0x29 => Message::DeviceInfo(DeviceInfo {
            destination: u(f, "destination") as u8,
            origin: u(f, "origin") as u8,
            device_name: text(f, "device_name"),
            serial_number: u(f, "serial_number") as u32,
            hardware_id: u(f, "hardware_id") as u32,
            firmware_id: u(f, "firmware_id") as u32,
            parameters_total: u(f, "parameters_total") as u8,
            parameter_version_number: u(f, "parameter_version_number") as u8,
        }),
        0x2C => Message::ParameterRead(ParameterRead {
            destination: u(f, "destination") as u8,
            origin: u(f, "origin") as u8,
            field_index: u(f, "field_index") as u8,
            field_chunk: u(f, "field_chunk") as u8,
        }),
        0x2D => {
            let value: Vec<u8> = ints(f, "value").iter().map(|&b| b as u8).collect();
            Message::ParameterWrite(ParameterWrite {
                destination: u(f, "destination") as u8,
                origin: u(f, "origin") as u8,
                field_index: u(f, "field_index") as u8,
                value: bytes(&value),
            })
        }
        0x32 => {
            let data: Vec<u8> = ints(f, "payload").iter().map(|&b| b as u8).collect();
            Message::Command(CommandFrame {
                destination: u(f, "destination") as u8,
                origin: u(f, "origin") as u8,
                command: u(f, "command") as u8,
                data: bytes(&data),
            })
        }
        other => panic!("frame type {other:#04x} not covered by this test"),
    }
}

fn interpreter() -> Interpreter {
    golden::interpreter("crsf")
}

#[test]
fn every_frame_decodes_to_its_fields_and_encodes_to_its_bytes() {
    let v = load_vectors("crsf.json");
    let interp = interpreter();
    let codec = interp.codec();
    let frames = v["frames"].as_array().expect("frames");
    for frame in frames {
        let name = frame["name"].as_str().unwrap_or("?");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let ty = u(frame, "type");
        assert_eq!(LAYOUT.parse(&bytes), Ok(&bytes[..]), "{name}: framing");
        let expected = Packet {
            header: Header {
                address: u(frame, "sync") as u8,
            },
            message: expected_message(ty, &frame["fields"]),
        };
        assert_eq!(Packet::decode(&bytes), Ok(expected), "{name}: decode");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = expected
            .encode(&mut buf)
            .unwrap_or_else(|e| panic!("{name}: encode failed: {e}"));
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
        if ty == 0x32 {
            // The inner CRC encoding computed, before the outer one: the recorded value.
            assert_eq!(
                u64::from(buf[n - 2]),
                u(&frame["fields"], "command_crc"),
                "{name}: inner CRC"
            );
        }

        // The run-time codec: the same values, the same bytes.
        let decoded = codec
            .parse(0, &bytes)
            .unwrap_or_else(|e| panic!("{name}: dynamic decode: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let json = shown(&value);
        assert_eq!(
            json["header"],
            json!({ "address": u(frame, "sync") }),
            "{name}"
        );
        assert_eq!(json["id"], json!(ty), "{name}: dynamic type");
        assert_eq!(
            json["payload"],
            shown(&expected)["payload"],
            "{name}: dynamic decode"
        );
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{name}: dynamic encode: {e:?}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: dynamic encode");
    }
    assert_eq!(
        frames.len(),
        23,
        "every frame of the vector file was checked"
    );
}

#[test]
fn every_address_of_the_set_is_a_sync_and_no_other_byte_is() {
    let frame = hex("c8040b00ea36");
    for address in 0..=0xFFu8 {
        let mut copy = frame.clone();
        copy[0] = address;
        let in_set = [0xC8, 0xEA, 0xEE, 0xEC, 0x00].contains(&address);
        let parsed = LAYOUT.parse(&copy);
        if in_set {
            assert_eq!(parsed, Ok(&copy[..]), "{address:#04x}");
            let packet = Packet::decode(&copy).expect("decodes");
            assert_eq!(packet.header.address, address);
            // Encoding writes the address the header holds.
            let mut buf = [0u8; MAX_FRAME_LEN];
            let n = packet.encode(&mut buf).expect("encodes");
            assert_eq!(F(&buf[..n]), F(&copy));
        } else {
            assert_eq!(
                parsed,
                Err(DecodeError::Frame(Reject::BadHeader)),
                "{address:#04x}"
            );
        }
    }
}

#[test]
fn an_address_outside_the_set_is_an_encode_error() {
    let packet = Packet {
        header: Header { address: 0xC9 },
        message: Message::Airspeed(Airspeed { speed: 36.0 }),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    assert_eq!(
        packet.encode(&mut buf),
        Err(EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::NONE
        })
    );
    let codec = interpreter();
    let codec = codec.codec();
    let value: protocol_dynamic::Value = serde_json::from_value(json!({
        "command": "AIRSPEED",
        "header": { "address": 0xC9 },
        "payload": { "speed": 36.0 },
    }))
    .expect("a frame value");
    assert!(
        codec.encode(&value).is_err(),
        "the run-time codec refuses it too"
    );
}

#[test]
fn stream_yields_expected_frames_at_every_chunk_size() {
    let v = load_vectors("crsf.json");
    let (bytes, expected) = stream_vector(&v["streams"][0]);
    // The layout as a value (the engine interpreting it).
    assert_stream_at_every_chunk_size::<MAX_FRAME_LEN>(&LAYOUT, &bytes, &expected, |frame| {
        Packet::from_frame(frame).expect("every expected frame decodes");
    });
    for chunk in 1..=bytes.len() {
        // The generated decoder (the layout a constant).
        let mut dec = decoder();
        let mut got = Vec::new();
        for part in bytes.chunks(chunk) {
            let mut input = part;
            while let Some(frame) = dec.decode(&mut input) {
                got.push((frame.offset, frame.bytes.to_vec()));
            }
        }
        assert_eq!(got, expected, "generated decoder, chunk size {chunk}");
    }
    golden::stream(&interpreter(), &bytes, &expected);
}

/// The recorded COMMAND frame with its inner CRC changed and its outer CRC made right again:
/// the frame is whole, its payload is not.
fn command_with_bad_inner_crc() -> Vec<u8> {
    let v = load_vectors("crsf.json");
    let frame = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .find(|f| f["name"] == "command_bind")
        .expect("the command frame");
    let mut bytes = hex(frame["hex"].as_str().expect("hex"));
    let n = bytes.len();
    bytes[n - 2] ^= 0x01;
    let outer = crc::Crc::<u8>::new(&crc::CRC_8_DVB_S2);
    bytes[n - 1] = outer.checksum(&bytes[2..n - 1]);
    bytes
}

#[test]
fn a_wrong_inner_crc_is_a_payload_error_that_the_event_stream_reports() {
    let bytes = command_with_bad_inner_crc();
    assert_eq!(
        LAYOUT.parse(&bytes),
        Ok(&bytes[..]),
        "the frame itself is valid"
    );
    assert_eq!(
        Packet::decode(&bytes),
        Err(DecodeError::PayloadCheck {
            place: protocol_kit::error::Place::new("COMMAND", "")
        })
    );
    // The stream: the frame is found, and its payload's error is an event, not a lost frame.
    let mut stream = bytes.clone();
    stream.extend_from_slice(&hex("c8040b00ea36"));
    let mut dec = decoder();
    let mut input = &stream[..];
    let mut got = Vec::new();
    while let Some(frame) = dec.decode(&mut input) {
        got.push(Packet::from_frame(frame.bytes).map(|p| p.message));
    }
    assert_eq!(
        got,
        vec![
            Err(DecodeError::PayloadCheck {
                place: protocol_kit::error::Place::new("COMMAND", "")
            }),
            Ok(Message::Heartbeat(Heartbeat {
                origin_address: 0xEA
            }))
        ]
    );
    // The run-time codec: the same error (`protocol decode` shows it as a `bad_payload`
    // event with the frame's bytes).
    let interp = interpreter();
    assert_eq!(
        interp.codec().parse(0, &bytes).err(),
        Some(protocol_dynamic::DecodeIssue::Frame(
            DecodeError::PayloadCheck {
                place: protocol_kit::error::Place::NONE
            }
        ))
    );
}

#[test]
fn a_flight_mode_without_its_nul_or_too_long_is_refused() {
    // "ANGLE" with its NUL replaced: no terminator before the payload ends.
    let mut bytes = hex("c80821414e474c450087");
    bytes[8] = b'!';
    let outer = crc::Crc::<u8>::new(&crc::CRC_8_DVB_S2);
    bytes[9] = outer.checksum(&bytes[2..9]);
    assert_eq!(
        Packet::decode(&bytes),
        Err(DecodeError::Unterminated {
            place: protocol_kit::error::Place::new("FLIGHT_MODE", "FlightMode.flight_mode")
        })
    );
    // A name that does not fit, or holds a NUL, is no value: nothing is cut.
    assert_eq!(protocol_kit::NulStr::<59>::from_text(&"M".repeat(60)), None);
    assert_eq!(protocol_kit::NulStr::<59>::from_text("AN\0GLE"), None);
    let codec = interpreter();
    let codec = codec.codec();
    for name in ["M".repeat(60), "AN\u{0}GLE".to_string()] {
        let value: protocol_dynamic::Value = serde_json::from_value(json!({
            "command": "FLIGHT_MODE",
            "header": { "address": 0xC8 },
            "payload": { "flight_mode": name },
        }))
        .expect("a frame value");
        assert!(codec.encode(&value).is_err(), "{name:?} is refused");
    }
}
