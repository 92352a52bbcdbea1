//! MAVLink golden vectors (`tests/vectors/mavlink.json`, written by pymavlink 2.4.50 and by the
//! `mavlink` crate 0.21) against `specs/mavlink.toml`: every frame decodes to its recorded
//! values and encodes back to the exact bytes (MAVLink 1, base fields only; MAVLink 2 signed or
//! not: CRC_EXTRA, extension fields, trailing-zero truncation, the signature carried), by
//! generated code and by the run-time codec (`protocol_dynamic`); the mixed v1/v2 stream yields
//! its frames at every chunk size through the link's one decoder, in both.

use crate::golden;

use protocol_dynamic::Interpreter;
use protocol_kit::{DecodeError, PacketDecoder, PacketEvent, Reject};
use protocol_tests::{
    F, assert_link_stream_at_every_chunk_size, assert_stream_at_every_chunk_size, hex,
    load_vectors, stream_vector,
};
use serde_json::Value;

protocol_kit::protocol!("../specs/mavlink.toml");

use mavlink::*;

/// A MAVLink 1 frame carries a message's base fields only: its vector records those, and the
/// decoded struct holds zero in the extension fields (the fields the spec marks `extension`).
fn with_extensions_zero(frame: &Value) -> Value {
    let mut frame = frame.clone();
    if frame["mavlink_version"] != 1 {
        return frame;
    }
    let interp = interpreter();
    let p = interp.protocol();
    let name = frame["message"].as_str().expect("message").to_string();
    let command = p.commands.iter().find(|c| c.name == name).expect("command");
    let s = &p.structs[command.payloads[0].expect("payload")];
    let base = s.base_size.unwrap_or(s.size);
    let fields = frame["fields"].as_object_mut().expect("fields");
    for field in s.fields.iter().filter(|f| f.offset >= base) {
        assert!(!fields.contains_key(&field.name), "{name}.{}", field.name);
        let zero = match &field.kind {
            protocol_codegen::ir::FieldKind::Value { count: Some(n), .. } => {
                Value::from(vec![0; *n])
            }
            _ => Value::from(0),
        };
        fields.insert(field.name.clone(), zero);
    }
    frame
}

fn frames() -> Vec<Value> {
    load_vectors("mavlink.json")["frames"]
        .as_array()
        .expect("frames")
        .clone()
}

fn u(v: &Value, k: &str) -> u64 {
    v[k].as_u64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn i(v: &Value, k: &str) -> i64 {
    v[k].as_i64().unwrap_or_else(|| panic!("field {k} missing"))
}

fn f(v: &Value, k: &str) -> f32 {
    v[k].as_f64().unwrap_or_else(|| panic!("field {k} missing")) as f32
}

/// A recorded `char[N]`: the string, NUL-padded to `N` bytes.
fn chars<const N: usize>(v: &Value, k: &str) -> [u8; N] {
    let s = v[k].as_str().unwrap_or_else(|| panic!("field {k} missing"));
    let mut out = [0u8; N];
    out[..s.len()].copy_from_slice(s.as_bytes());
    out
}

fn u16s<const N: usize>(v: &Value, k: &str) -> [u16; N] {
    let list = v[k]
        .as_array()
        .unwrap_or_else(|| panic!("field {k} missing"));
    assert_eq!(list.len(), N, "{k}");
    std::array::from_fn(|j| list[j].as_u64().expect("u16") as u16)
}

/// The message a vector records, built from its field values.
fn expected(frame: &Value) -> Message {
    let frame = &with_extensions_zero(frame);
    let v = &frame["fields"];
    match frame["message"].as_str().expect("message") {
        "HEARTBEAT" => Message::Heartbeat(Heartbeat {
            custom_mode: u(v, "custom_mode") as u32,
            r#type: u(v, "type") as u8,
            autopilot: u(v, "autopilot") as u8,
            base_mode: u(v, "base_mode") as u8,
            system_status: u(v, "system_status") as u8,
            mavlink_version: u(v, "mavlink_version") as u8,
        }),
        "SYS_STATUS" => Message::SysStatus(SysStatus {
            onboard_control_sensors_present: u(v, "onboard_control_sensors_present") as u32,
            onboard_control_sensors_enabled: u(v, "onboard_control_sensors_enabled") as u32,
            onboard_control_sensors_health: u(v, "onboard_control_sensors_health") as u32,
            load: u(v, "load") as u16,
            voltage_battery: u(v, "voltage_battery") as u16,
            current_battery: i(v, "current_battery") as i16,
            drop_rate_comm: u(v, "drop_rate_comm") as u16,
            errors_comm: u(v, "errors_comm") as u16,
            errors_count1: u(v, "errors_count1") as u16,
            errors_count2: u(v, "errors_count2") as u16,
            errors_count3: u(v, "errors_count3") as u16,
            errors_count4: u(v, "errors_count4") as u16,
            battery_remaining: i(v, "battery_remaining") as i8,
            onboard_control_sensors_present_extended: u(
                v,
                "onboard_control_sensors_present_extended",
            ) as u32,
            onboard_control_sensors_enabled_extended: u(
                v,
                "onboard_control_sensors_enabled_extended",
            ) as u32,
            onboard_control_sensors_health_extended: u(v, "onboard_control_sensors_health_extended")
                as u32,
        }),
        "SYSTEM_TIME" => Message::SystemTime(SystemTime {
            time_unix_usec: u(v, "time_unix_usec"),
            time_boot_ms: u(v, "time_boot_ms") as u32,
        }),
        "PARAM_VALUE" => Message::ParamValue(ParamValue {
            param_value: f(v, "param_value"),
            param_count: u(v, "param_count") as u16,
            param_index: u(v, "param_index") as u16,
            param_id: chars::<16>(v, "param_id"),
            param_type: u(v, "param_type") as u8,
        }),
        "GPS_RAW_INT" => Message::GpsRawInt(GpsRawInt {
            time_usec: u(v, "time_usec"),
            lat: i(v, "lat") as i32,
            lon: i(v, "lon") as i32,
            alt: i(v, "alt") as i32,
            eph: u(v, "eph") as u16,
            epv: u(v, "epv") as u16,
            vel: u(v, "vel") as u16,
            cog: u(v, "cog") as u16,
            fix_type: u(v, "fix_type") as u8,
            satellites_visible: u(v, "satellites_visible") as u8,
            alt_ellipsoid: i(v, "alt_ellipsoid") as i32,
            h_acc: u(v, "h_acc") as u32,
            v_acc: u(v, "v_acc") as u32,
            vel_acc: u(v, "vel_acc") as u32,
            hdg_acc: u(v, "hdg_acc") as u32,
            yaw: u(v, "yaw") as u16,
        }),
        "ATTITUDE" => Message::Attitude(Attitude {
            time_boot_ms: u(v, "time_boot_ms") as u32,
            roll: f(v, "roll"),
            pitch: f(v, "pitch"),
            yaw: f(v, "yaw"),
            rollspeed: f(v, "rollspeed"),
            pitchspeed: f(v, "pitchspeed"),
            yawspeed: f(v, "yawspeed"),
        }),
        "GLOBAL_POSITION_INT" => Message::GlobalPositionInt(GlobalPositionInt {
            time_boot_ms: u(v, "time_boot_ms") as u32,
            lat: i(v, "lat") as i32,
            lon: i(v, "lon") as i32,
            alt: i(v, "alt") as i32,
            relative_alt: i(v, "relative_alt") as i32,
            vx: i(v, "vx") as i16,
            vy: i(v, "vy") as i16,
            vz: i(v, "vz") as i16,
            hdg: u(v, "hdg") as u16,
        }),
        "RC_CHANNELS" => {
            let chan = |n: usize| u(v, &format!("chan{n}_raw")) as u16;
            Message::RcChannels(RcChannels {
                time_boot_ms: u(v, "time_boot_ms") as u32,
                chan1_raw: chan(1),
                chan2_raw: chan(2),
                chan3_raw: chan(3),
                chan4_raw: chan(4),
                chan5_raw: chan(5),
                chan6_raw: chan(6),
                chan7_raw: chan(7),
                chan8_raw: chan(8),
                chan9_raw: chan(9),
                chan10_raw: chan(10),
                chan11_raw: chan(11),
                chan12_raw: chan(12),
                chan13_raw: chan(13),
                chan14_raw: chan(14),
                chan15_raw: chan(15),
                chan16_raw: chan(16),
                chan17_raw: chan(17),
                chan18_raw: chan(18),
                chancount: u(v, "chancount") as u8,
                rssi: u(v, "rssi") as u8,
            })
        }
        "COMMAND_LONG" => Message::CommandLong(CommandLong {
            param1: f(v, "param1"),
            param2: f(v, "param2"),
            param3: f(v, "param3"),
            param4: f(v, "param4"),
            param5: f(v, "param5"),
            param6: f(v, "param6"),
            param7: f(v, "param7"),
            command: u(v, "command") as u16,
            target_system: u(v, "target_system") as u8,
            target_component: u(v, "target_component") as u8,
            confirmation: u(v, "confirmation") as u8,
        }),
        "COMMAND_ACK" => Message::CommandAck(CommandAck {
            command: u(v, "command") as u16,
            result: u(v, "result") as u8,
            progress: u(v, "progress") as u8,
            result_param2: i(v, "result_param2") as i32,
            target_system: u(v, "target_system") as u8,
            target_component: u(v, "target_component") as u8,
        }),
        "BATTERY_STATUS" => Message::BatteryStatus(BatteryStatus {
            current_consumed: i(v, "current_consumed") as i32,
            energy_consumed: i(v, "energy_consumed") as i32,
            temperature: i(v, "temperature") as i16,
            voltages: u16s::<10>(v, "voltages"),
            current_battery: i(v, "current_battery") as i16,
            id: u(v, "id") as u8,
            battery_function: u(v, "battery_function") as u8,
            r#type: u(v, "type") as u8,
            battery_remaining: i(v, "battery_remaining") as i8,
            time_remaining: i(v, "time_remaining") as i32,
            charge_state: u(v, "charge_state") as u8,
            voltages_ext: u16s::<4>(v, "voltages_ext"),
            mode: u(v, "mode") as u8,
            fault_bitmask: u(v, "fault_bitmask") as u32,
        }),
        "STATUSTEXT" => Message::Statustext(Statustext {
            severity: u(v, "severity") as u8,
            text: chars::<50>(v, "text"),
            id: u(v, "id") as u16,
            chunk_seq: u(v, "chunk_seq") as u8,
        }),
        other => panic!("vector not covered: {other}"),
    }
}

/// The signature a vector records: link id, 48-bit timestamp (little-endian), then the 6
/// bytes of the signature proper.
fn signature(frame: &Value) -> Option<[u8; 13]> {
    let s = frame.get("signature")?;
    let mut out = [0u8; 13];
    out[0] = u(s, "link_id") as u8;
    out[1..7].copy_from_slice(&u(s, "timestamp").to_le_bytes()[..6]);
    out[7..].copy_from_slice(&hex(s["signature_hex"].as_str().expect("signature_hex")));
    Some(out)
}

fn header(frame: &Value) -> Header {
    Header {
        compat_flags: 0,
        seq: u(frame, "seq") as u8,
        sysid: u(frame, "sysid") as u8,
        compid: u(frame, "compid") as u8,
        signature: signature(frame),
    }
}

fn v1_header(frame: &Value) -> V1Header {
    V1Header {
        seq: u(frame, "seq") as u8,
        sysid: u(frame, "sysid") as u8,
        compid: u(frame, "compid") as u8,
    }
}

/// A vector's frame decoded by the packet of its format, and encoded back.
/// `packet`'s frame encoded through the runtime's `EncodePacket` into a buffer of exactly its
/// `encoded_len` bytes (a truncated payload's zeros need no room in it).
fn exactly<P: protocol_kit::EncodePacket>(packet: &P, name: &str) -> Vec<u8> {
    let mut buf = vec![0u8; packet.encoded_len()];
    let n = packet
        .encode_into(&mut buf)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(n, buf.len(), "{name}: encoded_len");
    buf
}

fn decode_and_encode(frame: &Value, bytes: &[u8]) -> (Message, Vec<u8>) {
    let name = frame["name"].as_str().expect("name");
    let mut buf = [0u8; ANY_DECODER_BUFFER_LEN];
    let (message, n) = if frame["mavlink_version"] == 1 {
        let packet = V1Packet::decode(bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(packet.header, v1_header(frame), "{name}");
        let n = packet.encode(&mut buf).expect("encode");
        assert_eq!(packet.encoded_len(), n, "{name}: encoded_len");
        assert_eq!(exactly(&AnyPacket::V1(packet), name), buf[..n], "{name}");
        // MAVLink 2 does not decode it.
        assert!(Packet::decode(bytes).is_err(), "{name}");
        (packet.message, n)
    } else {
        let packet = Packet::decode(bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(packet.header, header(frame), "{name}");
        let n = packet.encode(&mut buf).expect("encode");
        assert_eq!(packet.encoded_len(), n, "{name}: encoded_len");
        assert_eq!(exactly(&AnyPacket::V2(packet), name), buf[..n], "{name}");
        assert!(V1Packet::decode(bytes).is_err(), "{name}");
        (packet.message, n)
    };
    (message, buf[..n].to_vec())
}

#[test]
fn every_expressed_frame_decodes_and_encodes_to_its_bytes() {
    let (mut v1, mut v2) = (0, 0);
    let mut truncated = 0;
    for frame in frames() {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let (message, encoded) = decode_and_encode(&frame, &bytes);
        assert_eq!(message, expected(&frame), "{name}");
        assert_eq!(F(&encoded), F(&bytes), "{name}: encode");
        // The sent payload length is the recorded one, the decoded struct the full message.
        assert_eq!(bytes[1] as u64, u(&frame, "payload_len"), "{name}");
        if frame["truncated"] == true {
            assert!(u(&frame, "payload_len") < u(&frame, "full_payload_len"));
            truncated += 1;
        }
        if frame["mavlink_version"] == 1 {
            v1 += 1;
        } else {
            v2 += 1;
        }
    }
    assert_eq!(v1, 13, "the MAVLink 1 frames");
    assert_eq!(v2, 16, "the MAVLink 2 frames, 2 of them signed");
    assert_eq!(truncated, 7, "of which truncated");
}

#[test]
fn a_message_with_extension_fields_goes_out_in_mavlink_1_without_them() {
    let v = frames();
    let v2 = v.iter().find(|f| f["name"] == "sys_status_v2").expect("v2");
    let v1 = v.iter().find(|f| f["name"] == "sys_status_v1").expect("v1");
    let message = Packet::decode(&hex(v2["hex"].as_str().expect("hex")))
        .expect("v2")
        .message;
    let Message::SysStatus(full) = message else {
        panic!("{message:?}")
    };
    assert_ne!(full.onboard_control_sensors_present_extended, 0);
    let packet = V1Packet {
        header: v1_header(v1),
        message,
    };
    let mut buf = [0u8; V1_MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encode");
    // The base fields of the v2 message are the v1 vector's: the same bytes.
    assert_eq!(F(&buf[..n]), F(&hex(v1["hex"].as_str().expect("hex"))));
    // Decoded back, the extension fields are zero.
    let back = V1Packet::decode(&buf[..n]).expect("decode").message;
    assert_eq!(
        back,
        Message::SysStatus(SysStatus {
            onboard_control_sensors_present_extended: 0,
            onboard_control_sensors_enabled_extended: 0,
            onboard_control_sensors_health_extended: 0,
            ..full
        })
    );
    // A v1 payload of the full size (with the extension fields) is refused.
    let mut long = buf[..5].to_vec();
    long[1] = 43;
    long.push(1); // msgid SYS_STATUS
    long.extend_from_slice(&[0; 43]);
    long.extend_from_slice(&[0, 0]);
    V1_LAYOUT.seal(&mut long).expect("seal");
    assert_eq!(
        V1Packet::decode(&long),
        Err(DecodeError::PayloadLength {
            expected: 31,
            actual: 43
        })
    );
}

#[test]
fn an_unknown_incompatibility_flag_is_refused() {
    let v = frames();
    let heartbeat = v
        .iter()
        .find(|f| f["name"] == "heartbeat_v2")
        .expect("heartbeat_v2");
    let mut bytes = hex(heartbeat["hex"].as_str().expect("hex"));
    assert!(Packet::decode(&bytes).is_ok());
    for bit in 1..8 {
        bytes[2] = 1 << bit;
        assert_eq!(
            Packet::decode(&bytes).map(|_| ()),
            Err(DecodeError::Frame(Reject::BadHeader)),
            "incompat bit {bit}"
        );
    }
}

#[test]
fn an_all_zero_payload_keeps_its_first_byte() {
    let packet = Packet {
        header: Header {
            compat_flags: 0,
            seq: 0,
            sysid: 1,
            compid: 1,
            signature: None,
        },
        message: Message::CommandAck(CommandAck {
            command: 0,
            result: 0,
            progress: 0,
            result_param2: 0,
            target_system: 0,
            target_component: 0,
        }),
    };
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encode");
    assert_eq!(buf[1], 1, "LEN");
    assert_eq!(n, HEADER_LEN + 1 + TRAILER_LEN);
    assert_eq!(Packet::decode(&buf[..n]), Ok(packet));
    // A payload longer than the message is still refused: COMMAND_ACK with 11 bytes.
    let mut long = hex("fd0b00000001014d0000");
    long.extend_from_slice(&[0x16; 11]);
    long.extend_from_slice(&[0, 0]);
    LAYOUT.seal(&mut long).expect("seal");
    assert_eq!(
        Packet::decode(&long),
        Err(DecodeError::PayloadLength {
            expected: 10,
            actual: 11
        })
    );
}

/// The vector stream and its expected frames: MAVLink 1 and 2, signed or not.
fn expressed_stream() -> (Vec<u8>, Vec<(u64, Vec<u8>)>) {
    let v = load_vectors("mavlink.json");
    let (bytes, expressed) = stream_vector(&v["streams"][0]);
    assert_eq!(
        expressed.len(),
        5,
        "heartbeat_v1, sys_status_v2, command_ack_v2_truncated, statustext_v1 and \
         heartbeat_v2_signed"
    );
    (bytes, expressed)
}

#[test]
fn the_mixed_stream_yields_the_expressed_frames_at_every_chunk_size() {
    let (bytes, expected) = expressed_stream();
    assert_link_stream_at_every_chunk_size::<_, ANY_DECODER_BUFFER_LEN>(
        AnyLayout,
        &bytes,
        &expected,
        |f| {
            let packet = AnyPacket::from_frame(f).expect("decodes");
            let v1 = matches!(packet, AnyPacket::V1(_));
            assert_eq!(v1, f.bytes[0] == 0xFE, "the format it came in");
        },
    );
}

/// The link's `PacketDecoder` (`AnyLayout`, as the integrations drive it) yields each expected
/// frame as the packet of the format whose sync starts it, at every chunk size.
#[test]
fn the_link_packet_decoder_yields_each_frame_in_its_format() {
    let (bytes, expected) = expressed_stream();
    let want: Vec<(u64, AnyPacket)> = expected
        .iter()
        .map(|(offset, f)| {
            let packet = match f[0] {
                0xFE => AnyPacket::V1(V1Packet::decode(f).expect("a MAVLink 1 frame")),
                _ => AnyPacket::V2(Packet::decode(f).expect("a MAVLink 2 frame")),
            };
            (*offset, packet)
        })
        .collect();
    for chunk in 1..=bytes.len() {
        let mut decoder = PacketDecoder::<_, ANY_DECODER_BUFFER_LEN>::new(AnyLayout);
        let mut events = Vec::new();
        for part in bytes.chunks(chunk) {
            events.extend(decoder.packets(part));
        }
        events.extend(std::iter::from_fn(|| decoder.flush_packet()));
        let got: Vec<(u64, AnyPacket)> = events
            .into_iter()
            .filter_map(|e| match e {
                PacketEvent::Packet { offset, packet, .. } => Some((offset, packet)),
                _ => None,
            })
            .collect();
        assert_eq!(got, want, "chunk size {chunk}");
    }
}

fn interpreter() -> Interpreter {
    golden::interpreter("mavlink")
}

/// Whether the run-time codec's value of a field is the recorded one: `char[N]` is recorded as
/// the string up to its first NUL, an `f32` as the `f64` of the same number.
fn same(recorded: &Value, dynamic: &Value) -> bool {
    match (recorded, dynamic) {
        (Value::String(s), Value::Array(bytes)) => {
            let bytes: Vec<u8> = bytes
                .iter()
                .map(|b| b.as_u64().expect("byte") as u8)
                .collect();
            let end = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
            bytes[..end] == *s.as_bytes()
        }
        (Value::Number(r), Value::Number(d)) if r.is_f64() => {
            r.as_f64().map(|x| x as f32) == d.as_f64().map(|x| x as f32)
        }
        _ => recorded == dynamic,
    }
}

#[test]
fn the_run_time_codec_decodes_and_encodes_every_expressed_frame() {
    let interp = interpreter();
    let codec = interp.codec();
    let v1 = codec.format_index("v1").expect("v1");
    let mut n = 0;
    for frame in &frames() {
        let name = frame["name"].as_str().expect("name");
        let bytes = hex(frame["hex"].as_str().expect("hex"));
        let format = if frame["mavlink_version"] == 1 { v1 } else { 0 };
        let decoded = codec
            .parse(format, &bytes)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let value = codec.frame_value(&decoded, 0, &bytes);
        let json = serde_json::to_value(&value).expect("json");
        assert_eq!(json["command"], frame["message"], "{name}");
        let payload = &json["payload"];
        let frame = &with_extensions_zero(frame);
        let fields = frame["fields"].as_object().expect("fields");
        assert_eq!(
            payload.as_object().map(|o| o.len()),
            Some(fields.len()),
            "{name}: {payload}"
        );
        for (k, want) in fields {
            assert!(
                same(want, &payload[k]),
                "{name}.{k}: {want} != {}",
                payload[k]
            );
        }
        let encoded = codec
            .encode(&value)
            .unwrap_or_else(|e| panic!("{name}: {e:?}"));
        assert_eq!(F(&encoded.bytes), F(&bytes), "{name}: dynamic encode");
        n += 1;
    }
    assert_eq!(n, 29, "13 MAVLink 1 and 16 MAVLink 2 frames");
}

#[test]
fn the_run_time_codec_streams_the_expressed_frames_at_every_chunk_size() {
    let (bytes, expected) = expressed_stream();
    golden::stream(&interpreter(), &bytes, &expected);
}

fn signed_frames() -> Vec<(String, Vec<u8>)> {
    let signed: Vec<_> = frames()
        .iter()
        .filter(|f| f["signed"] == true)
        .map(|f| {
            let name = f["name"].as_str().expect("name").to_string();
            (name, hex(f["hex"].as_str().expect("hex")))
        })
        .collect();
    assert_eq!(
        signed.len(),
        2,
        "heartbeat_v2_signed and sys_status_v2_signed"
    );
    signed
}

#[test]
fn a_signature_is_carried_not_verified_and_counted_in_the_frame() {
    for (name, bytes) in signed_frames() {
        let packet = Packet::decode(&bytes).unwrap_or_else(|e| panic!("{name}: {e:?}"));
        let signature = packet.header.signature.expect("signed");
        assert_eq!(signature[..], bytes[bytes.len() - 13..], "{name}");
        // The signature is not verified: other signature bytes decode alike.
        let mut other = bytes.clone();
        *other.last_mut().expect("byte") ^= 0xFF;
        let decoded = Packet::decode(&other).expect("decodes");
        assert_eq!(decoded.message, packet.message, "{name}");
        // The flag is covered by the CRC: cleared, the frame no longer checks.
        let mut cleared = bytes.clone();
        cleared[2] = 0;
        assert_eq!(
            Packet::decode(&cleared).map(|_| ()),
            Err(DecodeError::Frame(Reject::BadChecksum)),
            "{name}"
        );
        // Cut by one byte of its signature, the frame waits for it.
        assert_eq!(
            Packet::decode(&bytes[..bytes.len() - 1]).map(|_| ()),
            Err(DecodeError::Truncated {
                needed: bytes.len(),
                available: bytes.len() - 1
            }),
            "{name}"
        );
        // Encoding without the signature clears the flag and drops the bytes.
        let unsigned = Packet {
            header: Header {
                signature: None,
                ..packet.header
            },
            message: packet.message,
        };
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = unsigned.encode(&mut buf).expect("encode");
        assert_eq!(n, bytes.len() - 13, "{name}");
        assert_eq!(buf[2], 0, "{name}: incompat_flags");
        assert_eq!(Packet::decode(&buf[..n]), Ok(unsigned), "{name}");
    }
}

#[test]
fn signed_frames_stream_at_every_chunk_size() {
    // Garbage that starts a candidate, then the signed frames back to back.
    let mut bytes = vec![0x00, 0xFD];
    let mut expected = Vec::new();
    for (_, frame) in signed_frames() {
        expected.push((bytes.len() as u64, frame.clone()));
        bytes.extend_from_slice(&frame);
    }
    assert_stream_at_every_chunk_size::<DECODER_BUFFER_LEN>(&LAYOUT, &bytes, &expected, |f| {
        let packet = Packet::from_frame(f).expect("decodes");
        assert!(packet.header.signature.is_some());
    });
    golden::stream(&interpreter(), &bytes, &expected);
}
