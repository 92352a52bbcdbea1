//! serde's JSON of a generated packet (`protocol!(..., derive(serde))`) against the run-time
//! codec's JSON of the same frame, on every golden vector of every bundled spec: the packet's
//! JSON text is the codec's `command`, `header` and `payload`, in that order, character for
//! character. The codec's whole frame object (with `offset`, `id`, `hex`, ...) then
//! deserializes as the generated packet, which encodes to the vector's bytes (to what the
//! generated packet decoded from them encodes to, for the few vectors whose bytes are not the
//! canonical encoding of their values).

mod support;

use protocol::CanFrame;
use protocol_codegen::ir::Transport;
use protocol_dynamic::{Value, hex};
use support::{interpreter, unhex, vectors};

protocol::protocol!("../specs/hflink.toml", derive(serde));
protocol::protocol!("../specs/referee.toml", derive(serde));
protocol::protocol!("../specs/referee2018.toml", derive(serde));
protocol::protocol!("../specs/crsf.toml", derive(serde));
protocol::protocol!("../specs/scout.toml", derive(serde));
protocol::protocol!("../specs/mavlink.toml", derive(serde));
protocol::protocol!("../specs/dynamixel.toml", derive(serde));
protocol::protocol!("../specs/roborts.toml", derive(serde));
protocol::protocol!("../specs/ibus.toml", derive(serde));
protocol::protocol!("../specs/sbus.toml", derive(serde));
protocol::protocol!("../specs/ubx.toml", derive(serde));

/// A generated packet of a serial frame: its JSON, and the bytes that the packet read back
/// from `json` encodes to (and what the packet decoded from the frame encodes to).
type Serial = fn(&[u8], &str) -> (String, Vec<u8>, Vec<u8>);
/// The same for a CAN frame.
type Can = fn(&CanFrame, &str) -> (String, CanFrame, CanFrame);

macro_rules! serial {
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
            serial!(mavlink::Packet, MAX_FRAME_LEN),
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
    ]
}

/// The codec's frame object as JSON text, and the part of it a packet holds (`command`,
/// `header`, `payload`, in the codec's order) as JSON text.
fn codec_json(frame: &Value) -> (String, String) {
    let whole = serde_json::to_string(frame).expect("a value serializes");
    let fields = frame.as_struct().expect("a frame object");
    let part: Value = Value::Struct(
        fields
            .iter()
            .filter(|(k, _)| matches!(*k, "command" | "header" | "payload"))
            .map(|(k, v)| (k, v.clone()))
            .collect(),
    );
    (
        whole,
        serde_json::to_string(&part).expect("a value serializes"),
    )
}

#[test]
fn serde_json_of_generated_packets_is_the_codecs_on_every_golden_vector() {
    let mut total = 0;
    for (spec, file, serial, can) in specs() {
        let interp = interpreter(spec);
        let codec = interp.codec();
        let v = vectors(file);
        let mut compared = 0;
        let mut canonical = 0;
        for frame in v["frames"].as_array().expect("frames") {
            let name = frame["name"].as_str().unwrap_or("?");
            let label = format!("{spec}: {name}");
            if let Some(text) = frame["hex"].as_str().or(frame["uart"]["hex"].as_str()) {
                let bytes = unhex(text);
                let Ok(decoded) = codec.parse(0, &bytes) else {
                    // A vector of a frame the spec rejects (another year's referee command).
                    continue;
                };
                let (whole, part) = codec_json(&codec.frame_value(&decoded, 0, &bytes));
                let (shown, read_bytes, again) = serial(&bytes, &whole);
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
                let decoded = codec.decode_can(fi, &frame).expect("the codec decodes it");
                let virt = codec.frame_value(&decoded, 0, frame.data());
                let (whole, part) = codec_json(&virt);
                let (shown, read, again) = can_fn(&frame, &whole);
                assert_eq!(shown, part, "{label} (CAN): serde's JSON is the codec's");
                assert_eq!(read, again, "{label} (CAN): read back, encoded");
                canonical += usize::from(again == frame);
                compared += 1;
            }
        }
        println!("{spec} on {file}: {compared} frames, {canonical} encoded to their own bytes");
        assert!(compared > 0, "{spec}: no vector compared");
        total += compared;
    }
    println!("{total} frames in all");
}
