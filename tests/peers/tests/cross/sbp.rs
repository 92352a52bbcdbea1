//! SBP (`specs/sbp.toml`) against `sbp` 6.5 (libsbp's Rust crate), on random messages of every
//! command of the spec, both ways.
//!
//! A message is drawn as random payload bytes of one command (a random sender, a log text of
//! random length) decoded by the generated code, so every bit pattern of every field occurs.
//! The peer writes it from its values (its JSON form: `msg_type`, `sender` and the fields) and
//! reads the frame written here into its own types; the values cross between the two by name
//! and number only: a status word the spec splits into bit members is put together from them
//! (and split again) by the members' places in the spec, an enum is its spec name, a scaled
//! DOP its wire integer. Each side then decodes the other's frame to the same message, and
//! both write the same bytes.

mod ours {
    protocol_kit::protocol!("../../specs/sbp.toml", derive(serde));
}

use crate::encoded;
use ours::sbp as gen_sbp;
use proptest::prelude::*;
use protocol_peers::harness::{PeerAdapter, assert_every_message_crosses};
use protocol_spec::ir::{FieldKind, Protocol, ValueType};
use sbp::SbpMessage as _;
use serde_json::{Map, Value, json};

const CASES: usize = 2000;

/// The spec's IR: where each status word's members lie, which fields are enums or scaled.
fn ir() -> Protocol {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../specs/sbp.toml");
    let text = std::fs::read_to_string(path).expect("specs/sbp.toml");
    let source = protocol_spec::source::SpecSource::new("specs/sbp.toml", text);
    protocol_spec::compile(&source).expect("a valid spec")
}

/// The spec's name of enum `ei`'s value `raw`, or the number when it has none.
fn enum_value(p: &Protocol, ei: usize, raw: u64) -> Value {
    p.enums[ei]
        .variants
        .iter()
        .find(|v| v.value == raw)
        .map_or(json!(raw), |v| json!(v.name))
}

/// The number of an enum value as the spec's JSON gives it (a name, or a number).
fn enum_raw(p: &Protocol, ei: usize, v: &Value) -> u64 {
    match v {
        Value::String(name) => {
            let variant = p.enums[ei].variants.iter().find(|x| &x.name == name);
            variant.expect("a variant of the enum").value
        }
        other => other.as_u64().expect("a number"),
    }
}

/// The payload struct of the command `name`.
fn payload_struct<'p>(p: &'p Protocol, name: &str) -> &'p protocol_spec::ir::Struct {
    let c = p
        .commands
        .iter()
        .find(|c| c.name == name)
        .expect("a command");
    &p.structs[c.payloads[0].expect("a payload")]
}

/// The peer's fields (raw words, raw integers) in the spec's shape.
fn to_spec(p: &Protocol, command: &str, peer: &Map<String, Value>) -> Map<String, Value> {
    let mut out = Map::new();
    for f in &payload_struct(p, command).fields {
        let v = &peer[&f.name];
        match &f.kind {
            // The members include `<word>_reserved`, the bits above the named ones.
            FieldKind::Bits { members, .. } => {
                let raw = v.as_u64().expect("a word");
                for m in members {
                    let part = (raw >> m.shift) & ((1u64 << m.width) - 1);
                    let value = match m.enum_index {
                        Some(ei) => enum_value(p, ei, part),
                        None if m.width == 1 => json!(part == 1),
                        None => json!(part),
                    };
                    out.insert(m.name.clone(), value);
                }
            }
            FieldKind::Value {
                ty: ValueType::Enum(ei, _),
                ..
            } => {
                out.insert(
                    f.name.clone(),
                    enum_value(p, *ei, v.as_u64().expect("a number")),
                );
            }
            FieldKind::Value {
                ty: ValueType::Scalar { scale: Some(s), .. },
                ..
            } => {
                let raw = v.as_u64().expect("a number") as f64;
                out.insert(f.name.clone(), json!((raw * s.factor) as f32));
            }
            _ => {
                out.insert(f.name.clone(), v.clone());
            }
        }
    }
    out
}

/// The spec's fields as the peer's raw words and integers.
fn to_peer(p: &Protocol, command: &str, spec: &Map<String, Value>) -> Map<String, Value> {
    let mut out = Map::new();
    for f in &payload_struct(p, command).fields {
        let value = match &f.kind {
            FieldKind::Bits { members, .. } => {
                let mut raw = 0u64;
                for m in members {
                    let v = &spec[&m.name];
                    let part = match (m.enum_index, v) {
                        (Some(ei), v) => enum_raw(p, ei, v),
                        (None, Value::Bool(b)) => u64::from(*b),
                        (None, v) => v.as_u64().expect("a number"),
                    };
                    raw |= part << m.shift;
                }
                json!(raw)
            }
            FieldKind::Value {
                ty: ValueType::Enum(ei, _),
                ..
            } => json!(enum_raw(p, *ei, &spec[&f.name])),
            FieldKind::Value {
                ty: ValueType::Scalar { scale: Some(s), .. },
                ..
            } => {
                let physical = spec[&f.name].as_f64().expect("a number");
                json!((physical / s.factor).round() as u64)
            }
            _ => spec[&f.name].clone(),
        };
        out.insert(f.name.clone(), value);
    }
    out
}

/// `libsbp`'s Rust crate against the generated SBP codec.
struct LibSbp {
    ir: Protocol,
}

impl PeerAdapter for LibSbp {
    type Message = gen_sbp::Packet;

    fn peer(&self) -> &'static str {
        "sbp 6.5"
    }

    fn messages(&self) -> BoxedStrategy<gen_sbp::Packet> {
        let commands = gen_sbp::Command::ALL;
        (
            0..commands.len(),
            any::<u16>(),
            prop::collection::vec(any::<u8>(), 255),
            0usize..=254,
        )
            .prop_filter_map("a finite payload", move |(i, sender, bytes, text)| {
                let command = commands[i].0;
                let message = if command == gen_sbp::Command::MsgLog {
                    // The peer's JSON holds text as a string: printable ASCII crosses whole.
                    let level = bytes[0];
                    let text = bytes[1..=text].iter().map(|b| 0x20 + b % 0x5F);
                    let payload: Vec<u8> = std::iter::once(level).chain(text).collect();
                    gen_sbp::Message::read_payload(command, &payload).ok()?
                } else {
                    // The payload's length is the one its struct takes.
                    (0..=bytes.len())
                        .find_map(|n| gen_sbp::Message::read_payload(command, &bytes[..n]).ok())?
                };
                let packet = gen_sbp::Packet {
                    header: gen_sbp::Header { sender },
                    message,
                };
                // The peer's JSON holds no NaN or infinity (written here as the strings
                // "NaN(0x..)", "inf", "-inf"), and NaN equals nothing.
                let text = serde_json::to_string(&packet).ok()?;
                let special = ["\"NaN", "\"inf\"", "\"-inf\""];
                (!special.iter().any(|s| text.contains(s))).then_some(packet)
            })
            .boxed()
    }

    fn peer_write(&mut self, m: &gen_sbp::Packet) -> Result<Option<Vec<u8>>, String> {
        let ours = serde_json::to_value(m).map_err(|e| e.to_string())?;
        let command = ours["command"].as_str().ok_or("a command")?;
        let payload = ours["payload"].as_object().cloned().unwrap_or_default();
        let mut fields = to_peer(&self.ir, command, &payload);
        fields.insert("msg_type".into(), json!(m.message.command().id()));
        fields.insert("sender".into(), json!(m.header.sender));
        let fields = Value::Object(fields);
        let msg: sbp::Sbp =
            serde_json::from_value(fields.clone()).map_err(|e| format!("{e}: {fields}"))?;
        sbp::to_vec(&msg).map(Some).map_err(|e| e.to_string())
    }

    fn peer_read(
        &mut self,
        frame: &[u8],
        _like: &gen_sbp::Packet,
    ) -> Result<Option<gen_sbp::Packet>, String> {
        let msg = sbp::iter_messages(frame)
            .next()
            .ok_or("no message")?
            .map_err(|e| e.to_string())?;
        let sender = msg.sender_id().ok_or("no sender")?;
        let name = msg.message_name().to_owned();
        let Value::Object(fields) = serde_json::to_value(&msg).map_err(|e| e.to_string())? else {
            return Err("not an object".into());
        };
        let object = json!({
            "command": name,
            "header": { "sender": sender },
            "payload": to_spec(&self.ir, &name, &fields),
        });
        serde_json::from_value(object)
            .map(Some)
            .map_err(|e| e.to_string())
    }

    fn ours_write(&self, m: &gen_sbp::Packet) -> Result<Vec<u8>, String> {
        encoded(m)
    }

    fn ours_read(&self, frame: &[u8]) -> Result<gen_sbp::Packet, String> {
        gen_sbp::Packet::decode(frame).map_err(|e| e.to_string())
    }
}

#[test]
fn random_sbp_messages_cross_between_libsbp_and_the_generated_codec() {
    assert_every_message_crosses(&mut LibSbp { ir: ir() }, CASES, "sbp");
}
