//! The `table` output of `protocol decode`: one aligned line per frame or event, for a person
//! watching a link. Enums show their names, scaled fields their physical value, and every
//! value its unit.
//!
//! This module owns the text of a line; which frames and events there are is the decoding
//! session's business.

use protocol_spec::ir::{Field, FieldKind, Protocol, Struct, ValueType};
use serde_json::Value;

use protocol_dynamic::Decoded;

/// Column widths of a spec's table.
#[derive(Debug, Clone, Copy)]
pub struct Widths {
    command: usize,
    direction: usize,
}

impl Widths {
    /// Widths that fit every command and direction name of `p`.
    pub fn of(p: &Protocol) -> Self {
        Widths {
            command: p
                .commands
                .iter()
                .map(|c| c.name.len())
                .max()
                .unwrap_or(0)
                .max(7),
            direction: p.directions.iter().map(|d| d.name.len()).max().unwrap_or(0),
        }
    }
}

/// The JSON form of a decoded value (what `--format json` prints of it). Through the JSON
/// text, not `serde_json::to_value`: an `f32` is printed as its shortest decimal (`12.6`),
/// while `to_value` would widen it to the `f64` of its bits (`12.600000381469727`).
fn json(v: &protocol_dynamic::Value) -> Value {
    serde_json::to_string(v)
        .ok()
        .and_then(|text| serde_json::from_str(&text).ok())
        .unwrap_or(Value::Null)
}

/// A JSON value as a short text: numbers as JSON prints them (shortest round-trip decimals),
/// strings (enum names, hex) bare.
fn scalar_text(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Array(items) => {
            let inner: Vec<String> = items.iter().map(scalar_text).collect();
            format!("[{}]", inner.join(", "))
        }
        Value::Object(map) => {
            let inner: Vec<String> = map
                .iter()
                .map(|(k, v)| format!("{k}={}", scalar_text(v)))
                .collect();
            format!("{{{}}}", inner.join(" "))
        }
        other => other.to_string(),
    }
}

fn with_unit(text: String, unit: &str) -> String {
    if unit.is_empty() {
        text
    } else if unit.contains(' ') {
        format!("{text} ({unit})")
    } else {
        format!("{text} {unit}")
    }
}

/// `name=value unit` for every field of a struct value, nested structs flattened with dots.
fn struct_fields(p: &Protocol, s: &Struct, v: &Value, prefix: &str, out: &mut Vec<String>) {
    for f in &s.fields {
        field_text(p, f, &f.kind, v, prefix, out);
    }
}

fn field_text(
    p: &Protocol,
    f: &Field,
    kind: &FieldKind,
    v: &Value,
    prefix: &str,
    out: &mut Vec<String>,
) {
    match kind {
        FieldKind::Padding | FieldKind::Check(_) => {}
        FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => {
            field_text(p, f, inner, v, prefix, out)
        }
        FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
            for m in members {
                let value = v.get(&m.name).map(scalar_text).unwrap_or_default();
                out.push(format!("{prefix}{}={value}", m.name));
            }
        }
        FieldKind::Value {
            ty: ValueType::Struct(si),
            count: None,
        } if v.get(&f.name).is_some_and(Value::is_object) => {
            let nested = format!("{prefix}{}.", f.name);
            struct_fields(p, &p.structs[*si], &v[&f.name], &nested, out);
        }
        FieldKind::Value { .. }
        | FieldKind::Bytes { .. }
        | FieldKind::Group { .. }
        | FieldKind::Packed { .. }
        | FieldKind::NulText { .. }
        | FieldKind::Array { .. } => {
            if let Some(value) = v.get(&f.name) {
                out.push(format!(
                    "{prefix}{}={}",
                    f.name,
                    with_unit(scalar_text(value), &f.unit)
                ));
            }
        }
    }
}

/// The line of a decoded frame: offset, length, command, direction, header values, then the
/// payload's fields.
pub fn frame_line(p: &Protocol, w: Widths, d: &Decoded, offset: u64, len: usize) -> String {
    // A direction whose frames carry a struct in place of a command (a status packet).
    let carried = d
        .direction
        .and_then(|di| p.directions.get(di))
        .and_then(|x| x.message)
        .map(|(si, _)| si)
        .filter(|_| d.command.is_none());
    let command = match d.command.and_then(|ci| p.commands.get(ci)) {
        Some(c) => c.name.clone(),
        None if d.ack => "(ack)".to_string(),
        None => match carried {
            Some(si) => format!("({})", p.structs[si].name),
            None => format!("({})", p.frames[d.format].name),
        },
    };
    let direction = d
        .direction
        .and_then(|di| p.directions.get(di))
        .map_or("", |x| x.name.as_str());
    let mut parts: Vec<String> = d
        .header
        .iter()
        .map(|(k, v)| format!("{k}={}", header_text(&json(v))))
        .collect();
    if let Some(can_id) = d.can_id {
        parts.insert(0, format!("can_id={can_id:#05x}"));
    }
    let mut fields = Vec::new();
    let payload = json(&d.payload);
    let payload_struct = match d.command {
        Some(ci) => p.commands[ci]
            .payloads
            .get(d.direction.unwrap_or(0))
            .copied()
            .flatten(),
        None => carried.or(p.frames[d.format].message),
    };
    match payload_struct {
        Some(si) => struct_fields(p, &p.structs[si], &payload, "", &mut fields),
        None => {
            if let Value::String(hex) = &payload {
                fields.push(format!("{}={hex}", if d.ack { "data" } else { "payload" }));
            }
        }
    }
    let mut line = format!("{offset:>8} {len:>4} B  {command:<cw$}", cw = w.command);
    if w.direction > 0 {
        line.push_str(&format!("  {direction:<dw$}", dw = w.direction));
    }
    if !parts.is_empty() {
        line.push_str("  ");
        line.push_str(&parts.join(" "));
    }
    if !fields.is_empty() {
        line.push_str("  | ");
        line.push_str(&fields.join("  "));
    }
    // A frame without header values or fields ends at its padded command name.
    line.truncate(line.trim_end().len());
    line
}

fn header_text(v: &Value) -> String {
    match v.as_u64() {
        Some(n) => format!("{n:#04x}"),
        None => scalar_text(v),
    }
}

/// The line of an event: offset, bytes, what happened.
pub fn event_line(offset: u64, bytes: usize, what: &str) -> String {
    format!("{offset:>8} {bytes:>4} B  ! {what}")
}
