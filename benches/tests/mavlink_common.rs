//! The imported common dialect (`specs/mavlink-common.toml`) against the `mavlink` crate, every
//! message, on random field values, both ways:
//!
//! - the crate encodes: a message of random values (drawn per field from the spec: integers
//!   over their type's range, finite floats, enum values among the variants, bitmasks over
//!   their field's range, texts of printable ASCII) is built in the crate through its serde
//!   form, written by `mavlink::write_v2_msg`, decoded by the run-time codec, and the decoded
//!   values compared with the crate's;
//! - the run-time codec encodes the same values, `mavlink::MavlinkReader` reads the frame, and
//!   the crate's message is compared with the one it was built from (`PartialEq`) and its
//!   values with those encoded.
//!
//! It also checks that the crate knows exactly the spec's message ids (every 24-bit id probed)
//! and that each `check_extra` is the crate's CRC_EXTRA. The counts per direction print with
//! `cargo test -p protocol-benches --test mavlink_common -- --nocapture`.

use mavlink::dialects::common::MavMessage;
use mavlink::{MavHeader, MavlinkReader, Message};
use protocol_dynamic::{Codec, Interpreter, Value as Dyn};
use protocol_spec::ir::{FieldKind, Prim, Protocol, Struct, ValueType};
use serde_json::{Map, Value, json};

/// Random messages per command and direction.
const ROUNDS: usize = 24;

/// splitmix64: a fixed-seed source, so a failure reproduces.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn interpreter() -> Interpreter {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/mavlink-common.toml");
    Interpreter::load(path).unwrap_or_else(|e| panic!("{e}"))
}

/// The spec's name of a field the crate names `name` (`type` is `mavtype` there; the spec
/// writes MAVLink's camelCase and capitals as snake_case).
fn spec_name(name: &str) -> String {
    if name == "mavtype" {
        return "type".into();
    }
    let mut out = String::new();
    let mut previous_lower = false;
    for c in name.chars() {
        if c.is_ascii_uppercase() && previous_lower {
            out.push('_');
        }
        previous_lower = c.is_ascii_lowercase() || c.is_ascii_digit();
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// A random value of a primitive, as JSON.
fn random_prim(rng: &mut Rng, prim: Prim) -> Value {
    let bits = rng.next();
    match prim {
        Prim::U8 => json!(bits as u8),
        Prim::I8 => json!(bits as i8),
        Prim::U16 => json!(bits as u16),
        Prim::I16 => json!(bits as i16),
        Prim::U32 => json!(bits as u32),
        Prim::I32 => json!(bits as i32),
        Prim::U64 => json!(bits),
        Prim::I64 => json!(bits as i64),
        // Finite values of every magnitude: JSON has no NaN or infinity.
        Prim::F32 => json!(f32::from_bits(bits as u32 & !(1 << 30))),
        Prim::F64 => json!(f64::from_bits(bits & !(1 << 62))),
        other => panic!("MAVLink has no {other:?}"),
    }
}

/// A random value of a field, as the crate's serde form writes it: an enum as `{"type":
/// NAME}`, a bitmask as bitflags text (`0x..`), a text as its string.
fn random_field(rng: &mut Rng, p: &Protocol, kind: &FieldKind, template: &Value) -> Value {
    let FieldKind::Value { ty, count } = kind else {
        panic!("MAVLink fields are values: {kind:?}")
    };
    let one = |rng: &mut Rng, template: &Value| match ty {
        ValueType::Scalar { scalar, .. } if template.is_string() => {
            // A bitmask: any bits of the field's width (the crate keeps unknown bits).
            let raw = random_prim(rng, scalar.prim);
            json!(format!("{:#x}", raw.as_u64().unwrap_or(0)))
        }
        ValueType::Scalar { scalar, .. } => random_prim(rng, scalar.prim),
        ValueType::Enum(e, _) => {
            let variants = &p.enums[*e].variants;
            let v = &variants[rng.below(variants.len() as u64) as usize];
            json!({ "type": v.name })
        }
        ValueType::Text(n) => {
            let len = rng.below(*n as u64 + 1) as usize;
            let text: String = (0..len)
                .map(|_| (b' ' + rng.below(95) as u8) as char)
                .collect();
            json!(text)
        }
        ValueType::Struct(_) => panic!("MAVLink has no nested structs"),
    };
    match (count, template) {
        (Some(n), Value::Array(elems)) => {
            Value::Array((0..*n).map(|i| one(rng, &elems[i])).collect())
        }
        _ => one(rng, template),
    }
}

/// A message of random values in the crate's serde form, from the crate's default message of
/// that id (its field names and shapes) and the spec's struct (its types).
fn random_message(rng: &mut Rng, p: &Protocol, s: &Struct, default: &MavMessage) -> Value {
    let Value::Object(template) = serde_json::to_value(default).expect("serde") else {
        panic!("a message is an object")
    };
    let mut out = Map::new();
    for (name, shape) in template {
        if name == "type" {
            out.insert(name, shape);
            continue;
        }
        let wanted = spec_name(&name);
        let field = s.fields.iter().find(|f| f.name == wanted);
        let field = field.unwrap_or_else(|| panic!("{}: no field {wanted}", s.name));
        out.insert(name, random_field(rng, p, &field.kind, &shape));
    }
    Value::Object(out)
}

/// Bitflags text (`A | B | 0x0c`) as its integer, from the spec's constants.
fn bits(p: &Protocol, text: &str) -> u64 {
    text.split('|')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| match t.strip_prefix("0x") {
            Some(hex) => u64::from_str_radix(hex, 16).expect("hex bits"),
            None => p.constants.iter().find(|c| c.name == t).expect(t).value,
        })
        .fold(0, |a, b| a | b)
}

/// The payload object of the spec's codec for a message in the crate's serde form.
fn spec_payload(p: &Protocol, s: &Struct, crate_json: &Value) -> Value {
    let mut out = Map::new();
    for (name, value) in crate_json.as_object().expect("object") {
        if name == "type" {
            continue;
        }
        let field = s
            .fields
            .iter()
            .find(|f| f.name == spec_name(name))
            .expect(name);
        let text = matches!(
            &field.kind,
            FieldKind::Value {
                ty: ValueType::Text(_),
                ..
            }
        );
        let convert = |v: &Value| match v {
            Value::Object(o) => o["type"].clone(),
            Value::String(t) if !text => json!(bits(p, t)),
            other => other.clone(),
        };
        let value = match value {
            Value::Array(a) => Value::Array(a.iter().map(convert).collect()),
            v => convert(v),
        };
        out.insert(field.name.clone(), value);
    }
    Value::Object(out)
}

/// A `char[N]` as the codec's JSON gives it: a string, or its N bytes when bytes follow the
/// NUL; the crate shows the text before the NUL, so that is what is compared.
fn text_before_nul(v: &Value) -> Value {
    match v {
        Value::Array(bytes) => {
            let b: Vec<u8> = bytes.iter().map(|x| x.as_u64().unwrap() as u8).collect();
            let end = b.iter().position(|&x| x == 0).unwrap_or(b.len());
            json!(String::from_utf8_lossy(&b[..end]))
        }
        other => other.clone(),
    }
}

/// The payload the codec decoded, its texts as the crate shows them.
fn decoded_payload(s: &Struct, payload: &Value) -> Value {
    let mut out = payload.as_object().expect("payload").clone();
    for f in &s.fields {
        if matches!(
            &f.kind,
            FieldKind::Value {
                ty: ValueType::Text(_),
                ..
            }
        ) {
            let v = text_before_nul(&out[&f.name]);
            out.insert(f.name.clone(), v);
        }
    }
    Value::Object(out)
}

fn header() -> MavHeader {
    MavHeader {
        system_id: 7,
        component_id: 42,
        sequence: 200,
    }
}

/// The crate writes `msg`; the codec decodes the frame; the values agree.
fn crate_to_codec(codec: &Codec<'_>, p: &Protocol, s: &Struct, msg: &MavMessage, name: &str) {
    let mut frame = Vec::new();
    mavlink::write_v2_msg(&mut frame, header(), msg).expect("write");
    let decoded = codec
        .parse(0, &frame)
        .unwrap_or_else(|e| panic!("{name}: the codec rejects the crate's {frame:02x?}: {e:?}"));
    let value = serde_json::to_value(codec.frame_value(&decoded, 0, &frame)).expect("json");
    assert_eq!(value["command"], json!(name));
    assert_eq!(value["header"]["sysid"], json!(7));
    assert_eq!(value["header"]["compid"], json!(42));
    assert_eq!(value["header"]["seq"], json!(200));
    let expected = spec_payload(p, s, &serde_json::to_value(msg).expect("serde"));
    assert_eq!(
        decoded_payload(s, &value["payload"]),
        expected,
        "{name}: {frame:02x?}"
    );
}

/// The codec encodes the values of `msg`; the crate reads the frame into `msg` again.
fn codec_to_crate(codec: &Codec<'_>, p: &Protocol, s: &Struct, msg: &MavMessage, name: &str) {
    let payload = spec_payload(p, s, &serde_json::to_value(msg).expect("serde"));
    let object = json!({
        "format": "v2",
        "command": name,
        "header": { "compat_flags": 0, "seq": 200, "sysid": 7, "compid": 42, "signed": false },
        "payload": payload,
    });
    let object: Dyn = serde_json::from_value(object).expect("frame object");
    let frame = codec
        .encode(&object)
        .unwrap_or_else(|e| panic!("{name}: the codec cannot encode {payload}: {e:?}"))
        .bytes;
    let (h, read) = MavlinkReader::new(frame.as_slice())
        .read_any_message::<MavMessage>()
        .unwrap_or_else(|e| panic!("{name}: the crate rejects {frame:02x?}: {e:?}"));
    assert_eq!((h.system_id, h.component_id, h.sequence), (7, 42, 200));
    assert_eq!(&read, msg, "{name}: {frame:02x?}");
    let again = spec_payload(p, s, &serde_json::to_value(&read).expect("serde"));
    assert_eq!(again, payload, "{name}");
}

#[test]
fn every_common_message_agrees_with_the_mavlink_crate_both_ways() {
    let interpreter = interpreter();
    let p = interpreter.protocol();
    let codec = interpreter.codec();
    let mut rng = Rng(0x6d61_766c_696e_6b32);
    let (mut to_codec, mut to_crate) = (0usize, 0usize);
    for c in &p.commands {
        let id = c.id[0] as u32;
        let default = MavMessage::default_message_from_id(id)
            .unwrap_or_else(|| panic!("the crate has no message {} ({id})", c.name));
        assert_eq!(default.message_name(), c.name, "id {id}");
        assert_eq!(
            Some(MavMessage::extra_crc(id)),
            c.check_extra,
            "{}: CRC_EXTRA",
            c.name
        );
        let s = &p.structs[c.payloads[0].expect("payload")];
        for _ in 0..ROUNDS {
            let value = random_message(&mut rng, p, s, &default);
            let msg: MavMessage = serde_json::from_value(value.clone())
                .unwrap_or_else(|e| panic!("{}: the crate refuses {value}: {e}", c.name));
            crate_to_codec(&codec, p, s, &msg, &c.name);
            to_codec += 1;
            codec_to_crate(&codec, p, s, &msg, &c.name);
            to_crate += 1;
        }
    }
    println!(
        "{} messages: {to_codec} frames written by the mavlink crate decoded by the codec, \
         {to_crate} frames written by the codec read by the crate, values equal",
        p.commands.len()
    );
    assert_eq!(to_codec, p.commands.len() * ROUNDS);
}

/// The crate's common dialect has no message the spec lacks.
#[test]
fn the_crate_has_no_message_the_spec_lacks() {
    let interpreter = interpreter();
    let ids: Vec<u64> = interpreter
        .protocol()
        .commands
        .iter()
        .map(|c| c.id[0])
        .collect();
    let extra: Vec<u32> = (0..=0xFF_FFFFu32)
        .filter(|&id| MavMessage::default_message_from_id(id).is_some())
        .filter(|&id| !ids.contains(&u64::from(id)))
        .collect();
    assert!(
        extra.is_empty(),
        "the crate has messages {extra:?} the spec lacks"
    );
}
