//! The JSON Schema of a command's frame objects, derived from the spec: what an MCAP channel
//! declares for its messages, so that a viewer (Foxglove) knows every field and its type
//! before the first message.
//!
//! The schema follows the shapes of the run-time codec's values as `protocol decode` prints
//! them: integers, numbers for floats and scaled values (a non-finite float is a string),
//! enum variants by name (an integer for a value the enum lets through unnamed), bytes as hex
//! strings, arrays and groups as arrays, bit members as fields of their own. The units of the
//! spec are in each field's `description`.

use protocol_spec::ir::{Field, FieldKind, Prim, Protocol, Role, Transport, ValueType};
use serde_json::{Map, Value, json};

/// The schema of the frame objects of command `command` (an index into the spec's commands),
/// or, when `None`, of the frames without a command of frame format `format`: a format's
/// message struct, else bytes (a bare acknowledgement).
pub fn frame_schema(p: &Protocol, command: Option<usize>, format: usize) -> Value {
    let mut props = Map::new();
    props.insert("offset".into(), json!({"type": "integer", "minimum": 0}));
    props.insert("length".into(), json!({"type": "integer", "minimum": 0}));
    props.insert(
        "format".into(),
        string_enum(p.frames.iter().map(|f| &f.name)),
    );
    if p.directions_given() {
        props.insert(
            "direction".into(),
            string_enum(p.directions.iter().map(|d| &d.name)),
        );
    }
    if let Some(c) = command.and_then(|ci| p.commands.get(ci)) {
        props.insert("command".into(), json!({"const": c.name}));
        props.insert(
            "id".into(),
            json!({"type": ["integer", "array"], "items": {"type": "integer"}}),
        );
    }
    props.insert("ack".into(), json!({"type": "boolean"}));
    if p.frames
        .iter()
        .any(|f| matches!(f.transport, Transport::Can { .. }))
    {
        props.insert("can_id".into(), json!({"type": "integer", "minimum": 0}));
    }
    props.insert("header".into(), header_schema(p));
    let payloads: Vec<Value> = command
        .and_then(|ci| p.commands.get(ci))
        .map(|c| {
            let mut structs: Vec<Option<usize>> = Vec::new();
            for si in &c.payloads {
                if !structs.contains(si) {
                    structs.push(*si);
                }
            }
            structs
                .into_iter()
                .map(|si| si.map_or_else(empty_object, |si| struct_schema(p, si)))
                .collect()
        })
        .unwrap_or_default();
    let payload = match <[Value; 1]>::try_from(payloads) {
        Ok([one]) => one,
        // A frame without a command (a bare acknowledgement, a format without commands)
        // carries its payload as bytes.
        Err(none) if none.is_empty() => match p.frames.get(format).and_then(|f| f.message) {
            Some(si) => struct_schema(p, si),
            None => json!({"type": "string", "description": "the payload's bytes in hex"}),
        },
        Err(many) => json!({ "anyOf": many }),
    };
    props.insert("payload".into(), payload);
    props.insert(
        "hex".into(),
        json!({"type": "string", "description": "the frame's bytes in hex"}),
    );
    let title = command
        .and_then(|ci| p.commands.get(ci))
        .map_or_else(|| p.name.clone(), |c| format!("{}.{}", p.name, c.name));
    json!({
        "$schema": "https://json-schema.org/draft/2020-12/schema",
        "title": title,
        "type": "object",
        "properties": props,
        "required": ["offset", "length", "format", "header", "payload", "hex"],
    })
}

fn empty_object() -> Value {
    json!({"type": "object", "properties": {}})
}

fn string_enum<'a>(names: impl Iterator<Item = &'a String>) -> Value {
    json!({"type": "string", "enum": names.collect::<Vec<_>>()})
}

/// The header values a user sees, of every frame format of the spec (the formats of a link
/// differ in their headers: MAVLink 2 has more than MAVLink 1).
fn header_schema(p: &Protocol) -> Value {
    let mut props = Map::new();
    for f in &p.frames {
        let can = matches!(f.transport, Transport::Can { .. });
        for v in &f.values {
            if !matches!(v.role, Role::User { .. }) || (can && v.name == "can_id") {
                continue;
            }
            let ty = if v.prim == Prim::Bool {
                json!({"type": "boolean"})
            } else {
                json!({"type": "integer"})
            };
            props
                .entry(v.name.clone())
                .or_insert(with_doc(ty, &v.doc, ""));
        }
        if let Some(t) = &f.flag_trailer {
            props
                .entry(t.name.clone())
                .or_insert(json!({"type": ["string", "null"]}));
        }
    }
    json!({"type": "object", "properties": props})
}

/// The schema of struct `si`'s values.
fn struct_schema(p: &Protocol, si: usize) -> Value {
    let s = &p.structs[si];
    let mut props = Map::new();
    let mut required = Vec::new();
    for f in &s.fields {
        field_schema(p, f, &f.kind, true, &mut props, &mut required);
    }
    for c in &s.carries {
        let f = &s.fields[c.field];
        if let Some(schema) = props.get_mut(&f.name) {
            *schema = with_doc(carried_schema(p), &f.doc, &f.unit);
        }
    }
    json!({"type": "object", "properties": props, "required": required})
}

/// A carrying field (`carries`): the packet it carries, its command and payload one level
/// deep, as `protocol decode` shows it; its bytes and the error of reading them when they hold
/// no packet of the spec; or its bytes alone where the codec does not open it (inside a
/// repeated group's elements).
fn carried_schema(p: &Protocol) -> Value {
    let bytes = json!({"type": "string", "contentEncoding": "base16"});
    json!({"anyOf": [
        {
            "type": "object",
            "properties": {
                "command": string_enum(p.commands.iter().map(|c| &c.name)),
                "payload": {"type": ["object", "string", "null"]},
            },
            "required": ["command", "payload"],
        },
        {
            "type": "object",
            "properties": {"bytes": bytes, "error": {"type": "string"}},
            "required": ["bytes", "error"],
        },
        bytes,
    ]})
}

/// The properties a field adds to its struct's object (none, one, or one per bit member).
fn field_schema(
    p: &Protocol,
    f: &Field,
    kind: &FieldKind,
    present: bool,
    props: &mut Map<String, Value>,
    required: &mut Vec<String>,
) {
    let mut add = |name: &str, schema: Value, props: &mut Map<String, Value>| {
        props.insert(name.to_string(), with_doc(schema, &f.doc, &f.unit));
        if present {
            required.push(name.to_string());
        }
    };
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => {
            let mut inner_props = Map::new();
            field_schema(p, f, inner, false, &mut inner_props, &mut Vec::new());
            for (name, schema) in inner_props {
                props.insert(name, json!({"anyOf": [schema, {"type": "null"}]}));
            }
        }
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            for m in members {
                let schema = match m.enum_index {
                    Some(ei) => enum_schema(p, ei),
                    None if m.prim == Prim::Bool => json!({"type": "boolean"}),
                    None if m.scale.is_some() => json!({"type": "number"}),
                    None => json!({"type": "integer"}),
                };
                props.insert(m.name.clone(), with_doc(schema, &m.doc, &m.unit));
                if present {
                    required.push(m.name.clone());
                }
            }
        }
        FieldKind::Value { ty, count: None } => add(&f.name, value_schema(p, ty), props),
        FieldKind::Value { ty, count: Some(n) } => {
            add(&f.name, array(value_schema(p, ty), Some(*n), *n), props)
        }
        FieldKind::Array { ty, max, .. } => {
            add(&f.name, array(value_schema(p, ty), None, *max), props)
        }
        FieldKind::Group { elem, max } => {
            add(&f.name, array(struct_schema(p, *elem), None, *max), props);
        }
        FieldKind::Packed { count, scale, .. } => {
            let item = if scale.is_some() {
                number()
            } else {
                json!({"type": "integer"})
            };
            add(&f.name, array(item, Some(*count), *count), props);
        }
        FieldKind::Bytes {
            max, text: true, ..
        } => add(&f.name, text(*max), props),
        FieldKind::Bytes { .. } => add(
            &f.name,
            json!({"type": "string", "contentEncoding": "base16"}),
            props,
        ),
        FieldKind::NulText { max } => add(&f.name, text(*max + 1), props),
    }
}

/// Text of at most `max` bytes: a string, or its bytes when they are not canonical UTF-8 text
/// (the codec keeps every byte so that encoding gives them back).
fn text(max: usize) -> Value {
    json!({"type": ["string", "array"], "items": {"type": "integer"}, "maxItems": max})
}

/// A float: a number, or the text of a non-finite value.
fn number() -> Value {
    json!({"type": ["number", "string"]})
}

fn array(items: Value, min: Option<usize>, max: usize) -> Value {
    let mut a = json!({"type": "array", "items": items, "maxItems": max});
    if let (Some(n), Value::Object(o)) = (min, &mut a) {
        o.insert("minItems".into(), n.into());
    }
    a
}

fn value_schema(p: &Protocol, ty: &ValueType) -> Value {
    match ty {
        ValueType::Scalar { scalar, scale } => match (scalar.prim, scale) {
            (_, Some(_)) => number(),
            (prim, None) if prim.is_float() => number(),
            (prim, None) if prim.is_bool() => json!({"type": "boolean"}),
            (_, None) => json!({"type": "integer"}),
        },
        ValueType::Struct(si) => struct_schema(p, *si),
        ValueType::Enum(ei, _) => enum_schema(p, *ei),
        // Text as a string, or its bytes when they are not canonical text.
        ValueType::Text(n) => {
            json!({"type": ["string", "array"], "items": {"type": "integer"}, "maxItems": n})
        }
    }
}

/// An enum's variants by name; an integer for a value the enum lets through unnamed.
fn enum_schema(p: &Protocol, ei: usize) -> Value {
    let e = &p.enums[ei];
    let names: Vec<&str> = e.variants.iter().map(|v| v.name.as_str()).collect();
    json!({"anyOf": [{"type": "string", "enum": names}, {"type": "integer"}], "title": e.name})
}

fn with_doc(mut schema: Value, doc: &str, unit: &str) -> Value {
    let text = match (doc.trim(), unit) {
        ("", "") => return schema,
        (d, "") => d.to_string(),
        ("", u) => format!("[{u}]"),
        (d, u) => format!("{d} [{u}]"),
    };
    if let Value::Object(o) = &mut schema {
        o.insert("description".into(), Value::from(text));
    }
    schema
}
