//! serde's JSON of a generated packet (`protocol!(..., derive(serde))`) against the run-time
//! codec's JSON of the same frame, on every golden vector of every bundled spec (each command
//! format of a link; each direction of a spec whose decoder is given it): the packet's JSON
//! text is the codec's `direction` (given directions only), `command`, `header` and `payload`,
//! in that order, character for character. The codec's whole frame object (with `offset`, `id`, `hex`, ...) then
//! deserializes as the generated packet, which encodes to the vector's bytes (to what the
//! generated packet decoded from them encodes to, for the few vectors whose bytes are not the
//! canonical encoding of their values).

use crate::support;

use protocol_dynamic::{Value, hex, word_field};
use protocol_kit::CanFrame;
use protocol_spec::ir::{DirectionRule, Transport};
use support::{Rng, interpreter, unhex, vectors};

protocol_kit::protocol!("../specs/hflink.toml", derive(serde));
protocol_kit::protocol!("../specs/referee.toml", derive(serde));
protocol_kit::protocol!("../specs/referee2018.toml", derive(serde));
protocol_kit::protocol!("../specs/crsf.toml", derive(serde));
protocol_kit::protocol!("../specs/scout.toml", derive(serde));
protocol_kit::protocol!("../specs/mavlink.toml", derive(serde));
protocol_kit::protocol!("../specs/dynamixel.toml", derive(serde));
protocol_kit::protocol!("../specs/roborts.toml", derive(serde));
protocol_kit::protocol!("../specs/ibus.toml", derive(serde));
protocol_kit::protocol!("../specs/sbus.toml", derive(serde));
protocol_kit::protocol!("../specs/ubx.toml", derive(serde));
protocol_kit::protocol!("../specs/msp.toml", derive(serde));
protocol_kit::protocol!("../specs/dynamixel1.toml", derive(serde));
protocol_kit::protocol!("../specs/vesc.toml", derive(serde));
protocol_kit::protocol!("../specs/feetech.toml", derive(serde));
protocol_kit::protocol!("../specs/lx16a.toml", derive(serde));
protocol_kit::protocol!("../specs/shdlc.toml", derive(serde));
protocol_kit::protocol!("tests/fixtures/features.toml", derive(serde));

/// A generated packet of a serial frame of a format (an index into the spec's frames): its
/// JSON, and the bytes that the packet read back from `json` encodes to (and what the packet
/// decoded from the frame encodes to).
type Serial = fn(usize, &[u8], &str) -> (String, Vec<u8>, Vec<u8>);
/// The same for a CAN frame.
type Can = fn(&CanFrame, &str) -> (String, CanFrame, CanFrame);

macro_rules! serial {
    ($m:ident :: $packet:ident, $max:ident) => {
        |fi: usize, bytes: &[u8], json: &str| {
            assert_eq!(fi, 0, "the first frame format");
            serial_one!($m::$packet, $max)(bytes, json)
        }
    };
}

/// The packets of a link's two command formats; and the link's `AnyPacket` of each, whose
/// JSON is the packet's after the codec's `format`, and which reads back from the codec's
/// whole frame object as the same packet.
macro_rules! serial_link {
    (
        $m:ident :: [$first:ident as $first_v:ident, $other:ident as $other_v:ident],
        [$max:ident, $other_max:ident]
    ) => {
        |fi: usize, bytes: &[u8], json: &str| {
            let (any, out) = match fi {
                0 => (
                    $m::AnyPacket::$first_v($m::$first::decode(bytes).expect("decodes")),
                    serial_one!($m::$first, $max)(bytes, json),
                ),
                _ => (
                    $m::AnyPacket::$other_v($m::$other::decode(bytes).expect("decodes")),
                    serial_one!($m::$other, $other_max)(bytes, json),
                ),
            };
            let shown = serde_json::to_string(&any).expect("a link's packet serializes");
            let whole: serde_json::Value = serde_json::from_str(json).expect("JSON");
            let format = serde_json::to_string(&whole["format"]).expect("a format name");
            assert_eq!(shown, format!("{{\"format\":{format},{}", &out.0[1..]));
            let read: $m::AnyPacket = serde_json::from_str(json)
                .unwrap_or_else(|e| panic!("{json} reads as a link's packet: {e}"));
            let encoded = |p: &$m::AnyPacket| {
                let mut buf = vec![0u8; protocol_kit::EncodePacket::encoded_len(p)];
                let n = protocol_kit::EncodePacket::encode_into(p, &mut buf).expect("encodes");
                buf[..n].to_vec()
            };
            assert_eq!(encoded(&read), encoded(&any), "{json}: read back, encoded");
            out
        }
    };
}

macro_rules! serial_one {
    ($m:ident :: $packet:ident, $max:ident) => {
        |bytes: &[u8], json: &str| {
            let packet = $m::$packet::decode(bytes).expect("generated code decodes the vector");
            let shown = serde_json::to_string(&packet).expect("a packet serializes");
            let read: $m::$packet = serde_json::from_str(json)
                .unwrap_or_else(|e| panic!("{json} reads as a packet: {e}"));
            let mut buf = vec![0u8; $m::$max];
            let n = read.encode(&mut buf).expect("the packet read encodes");
            let mut again = vec![0u8; $m::$max];
            let m = packet
                .encode(&mut again)
                .expect("the packet decoded encodes");
            (shown, buf[..n].to_vec(), again[..m].to_vec())
        }
    };
}

fn scout_can(can: &CanFrame, json: &str) -> (String, CanFrame, CanFrame) {
    let packet = scout::CanPacket::decode(can).expect("generated code decodes the CAN frame");
    let shown = serde_json::to_string(&packet).expect("a packet serializes");
    let read: scout::CanPacket =
        serde_json::from_str(json).unwrap_or_else(|e| panic!("{json} reads as a packet: {e}"));
    let encoded = read.encode().expect("the packet read encodes");
    (
        shown,
        encoded,
        packet.encode().expect("the packet decoded encodes"),
    )
}

/// Each bundled spec, the golden vector file its frames are in, and its generated packets.
fn specs() -> Vec<(&'static str, &'static str, Serial, Option<Can>)> {
    vec![
        (
            "crsf",
            "crsf.json",
            serial!(crsf::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "hflink",
            "hflink.json",
            serial!(hflink::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "referee",
            "robomaster_referee.json",
            serial!(referee::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "referee2018",
            "robomaster_referee.json",
            serial!(referee2018::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "scout",
            "agilex_scout.json",
            serial!(scout::Packet, MAX_FRAME_LEN),
            Some(scout_can),
        ),
        (
            "dynamixel",
            "dynamixel_protocol2.json",
            serial!(dynamixel::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "roborts",
            "roborts_sdk.json",
            serial!(roborts::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "mavlink",
            "mavlink.json",
            serial_link!(
                mavlink::[Packet as V2, V1Packet as V1],
                [MAX_FRAME_LEN, V1_MAX_FRAME_LEN]
            ),
            None,
        ),
        (
            "msp",
            "msp.json",
            serial_link!(
                msp::[Packet as V1, V2Packet as V2],
                [MAX_FRAME_LEN, V2_MAX_FRAME_LEN]
            ),
            None,
        ),
        (
            "ibus",
            "ibus.json",
            serial!(ibus::Packet, MAX_FRAME_LEN),
            None,
        ),
        (
            "sbus",
            "sbus.json",
            serial!(sbus::Packet, MAX_FRAME_LEN),
            None,
        ),
        ("ubx", "ubx.json", serial!(ubx::Packet, MAX_FRAME_LEN), None),
        (
            "ubx",
            "ubx_pyubx2.json",
            serial!(ubx::Packet, MAX_FRAME_LEN),
            None,
        ),
    ]
}

/// The codec's frame object as JSON text, and the part of it a packet holds (`direction` when
/// the decoder is given it, `command`, `header`, `payload`, in the codec's order) as JSON text.
fn codec_json(frame: &Value) -> (String, String) {
    let whole = serde_json::to_string(frame).expect("a value serializes");
    let fields = frame.as_struct().expect("a frame object");
    let part: Value = Value::Struct(
        fields
            .iter()
            .filter(|(k, _)| matches!(*k, "direction" | "command" | "header" | "payload"))
            .map(|(k, v)| (k, v.clone()))
            .collect(),
    );
    (
        whole,
        serde_json::to_string(&part).expect("a value serializes"),
    )
}

/// Every golden vector of `file` through the codec of `spec` (given `direction`, for a spec
/// whose decoder is given it) and through the generated packets: serde's JSON is the codec's,
/// and the codec's JSON reads back as the packet, which encodes alike. The frames compared.
fn compare_file(
    spec: &str,
    file: &str,
    serial: Serial,
    can: Option<Can>,
    direction: Option<&str>,
) -> usize {
    let interp = interpreter(spec);
    // A generated struct's serde JSON holds a carrying field's bytes (its accessor reads the
    // packet): the codec's view of the same struct.
    let codec = interp.codec().with_carried_packets(false);
    let given = direction.and_then(|d| codec.direction_index(d));
    let codec = codec.with_direction(given);
    let link = interp.protocol().link.clone();
    let v = vectors(file);
    let mut compared = 0;
    let mut canonical = 0;
    let can_captures = [&v["can_frames_captured"], &v["streams"][1]["frames"]];
    let captured = can_captures
        .into_iter()
        .flat_map(|list| list.as_array().into_iter().flatten())
        .map(|frame| serde_json::json!({ "name": "captured", "can": frame }));
    let frames: Vec<serde_json::Value> = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .cloned()
        .chain(captured)
        .collect();
    for frame in &frames {
        let name = frame["name"].as_str().unwrap_or("?");
        let label = format!("{spec}: {name}");
        if let Some(text) = frame["hex"].as_str().or(frame["uart"]["hex"].as_str()) {
            let bytes = unhex(text);
            // A link's frame goes through the command format whose framing it has.
            let fi = link
                .iter()
                .copied()
                .find(|&fi| codec.layout(fi).is_some_and(|l| l.parse(&bytes).is_ok()))
                .unwrap_or(0);
            let Ok(decoded) = codec.parse(fi, &bytes) else {
                // A vector of a frame the spec rejects (another year's referee command).
                continue;
            };
            let (whole, part) = codec_json(&codec.frame_value(&decoded, 0, &bytes));
            let (shown, read_bytes, again) = serial(fi, &bytes, &whole);
            assert_eq!(shown, part, "{label}: serde's JSON is the codec's");
            assert_eq!(hex(&read_bytes), hex(&again), "{label}: read back, encoded");
            canonical += usize::from(again == bytes);
            compared += 1;
        }
        if let (Some(id), Some(data)) = (
            frame["can"]["can_id"].as_u64(),
            frame["can"]["data_hex"].as_str(),
        ) {
            let can_fn = can.expect("a CAN packet");
            let frame = CanFrame::new(id as u32, &unhex(data)).expect("a CAN frame");
            let fi = interp
                .protocol()
                .frames
                .iter()
                .position(|f| matches!(f.transport, Transport::Can { .. }))
                .expect("a CAN format");
            let Ok(decoded) = codec.decode_can(fi, &frame) else {
                // A captured frame with a bad check: the differential test checks that
                // generated code refuses it alike.
                continue;
            };
            let virt = codec.frame_value(&decoded, 0, frame.data());
            let (whole, part) = codec_json(&virt);
            let (shown, read, again) = can_fn(&frame, &whole);
            assert_eq!(shown, part, "{label} (CAN): serde's JSON is the codec's");
            assert_eq!(read, again, "{label} (CAN): read back, encoded");
            canonical += usize::from(again == frame);
            compared += 1;
        }
    }
    let given = direction.map_or(String::new(), |d| format!(" ({d})"));
    println!("{spec}{given} on {file}: {compared} frames, {canonical} encoded to their own bytes");
    assert!(compared > 0, "{spec}: no vector compared");
    compared
}

/// A packet of a spec whose decoder is given the direction, decoded by `$decode` (a frame of
/// the other direction is not passed here: the codec decodes it first), encoded into `$len`
/// bytes (`MAX_FRAME_LEN` unless given).
macro_rules! given {
    ($m:ident, $decode:ident) => {
        given!($m, $decode, $m::MAX_FRAME_LEN)
    };
    ($m:ident, $decode:ident, $len:expr) => {
        |_: usize, bytes: &[u8], json: &str| {
            let packet = $m::Packet::$decode(bytes).expect("a packet of the direction");
            let shown = serde_json::to_string(&packet).expect("a packet serializes");
            let read: $m::Packet = serde_json::from_str(json)
                .unwrap_or_else(|e| panic!("{json} reads as a packet: {e}"));
            assert_eq!(read, packet, "{json}: read back");
            let mut buf = vec![0u8; $len];
            let n = read.encode(&mut buf).expect("the packet read encodes");
            let mut again = vec![0u8; $len];
            let m = packet
                .encode(&mut again)
                .expect("the packet decoded encodes");
            (shown, buf[..n].to_vec(), again[..m].to_vec())
        }
    };
}

/// SHDLC's longest frame on the wire: escaping may double every byte between the flags, and
/// its responses (with the state byte) are its longest frames.
const SHDLC_WIRE_LEN: usize = 2 * shdlc::RESPONSE_MAX_FRAME_LEN;
#[test]
fn serde_json_of_generated_packets_is_the_codecs_on_every_golden_vector() {
    let mut total = 0;
    for (spec, file, serial, can) in specs() {
        total += compare_file(spec, file, serial, can, None);
    }
    // Dynamixel 1.0, VESC, Feetech, LX-16A and SHDLC: the decoder is given the direction; each
    // reads the frames of its own (an SHDLC response by its own layout, with the state byte).
    for (spec, file, direction, serial) in [
        (
            "dynamixel1",
            "dynamixel_protocol1.json",
            "request",
            dynamixel1_request as Serial,
        ),
        (
            "dynamixel1",
            "dynamixel_protocol1.json",
            "response",
            dynamixel1_response as Serial,
        ),
        (
            "vesc",
            "vesc_pyvesc.json",
            "request",
            given!(vesc, decode_request),
        ),
        (
            "vesc",
            "vesc_pyvesc.json",
            "response",
            given!(vesc, decode_response),
        ),
        (
            "feetech",
            "feetech_scservo.json",
            "request",
            given!(feetech, decode_request),
        ),
        (
            "feetech",
            "feetech_scservo.json",
            "response",
            given!(feetech, decode_response),
        ),
        (
            "lx16a",
            "lx16a_pylx16a.json",
            "request",
            given!(lx16a, decode_request),
        ),
        (
            "lx16a",
            "lx16a_pylx16a.json",
            "response",
            given!(lx16a, decode_response),
        ),
        (
            "shdlc",
            "shdlc_sensirion.json",
            "request",
            given!(shdlc, decode_request, SHDLC_WIRE_LEN),
        ),
        (
            "shdlc",
            "shdlc_sensirion.json",
            "response",
            given!(shdlc, decode_response, SHDLC_WIRE_LEN),
        ),
    ] {
        total += compare_file(spec, file, serial, None, Some(direction));
    }
    println!("{total} frames in all");
}

/// A Dynamixel 1.0 packet decoded in one direction: its JSON (with `direction`), the bytes the
/// packet read back from `json` encodes to, and what the decoded packet encodes to.
fn dynamixel1_serial(packet: dynamixel1::Packet, json: &str) -> (String, Vec<u8>, Vec<u8>) {
    let shown = serde_json::to_string(&packet).expect("a packet serializes");
    let read: dynamixel1::Packet =
        serde_json::from_str(json).unwrap_or_else(|e| panic!("{json} reads as a packet: {e}"));
    assert_eq!(read, packet, "{json}: read back");
    let mut buf = vec![0u8; dynamixel1::MAX_FRAME_LEN];
    let n = read.encode(&mut buf).expect("the packet read encodes");
    let mut again = vec![0u8; dynamixel1::MAX_FRAME_LEN];
    let m = packet
        .encode(&mut again)
        .expect("the packet decoded encodes");
    (shown, buf[..n].to_vec(), again[..m].to_vec())
}

fn dynamixel1_request(_: usize, bytes: &[u8], json: &str) -> (String, Vec<u8>, Vec<u8>) {
    let packet = dynamixel1::Packet::decode_request(bytes).expect("an instruction packet");
    dynamixel1_serial(packet, json)
}

fn dynamixel1_response(_: usize, bytes: &[u8], json: &str) -> (String, Vec<u8>, Vec<u8>) {
    let packet = dynamixel1::Packet::decode_response(bytes).expect("a status packet");
    dynamixel1_serial(packet, json)
}

/// Random frames of the features fixture (every feature of the spec language that the bundled
/// specs do not use: two-key dispatch, directions, kept unknown enum values, bitfields, 24-bit
/// and 64-bit integers, scaled and packed values, floats of any bits, NaNs included): where
/// both decode a frame, the JSON is the same and the packet read back encodes to the frame.
#[test]
fn serde_json_of_generated_packets_is_the_codecs_on_random_frames() {
    let interp = interpreter("features");
    let codec = interp.codec();
    let p = interp.protocol();
    let f = &p.frames[0];
    assert!(f.ack.is_none() && f.stuffing.is_none() && f.sync_set.is_empty());
    let mut rng = Rng(0x5EED_5E2D_E000_0001);
    let (mut compared, mut non_finite) = (0, 0);
    for c in &p.commands {
        for (slot, payload) in c.payloads.iter().enumerate() {
            let len = payload.map_or(0, |si| p.structs[si].size);
            for _ in 0..200 {
                let mut frame = vec![0u8; f.header_len + len + f.trailer_len];
                rng.fill(&mut frame);
                for (&vi, id) in f.dispatch.iter().zip(&c.id) {
                    word_field(&f.values[vi])
                        .write(&mut frame, *id)
                        .expect("id fits");
                }
                let (vi, value) = match p.directions[slot].rule {
                    DirectionRule::InSet { value, set } => (
                        value,
                        rng.range(p.addresses[set].first, p.addresses[set].last),
                    ),
                    DirectionRule::Equals { value, equals } => (value, equals),
                    DirectionRule::Given => unreachable!("the fixture's directions are told"),
                };
                word_field(&f.values[vi])
                    .write(&mut frame, value)
                    .expect("fits");
                features::LAYOUT.seal(&mut frame).expect("the layout seals");
                let (Ok(packet), Ok(decoded)) =
                    (features::Packet::decode(&frame), codec.parse(0, &frame))
                else {
                    // A value the spec rejects (an unknown `Drive`): the differential test
                    // checks that both refuse it alike.
                    continue;
                };
                let (whole, part) = codec_json(&codec.frame_value(&decoded, 0, &frame));
                let shown = serde_json::to_string(&packet).expect("a packet serializes");
                let label = format!("{} slot {slot}: {}", c.name, hex(&frame));
                assert_eq!(shown, part, "{label}: serde's JSON is the codec's");
                let read: features::Packet = serde_json::from_str(&whole)
                    .unwrap_or_else(|e| panic!("{label}: {whole} reads as a packet: {e}"));
                let mut buf = [0u8; features::MAX_FRAME_LEN];
                let n = read.encode(&mut buf).expect("the packet read encodes");
                // Padding encodes as zeros: the frame as generated code encodes it again.
                let mut again = [0u8; features::MAX_FRAME_LEN];
                let m = packet.encode(&mut again).expect("the packet encodes");
                assert_eq!(
                    hex(&buf[..n]),
                    hex(&again[..m]),
                    "{label}: read back, encoded"
                );
                non_finite += usize::from(shown.contains("NaN") || shown.contains("inf"));
                compared += 1;
            }
        }
    }
    println!("{compared} random frames, {non_finite} with a non-finite float");
    assert!(
        compared > 500 && non_finite > 0,
        "{compared} frames, {non_finite} non-finite"
    );
}

/// A link's packet reads its `format` first (keys before it that are no packet's are skipped),
/// and refuses a packet key before it, a format the link lacks, and a map without one.
#[test]
fn a_links_packet_reads_its_format_before_the_packets_keys() {
    let v = vectors("mavlink.json");
    let frame = v["frames"]
        .as_array()
        .expect("frames")
        .iter()
        .find(|f| f["name"] == "heartbeat_v2")
        .expect("a MAVLink 2 heartbeat");
    let bytes = unhex(frame["hex"].as_str().expect("hex"));
    let packet = mavlink::AnyPacket::V2(mavlink::Packet::decode(&bytes).expect("decodes"));
    let text = serde_json::to_string(&packet).expect("serializes");
    assert!(
        text.starts_with(r#"{"format":"v2","command":"HEARTBEAT","header":"#),
        "{text}"
    );
    let rest = text
        .strip_prefix(r#"{"format":"v2","#)
        .expect("format first");
    let reads = |json: &str| serde_json::from_str::<mavlink::AnyPacket>(json);
    assert_eq!(reads(&text).expect("reads"), packet);
    let skipped = format!(r#"{{"offset":3,"format":"v2",{rest}"#);
    assert_eq!(reads(&skipped).expect("reads"), packet);
    // The MAVLink 1 format reads the same keys as its own packet.
    let v1 = reads(&format!(r#"{{"format":"v1",{rest}"#)).expect("reads as MAVLink 1");
    assert!(matches!(v1, mavlink::AnyPacket::V1(_)), "{v1:?}");
    for bad in [
        format!(r#"{{{rest}"#),
        format!(r#"{{"format":"v3",{rest}"#),
        format!(r#"{{"command":"HEARTBEAT","format":"v2",{rest}"#),
    ] {
        assert!(reads(&bad).is_err(), "{bad} is refused");
    }
}
