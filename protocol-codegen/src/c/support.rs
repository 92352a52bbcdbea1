//! What the C printer supports: [`unsupported`] lists every feature of a spec it refuses, so
//! that `protocol gen c` fails with a clear message instead of printing wrong code.

use crate::ir::{FieldKind, Protocol, Role, Transport, ValueType};
use crate::layout::lower_layout;
use crate::rules::Carries;

use super::names::Fx;
use super::shape::keyed_format;

/// One line per feature of `p` the C printer does not support yet; empty when it prints the
/// whole spec.
pub fn unsupported(p: &Protocol) -> Vec<String> {
    let mut out = Vec::new();
    // The C decoder and encoder have one layout per format.
    for d in p.directions.iter().filter(|d| d.frame.is_some()) {
        out.push(format!(
            "direction `{}`: header fields of one direction only (`direction` on a layout element)",
            d.name
        ));
    }
    for (fi, f) in p.frames.iter().enumerate() {
        let at = format!("frame `{}`", f.name);
        let x = Fx::new(p, fi);
        let rules = &x.rules;
        // A CAN format finds its command from the CAN id, or (the first format, a CAN-only
        // link) from its dispatch key, which may name members of the id (`can_id_bits`).
        if matches!(f.transport, Transport::Can { .. })
            && rules.carries != Carries::CanCommand
            && fi > 0
        {
            out.push(format!(
                "{at}: CAN transport in a format whose frames' command does not follow from the CAN id"
            ));
        }
        let keyed = keyed_format(p, &x);
        // Its command tables would be empty arrays, which C99 has not.
        if keyed && p.commands.is_empty() {
            out.push(format!("{at}: a dispatch key without commands"));
        }
        // Its encoder would have no command to write (and C compilers warn of every
        // parameter it leaves unused).
        if rules.carries == Carries::CanCommand
            && !p.commands.is_empty()
            && p.commands.iter().all(|c| c.can_id.is_none())
        {
            out.push(format!(
                "{at}: a CAN format that carries no command (none has a `can_id`)"
            ));
        }
        let stuffing = rules.stuffing.is_some();
        if stuffing && (!keyed || p.directions.iter().any(|d| d.message.is_some())) {
            out.push(format!(
                "{at}: byte stuffing in a format without dispatch key or with a direction's message"
            ));
        }
        if rules.ack.is_some() && !keyed {
            out.push(format!(
                "{at}: acknowledgement frames in a format without dispatch key"
            ));
        }
        if fi > 0 {
            if stuffing {
                out.push(format!("{at}: byte stuffing in a format after the first"));
            }
            if rules.ack.is_some() {
                out.push(format!(
                    "{at}: acknowledgement frames in a format after the first"
                ));
            }
            if lower_layout(f).length.bare_len().is_some() {
                out.push(format!("{at}: bare headers in a format after the first"));
            }
            if f.values.iter().any(|v| matches!(v.role, Role::Ack(_))) {
                out.push(format!(
                    "{at}: an acknowledgement flag in a format after the first"
                ));
            }
        }
    }
    // A carried packet is read into the packet of a format that carries every command.
    if p.structs.iter().any(|s| !s.carries.is_empty())
        && super::carried::carried_format(p).is_none()
    {
        out.push("a carried packet (`carries`) where no frame format carries every command".into());
    }
    for s in &p.structs {
        for field in &s.fields {
            if let Some(why) = kind_refused(p, &field.kind) {
                out.push(format!("struct `{}` field `{}`: {why}", s.name, field.name));
            }
            // The C struct holds a `bytes` or `str` field's count in a member `<name>_len`.
            let len_member = format!("{}_len", field.name);
            if matches!(field.kind, FieldKind::Bytes { .. })
                && s.fields.iter().any(|o| o.name == len_member)
            {
                out.push(format!(
                    "struct `{}` field `{len_member}`: the name of the C member that counts the \
                     bytes of `{}` (rename the field)",
                    s.name, field.name
                ));
            }
        }
    }
    out
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
        FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => kind_refused(p, inner),
        _ => None,
    }
}
