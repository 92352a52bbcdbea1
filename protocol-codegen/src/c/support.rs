//! What the C printer supports: [`unsupported`] lists every feature of a spec it refuses, so
//! that `protocol gen c` fails with a clear message instead of printing wrong code.

use crate::ir::{Algorithm, FieldKind, PacketKind, Prim, Protocol, Role, Transport, ValueType};

/// One line per feature of `p` the C printer does not support yet; empty when it prints the
/// whole spec.
pub fn unsupported(p: &Protocol) -> Vec<String> {
    let mut out = Vec::new();
    for (fi, f) in p.frames.iter().enumerate() {
        let at = format!("frame `{}`", f.name);
        if matches!(f.transport, Transport::Can { .. }) && f.packet != PacketKind::Can {
            out.push(format!(
                "{at}: CAN transport in a format whose frames' command does not follow from the CAN id"
            ));
        }
        if fi > 0 && f.packet == PacketKind::Commands && !p.directions.is_empty() {
            out.push(format!(
                "{at}: a second format carrying the commands in a spec with directions"
            ));
        }
        if f.stuffing.is_some() {
            out.push(format!("{at}: byte stuffing"));
        }
        if f.ack.is_some() {
            out.push(format!("{at}: acknowledgement frames"));
        }
        if f.bare_len.is_some() {
            out.push(format!("{at}: bare headers"));
        }
        if f.values.iter().any(|v| matches!(v.role, Role::Ack(_))) {
            out.push(format!("{at}: an acknowledgement flag"));
        }
        for c in &f.checks {
            if let Some(why) = algorithm_refused(&c.algorithm) {
                out.push(format!("{at}: check `{}`: {why}", c.name));
            }
        }
    }
    for s in &p.structs {
        for field in &s.fields {
            if let Some(why) = kind_refused(p, &field.kind) {
                out.push(format!("struct `{}` field `{}`: {why}", s.name, field.name));
            }
        }
    }
    out
}

/// Why the C printer refuses a check algorithm, if it does.
fn algorithm_refused(a: &Algorithm) -> Option<&'static str> {
    let fits = match a {
        Algorithm::Crc8(c) => c.params.width == 8,
        Algorithm::Crc16(c) => c.params.width == 16,
        Algorithm::Crc32(c) => c.params.width == 32,
        Algorithm::Crc64(c) => c.params.width == 64,
        _ => true,
    };
    (!fits).then_some("a CRC narrower than its register (width not 8, 16, 32 or 64 bits)")
}

/// Why the C printer refuses a field kind, if it does.
fn kind_refused(p: &Protocol, kind: &FieldKind) -> Option<&'static str> {
    match kind {
        FieldKind::Padding | FieldKind::Group { .. } => None,
        FieldKind::Value { ty, .. } => match ty {
            ValueType::Scalar { scale: Some(_), .. } => Some("scaled values"),
            ValueType::Scalar { .. } | ValueType::Struct(_) | ValueType::Text(_) => None,
            ValueType::Enum(ei, scalar) => {
                (p.enums[*ei].prim != scalar.prim).then_some("an enum read as another integer type")
            }
        },
        FieldKind::Bytes { size_from, .. } => size_from
            .is_some()
            .then_some("bytes sized by another field"),
        FieldKind::Packed { scale, .. } => scale.is_some().then_some("scaled values"),
        FieldKind::Optional(inner) => kind_refused(p, inner),
        FieldKind::NulText { .. } => Some("NUL-terminated text (`cstr`)"),
        FieldKind::Array { .. } => Some("variable-length arrays of primitives"),
        FieldKind::Check(_) => Some("a check inside the payload"),
        FieldKind::Bits { members, .. } => members
            .iter()
            .any(|m| {
                m.enum_index.is_some_and(|ei| {
                    !p.enums[ei].prim.is_unsigned() && p.enums[ei].prim != Prim::Bool
                })
            })
            .then_some("a signed enum in a bit member"),
    }
}
