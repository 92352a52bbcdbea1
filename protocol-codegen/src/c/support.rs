//! What the C printer supports: [`unsupported`] lists every feature of a spec it refuses, so
//! that `protocol gen c` fails with a clear message instead of printing wrong code.

use crate::ir::{Algorithm, FieldKind, PacketKind, Protocol, Transport, ValueType};

/// One line per feature of `p` the C printer does not support yet; empty when it prints the
/// whole spec.
pub fn unsupported(p: &Protocol) -> Vec<String> {
    let mut out = Vec::new();
    if p.frames.len() != 1 {
        out.push(format!(
            "{} frame formats: the C printer supports exactly one",
            p.frames.len()
        ));
    }
    for f in &p.frames {
        let at = format!("frame `{}`", f.name);
        if let Transport::Can { .. } = f.transport {
            out.push(format!("{at}: CAN transport"));
        }
        if f.packet == PacketKind::Commands {
            out.push(format!(
                "{at}: a second format carrying the commands (several command formats on one link)"
            ));
        }
        if f.dispatch.is_empty() && f.message.is_none() {
            out.push(format!(
                "{at}: a frame format without dispatch key or message"
            ));
        }
        if f.length_extension.is_some() {
            out.push(format!(
                "{at}: a wider length announced by a marker value of the length field"
            ));
        }
        if let Some(t) = &f.flag_trailer {
            out.push(format!(
                "{at}: optional bytes `{}` present when a header flag is set",
                t.name
            ));
        }
        for c in &f.checks {
            if let Some(why) = algorithm_refused(&c.algorithm) {
                out.push(format!("{at}: check `{}`: {why}", c.name));
            }
        }
    }
    if p.directions_given() {
        out.push("directions given to the decoder (no header field tells them)".to_string());
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
        FieldKind::Value {
            ty: ValueType::Enum(ei, scalar),
            ..
        }
        | FieldKind::Array {
            ty: ValueType::Enum(ei, scalar),
            ..
        } => (p.enums[*ei].prim != scalar.prim).then_some("an enum read as another integer type"),
        FieldKind::Optional(inner) => kind_refused(p, inner),
        _ => None,
    }
}
