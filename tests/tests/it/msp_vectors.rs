//! MSP golden vectors (`tests/vectors/msp.json`: framing and payloads of Betaflight's
//! `msp_serial.c` and `msp.c`, and cu-msp-lib 1.3.0's tests) against `specs/msp.toml`: every
//! frame the spec expresses, v1 (jumbo frames and v2 over v1 included) and v2, decodes to its
//! recorded values and encodes back to the exact bytes, by generated code and by the run-time
//! codec (`protocol_dynamic`); the link's one decoder (`any_decoder`, `Codec::link_stream`)
//! finds the frames of both formats, at every chunk size, in the mixed stream and in the stream
//! of every vector.
//!
//! The frames the spec does not express are listed by [`not_expressed`], with the reason, and
//! checked to be refused rather than misread.
//!
//! The vectors record the wire integers: a field the spec scales ([`SCALED`]) is the integer
//! divided by the integer whose reciprocal its scale is, in the spec's `f32`, as the generated
//! code computes it.

use crate::golden;

use protocol_dynamic::Interpreter;
use protocol_kit::{Bytes, DecodeError, FixedStr, Group, NulStr, Reject, StreamDecoder};
use protocol_tests::{
    F, assert_link_stream_at_every_chunk_size, assert_stream_at_every_chunk_size, hex,
    load_vectors, stream_vector,
};
use serde_json::Value;

protocol_kit::protocol!("../specs/msp.toml");

use msp::*;

fn frames() -> Vec<Value> {
    load_vectors("msp.json")["frames"]
        .as_array()
        .expect("frames")
        .clone()
}

fn named(name: &str) -> Value {
    frames()
        .into_iter()
        .find(|f| f["name"] == name)
        .unwrap_or_else(|| panic!("{name}"))
}

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn i(v: &Value, k: &str) -> i64 {
    v[k].as_i64().unwrap_or_else(|| panic!("field {k} missing"))
}

/// The fields of these vectors that the spec scales, and the integer that divides the wire
/// value (the reciprocal of the scale).
const SCALED: [(&str, f32); 5] = [
    ("roll", 10.0),
    ("pitch", 10.0),
    ("battery_voltage", 10.0),
    ("amperage", 100.0),
    ("battery_voltage_mv", 100.0),
];

/// The physical value of the scaled field `k`.
fn scaled(v: &Value, k: &str) -> f32 {
    let (_, div) = SCALED
        .iter()
        .find(|(name, _)| *name == k)
        .unwrap_or_else(|| panic!("{k} is not scaled"));
    i(v, k) as f32 / div
}

/// A JSON value through its text, as a decoder prints it (an `f32` keeps its shortest form).
fn shown(value: &impl serde::Serialize) -> Value {
    serde_json::from_str(&serde_json::to_string(value).expect("JSON")).expect("JSON")
}

fn payload_bytes(frame: &Value) -> Vec<u8> {
    hex(frame["payload_hex"].as_str().expect("payload_hex"))
}

/// The direction byte a vector records (`<`, `>` or `!`).
fn direction(frame: &Value) -> u8 {
    frame["direction"].as_str().expect("direction").as_bytes()[0]
}

/// Why the spec does not express a frame, or `None` when it does.
fn not_expressed(frame: &Value) -> Option<&'static str> {
    match frame["name"].as_str().expect("name") {
        "cu_msp_lib_serialize" => Some(
            "an MSP_FC_VARIANT request with two arbitrary bytes (cu-msp-lib's framing test): the \
             request carries no payload here, so it is a bad payload length",
        ),
        "error_response" => Some(
            "an error reply ('!') of command 42, which the spec does not list: an unknown \
             command (msp_errors.json holds the error reply of every listed command)",
        ),
        _ => None,
    }
}

fn channels(list: &Value) -> RcChannels {
    let values = list.as_array().expect("channels");
    let mut channels = Group::new();
    for v in values {
        let value = v.as_u64().expect("channel") as u16;
        channels.push(Channel { value }).expect("at most 32");
    }
    RcChannels { channels }
}

/// The message a vector records, built from its field values.
fn expected(frame: &Value) -> Message {
    let v = &frame["fields"];
    let request = direction(frame) == b'<';
    match (u(frame, "cmd"), request) {
        (1, true) => Message::Request(Request::ApiVersion),
        (1, false) => Message::Response(Response::ApiVersion(ApiVersion {
            protocol_version: u(v, "protocol_version") as u8,
            api_version_major: u(v, "api_version_major") as u8,
            api_version_minor: u(v, "api_version_minor") as u8,
        })),
        (2, false) => {
            let id = v["identifier"].as_str().expect("identifier");
            Message::Response(Response::FcVariant(FcVariant {
                identifier: FixedStr::from_text(id).expect("4 letters"),
            }))
        }
        (3, false) => Message::Response(Response::FcVersion(FcVersion {
            major: u(v, "major") as u8,
            minor: u(v, "minor") as u8,
            patch: u(v, "patch") as u8,
        })),
        (101, false) => {
            let extra: Vec<u8> = v["extra_flight_mode_flags"]
                .as_array()
                .expect("extra flags")
                .iter()
                .map(|b| b.as_u64().expect("byte") as u8)
                .collect();
            Message::Response(Response::Status(Status {
                cycle_time: u(v, "cycle_time") as u16,
                i2c_errors: u(v, "i2c_errors") as u16,
                sensors: u(v, "sensors") as u16,
                flight_mode_flags: u(v, "flight_mode_flags") as u32,
                current_pid_profile_index: u(v, "current_pid_profile_index") as u8,
                average_system_load_percent: u(v, "average_system_load_percent") as u16,
                gyro_cycle_time: u(v, "gyro_cycle_time") as u16,
                extra_flight_mode_flags_count: extra.len() as u8,
                extra_flight_mode_flags: Bytes::from_slice(&extra).expect("fits"),
                arming_disable_flags_count: u(v, "arming_disable_flags_count") as u8,
                arming_disable_flags: u(v, "arming_disable_flags") as u32,
                config_state_flags: u(v, "config_state_flags") as u8,
                core_temp_celsius: u(v, "core_temp_celsius") as u16,
                control_rate_profile_count: u(v, "control_rate_profile_count") as u8,
            }))
        }
        (102, false) => Message::Response(Response::RawImu(RawImu {
            acc_x: i(v, "acc_x") as i16,
            acc_y: i(v, "acc_y") as i16,
            acc_z: i(v, "acc_z") as i16,
            gyro_x: i(v, "gyro_x") as i16,
            gyro_y: i(v, "gyro_y") as i16,
            gyro_z: i(v, "gyro_z") as i16,
            mag_x: i(v, "mag_x") as i16,
            mag_y: i(v, "mag_y") as i16,
            mag_z: i(v, "mag_z") as i16,
        })),
        (105, false) => Message::Response(Response::Rc(channels(&v["channels"]))),
        (108, false) => Message::Response(Response::Attitude(attitude(v))),
        (109, false) => Message::Response(Response::Altitude(Altitude {
            altitude: i(v, "altitude") as i32,
            vario: i(v, "vario") as i16,
        })),
        (110, false) => Message::Response(Response::Analog(Analog {
            battery_voltage: scaled(v, "battery_voltage"),
            mah_drawn: u(v, "mah_drawn") as u16,
            rssi: u(v, "rssi") as u16,
            amperage: scaled(v, "amperage"),
            battery_voltage_mv: scaled(v, "battery_voltage_mv"),
        })),
        (116, false) => {
            let names = payload_bytes(frame);
            assert_eq!(names.len() as u64, u(v, "size"));
            Message::Response(Response::Boxnames(BoxNames {
                names: Bytes::from_slice(&names).expect("fits"),
            }))
        }
        (200, true) => Message::Request(Request::SetRawRc(channels(&v["channels"]))),
        (4099, true) => {
            let name = v["name"].as_str().expect("name");
            Message::Request(Request::CommonSetting(SettingName {
                name: NulStr::from_text(name).expect("at most 64 bytes"),
            }))
        }
        (other, request) => panic!("vector not covered: command {other}, request {request}"),
    }
}

fn attitude(v: &Value) -> Attitude {
    Attitude {
        roll: scaled(v, "roll"),
        pitch: scaled(v, "pitch"),
        yaw: i(v, "yaw") as i16,
    }
}

fn v1_frames() -> impl Iterator<Item = Value> {
    frames().into_iter().filter(|f| f["version"] == "v1")
}

#[test]
fn every_expressed_v1_frame_decodes_and_encodes_to_its_bytes() {
    let mut expressed = 0;
    for frame in v1_frames().filter(|f| not_expressed(f).is_none()) {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let header = Header {
            direction: direction(&frame),
        };
        assert_eq!(packet.header, header, "{name}");
        assert_eq!(packet.message, expected(&frame), "{name}");
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encode");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
        assert_eq!(packet.encoded_len(), n, "{name}: encoded_len");
        expressed += 1;
    }
    assert_eq!(expressed, 12, "the v1 frames, the jumbo frame among them");
}

#[test]
fn a_v2_frame_inside_a_v1_frame_carries_its_fields() {
    let frame = named("v2_over_v1_attitude_response");
    let bytes = hex(frame["hex"].as_str().expect("hex"));
    let packet = Packet::decode(&bytes).expect("decodes");
    let Message::Response(Response::V2Frame(inner)) = packet.message else {
        panic!("{:?}", packet.message);
    };
    assert_eq!(u64::from(inner.command), u(&frame, "cmd"));
    assert_eq!(inner.payload.as_slice(), &payload_bytes(&frame)[..]);
    // The carried command, read in the direction of the frame around it.
    let read = inner.payload_response().expect("a carried response");
    assert_eq!(read, Response::Attitude(attitude(&frame["fields"])));
    // The inner frame's CRC-8/DVB-S2 is checked: one bit off in it fails the payload.
    let mut bad = bytes.clone();
    let n = bad.len();
    bad[n - 2] ^= 0x01;
    bad[n - 1] ^= 0x01;
    assert!(matches!(
        Packet::decode(&bad),
        Err(DecodeError::PayloadCheck { .. })
    ));
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encode");
    assert_eq!(F(&buf[..n]), F(&bytes));
}

fn v2_frames() -> impl Iterator<Item = Value> {
    frames().into_iter().filter(|f| f["version"] == "v2")
}

#[test]
fn the_frames_not_expressed_are_refused_not_misread() {
    let mut listed = Vec::new();
    for frame in frames() {
        let Some(why) = not_expressed(&frame) else {
            continue;
        };
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        // The framing holds: the frame is found whole, its payload is refused.
        let refused = if frame["version"] == "v2" {
            assert_eq!(V2_LAYOUT.parse(&bytes), Ok(&bytes[..]), "{name}");
            V2Packet::decode(&bytes).map(|_| ())
        } else {
            assert_eq!(LAYOUT.parse(&bytes), Ok(&bytes[..]), "{name}");
            Packet::decode(&bytes).map(|_| ())
        };
        assert!(
            matches!(
                refused,
                Err(DecodeError::PayloadLength { .. }
                    | DecodeError::UnknownCommand { .. }
                    | DecodeError::UnknownDirection)
            ),
            "{name}: {refused:?}"
        );
        listed.push(format!("{name}: {why}"));
    }
    assert_eq!(listed.len(), 2, "{listed:#?}");
}

/// The v2 vectors' frames: the commands and directions of v1, in v2's header.
#[test]
fn every_expressed_v2_frame_decodes_and_encodes_to_its_bytes() {
    let mut seen = 0;
    for frame in v2_frames().filter(|f| not_expressed(f).is_none()) {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let packet = V2Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let header = V2Header {
            direction: direction(&frame),
            flag: 0,
        };
        assert_eq!(packet.header, header, "{name}");
        assert_eq!(packet.message, expected(&frame), "{name}");
        let mut buf = [0u8; V2_MAX_FRAME_LEN];
        let n = packet.encode(&mut buf).expect("encode");
        assert_eq!(F(&buf[..n]), F(&bytes), "{name}: encode");
        assert_eq!(packet.encoded_len(), n, "{name}: encoded_len");
        seen += 1;
    }
    assert_eq!(
        seen, 3,
        "v2_api_version_request, v2_common_setting_request, v2_attitude_response"
    );
}

/// A v2-only command (id above 255) is carried by v2 frames alone: encoding it in a v1 frame
/// is refused, by generated code and by the run-time codec.
#[test]
fn a_v2_only_command_is_not_encoded_in_a_v1_frame() {
    let message = Message::Request(Request::CommonSetting(SettingName {
        name: NulStr::from_text("gyro_lpf1_static_hz").expect("fits"),
    }));
    let v1 = Packet {
        header: Header { direction: b'<' },
        message,
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    assert_eq!(
        v1.encode(&mut buf),
        Err(protocol_kit::EncodeError::ValueOutOfRange {
            place: protocol_kit::error::Place::NONE
        })
    );
    let v2 = V2Packet {
        header: V2Header {
            direction: b'<',
            flag: 0,
        },
        message,
    };
    let n = v2.encode(&mut buf).expect("a v2 frame");
    let recorded = named("v2_common_setting_request");
    assert_eq!(
        F(&buf[..n]),
        F(&hex(recorded["hex"].as_str().expect("hex")))
    );
    assert_eq!(Command::CommonSetting.id(), 0x1003);
    let interp = interpreter();
    let codec = interp.codec();
    let object: protocol_dynamic::Value = serde_json::from_value(serde_json::json!({
        "format": "v1",
        "command": "COMMON_SETTING",
        "header": { "direction": 60 },
        "payload": { "name": "gyro_lpf1_static_hz" },
    }))
    .expect("a frame object");
    let refused = codec.encode(&object);
    let why = refused.expect_err("refused in v1").to_string();
    assert!(why.contains("not carried by frame `v1`"), "{why}");
}

#[test]
fn a_message_of_the_other_direction_than_its_header_is_not_encoded() {
    for direction in [b'>', b'!'] {
        let packet = V2Packet {
            header: V2Header { direction, flag: 0 },
            message: Message::Request(Request::ApiVersion),
        };
        let mut buf = [0u8; V2_MAX_FRAME_LEN];
        assert_eq!(
            packet.encode(&mut buf),
            Err(protocol_kit::EncodeError::ValueOutOfRange {
                place: protocol_kit::error::Place::NONE
            }),
            "{direction}"
        );
    }
    // An error reply ('!') in v2 is the command alone, as in v1.
    let mut frame = hex("24583c000100000045");
    frame[2] = b'!';
    V2_LAYOUT.seal(&mut frame).expect("seal");
    let packet = V2Packet::decode(&frame).expect("an error reply");
    assert_eq!(packet.message, Message::Error(Command::ApiVersion));
}

fn box_names(len: usize) -> Packet {
    let names: Vec<u8> = (0..len).map(|k| b'A' + (k % 26) as u8).collect();
    Packet {
        header: Header { direction: b'>' },
        message: Message::Response(Response::Boxnames(BoxNames {
            names: Bytes::from_slice(&names).expect("fits"),
        })),
    }
}

#[test]
fn encoding_uses_the_jumbo_form_exactly_when_the_payload_needs_it() {
    let mut buf = [0u8; MAX_FRAME_LEN];
    for len in [0, 1, 200, 254, 255, 256, 300, MAX_PAYLOAD_LEN] {
        let packet = box_names(len);
        let n = packet.encode(&mut buf).expect("encode");
        let frame = &buf[..n];
        if len < 255 {
            // As Betaflight's mspSerialEncode: the size byte, no jumbo size.
            assert_eq!(n, 6 + len, "{len}");
            assert_eq!(frame[3] as usize, len, "{len}");
        } else {
            assert_eq!(n, 8 + len, "{len}");
            assert_eq!(frame[3], 255, "{len}");
            assert_eq!(
                u16::from_le_bytes([frame[5], frame[6]]) as usize,
                len,
                "{len}"
            );
        }
        assert_eq!(packet.encoded_len(), n, "{len}");
        assert_eq!(Packet::decode(frame), Ok(packet), "{len}");
    }
}

#[test]
fn an_impossible_jumbo_length_is_rejected_as_soon_as_its_bytes_are_in() {
    use protocol_kit::decoder::Probe;
    let jumbo = hex(named("v1_jumbo_boxnames_response")["hex"]
        .as_str()
        .expect("hex"));
    // The size byte says jumbo: the jumbo size is awaited, not the frame.
    assert_eq!(LAYOUT.probe(&jumbo[..5]), Probe::Need(7));
    assert_eq!(LAYOUT.probe(&jumbo[..7]), Probe::Need(jumbo.len()));
    // A jumbo size beyond the largest payload, or one that fits the size byte, is refused
    // with the jumbo size's bytes, before any payload byte arrives.
    for wide in [(MAX_PAYLOAD_LEN + 1) as u16, 0xFFFF, 0, 254] {
        let mut bad = jumbo[..7].to_vec();
        bad[5..7].copy_from_slice(&wide.to_le_bytes());
        assert_eq!(
            LAYOUT.probe(&bad),
            Probe::Reject(Reject::BadLength),
            "{wide}"
        );
    }
    // A decoder whose buffer holds no jumbo frame refuses the size byte 255 at once.
    let mut small = StreamDecoder::<_, 200>::new(Layout);
    let mut input = &jumbo[..5];
    let event = small.next_event(&mut input);
    assert!(
        matches!(
            event,
            Some(protocol_kit::Event::Rejected {
                reason: Reject::BadLength,
                ..
            })
        ),
        "{event:?}"
    );
}

#[test]
fn a_jumbo_frame_cut_short_does_not_hold_back_the_frame_after_it() {
    // A jumbo reply cut after 20 bytes claims 308; the analog reply after it is yielded as soon
    // as it is complete, and the cut frame rejected as truncated, without waiting for 308 bytes.
    let jumbo = hex(named("v1_jumbo_boxnames_response")["hex"]
        .as_str()
        .expect("hex"));
    let analog = hex(named("analog_response")["hex"].as_str().expect("hex"));
    let mut bytes = jumbo[..20].to_vec();
    bytes.extend_from_slice(&analog);
    let mut decoder = decoder();
    let mut got = Vec::new();
    decoder.feed(&bytes, |frame| {
        got.push((frame.offset, frame.bytes.to_vec()))
    });
    assert_eq!(got, [(20, analog)]);
    assert_eq!(decoder.stats().truncated, 1);
    assert_eq!(decoder.pending(), 0);
}

/// The vector stream's expected frames of one format: v1 (`$M`) or v2 (`$X`).
fn stream_of(sync: u8) -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let v = load_vectors("msp.json");
    let (bytes, all) = stream_vector(&v["streams"][0]);
    let of: Vec<_> = all.into_iter().filter(|(_, f)| f[1] == sync).collect();
    (bytes, of)
}

#[test]
fn the_mixed_stream_yields_its_frames_at_every_chunk_size() {
    let (bytes, v1) = stream_of(b'M');
    assert_eq!(
        v1.len(),
        4,
        "api_version_request, analog, jumbo boxnames, v2 over v1"
    );
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &v1, |f| {
        Packet::from_frame(f).expect("decodes");
    });
    let (bytes, v2) = stream_of(b'X');
    assert_eq!(v2.len(), 1, "v2_attitude_response");
    assert_stream_at_every_chunk_size::<V2_DECODER_BUFFER_LEN>(&V2_LAYOUT, &bytes, &v2, |f| {
        V2Packet::from_frame(f).expect("decodes");
    });
}

/// The link's one decoder on the mixed stream: the frames of both formats, in order, each
/// decoded by the format it came in.
#[test]
fn the_link_decoder_yields_both_formats_of_the_mixed_stream_at_every_chunk_size() {
    let v = load_vectors("msp.json");
    let (bytes, all) = stream_vector(&v["streams"][0]);
    assert_eq!(all.len(), 5);
    assert_link_stream_at_every_chunk_size::<_, ANY_DECODER_BUFFER_LEN>(
        AnyLayout,
        &bytes,
        &all,
        |f| {
            let packet = AnyPacket::from_frame(f).expect("decodes");
            let v2 = matches!(packet, AnyPacket::V2(_));
            assert_eq!(v2, f.bytes[1] == b'X', "{:?}", f.bytes);
        },
    );
}

/// Every vector frame, one after the other, through the link's one decoder at every chunk
/// size: each is found whole; the expressed ones decode to their recorded message in their
/// format, the others are refused as they are one by one.
#[test]
fn the_link_decoder_decodes_every_vector_frame_at_every_chunk_size() {
    let all = frames();
    let mut bytes = Vec::new();
    let mut found = Vec::new();
    for frame in &all {
        let b = hex(frame["hex"].as_str().expect("hex"));
        found.push((bytes.len() as u64, b.clone()));
        bytes.extend_from_slice(&b);
    }
    let mut decoded = 0;
    assert_link_stream_at_every_chunk_size::<_, ANY_DECODER_BUFFER_LEN>(
        AnyLayout,
        &bytes,
        &found,
        |f| {
            let frame = all
                .iter()
                .find(|v| hex(v["hex"].as_str().expect("hex")) == f.bytes)
                .expect("a vector frame");
            let got = AnyPacket::from_frame(f);
            match (not_expressed(frame), got) {
                (None, Ok(packet)) => {
                    let v2 = frame["version"] == "v2";
                    assert_eq!(matches!(packet, AnyPacket::V2(_)), v2, "{}", frame["name"]);
                    if frame["version"] != "v2-over-v1" {
                        assert_eq!(packet.message(), &expected(frame), "{}", frame["name"]);
                    }
                    let mut buf = [0u8; MAX_FRAME_LEN];
                    let n = packet.encode(&mut buf).expect("encode");
                    assert_eq!(F(&buf[..n]), F(f.bytes), "{}", frame["name"]);
                    decoded += 1;
                }
                (Some(_), Err(_)) => {}
                (why, got) => panic!("{}: {why:?} but {got:?}", frame["name"]),
            }
        },
    );
    let runs = bytes.len();
    assert_eq!(
        decoded,
        16 * runs,
        "16 frames expressed, at each of {runs} chunk sizes"
    );
}

fn interpreter() -> Interpreter {
    golden::interpreter("msp")
}

/// Whether the run-time codec's value of a payload field is the recorded one: bytes are a hex
/// string there, a group of channels a list of `{ "value": n }`.
fn same(recorded: &Value, dynamic: &Value) -> bool {
    match (recorded, dynamic) {
        (Value::Array(want), Value::String(hex_text)) => {
            let want: Vec<u8> = want
                .iter()
                .map(|b| b.as_u64().expect("byte") as u8)
                .collect();
            hex(hex_text) == want
        }
        (Value::Array(want), Value::Array(got)) => {
            want.len() == got.len()
                && want
                    .iter()
                    .zip(got)
                    .all(|(w, g)| g.get("value").unwrap_or(g) == w)
        }
        _ => recorded == dynamic,
    }
}

#[test]
fn the_run_time_codec_decodes_and_encodes_every_expressed_frame() {
    let interp = interpreter();
    let codec = interp.codec();
    let mut seen = 0;
    for frame in frames().into_iter().filter(|f| not_expressed(f).is_none()) {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let format = usize::from(frame["version"] == "v2");
        let decoded = codec
            .parse(format, &bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let json = shown(&value);
        assert_eq!(
            json["format"],
            if format == 1 { "v2" } else { "v1" },
            "{name}"
        );
        assert_eq!(
            json["header"]["direction"],
            u64::from(direction(&frame)),
            "{name}"
        );
        let payload = &json["payload"];
        let fields = frame["fields"].as_object().expect("fields");
        let payload = if frame["version"] == "v2-over-v1" {
            // The inner frame's command, and the packet it carries: the command's payload,
            // whose fields the vector records (its bytes are the frame's, encoded below).
            assert_eq!(payload["command"], frame["cmd"], "{name}");
            assert_eq!(payload["payload"]["command"], "ATTITUDE", "{name}");
            &payload["payload"]["payload"]
        } else {
            payload
        };
        for (k, want) in fields {
            let want = &if SCALED.iter().any(|(name, _)| name == k) {
                shown(&scaled(&frame["fields"], k))
            } else {
                want.clone()
            };
            let got = match (k.as_str(), payload.get(k)) {
                // The jumbo vector records the size of the names.
                ("size", None) => Value::from(hex(payload["names"].as_str().expect("names")).len()),
                (_, got) => got
                    .cloned()
                    .unwrap_or_else(|| panic!("{name}.{k}: {payload}")),
            };
            assert!(same(want, &got), "{name}.{k}: {want} != {got}");
        }
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: dynamic encode");
        seen += 1;
    }
    assert_eq!(seen, 16);
}

#[test]
fn the_run_time_codec_refuses_the_frames_not_expressed() {
    let interp = interpreter();
    let codec = interp.codec();
    for frame in frames().into_iter().filter(|f| not_expressed(f).is_some()) {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let format = usize::from(frame["version"] == "v2");
        assert!(codec.parse(format, &bytes).is_err(), "{name}");
    }
}

#[test]
fn the_run_time_codec_streams_both_formats_at_every_chunk_size() {
    let v = load_vectors("msp.json");
    let (bytes, all) = stream_vector(&v["streams"][0]);
    golden::stream(&interpreter(), &bytes, &all);
}
