//! The twin's refusals where the spec has an empty direction (MSP's error replies, `!`): a
//! request the twin does not know or cannot answer gets the frame of that direction that
//! carries its command; and the header field that tells a direction by one value, set to the
//! direction of what the twin writes.

use protocol_dynamic::{Decoded, Fields, Value};
use protocol_spec::ir::{DirectionRule, Frame, Protocol, Role};
use protocol_spec::session::command_key;

use super::{Twin, swapped};

impl Twin<'_, '_> {
    /// The error reply to `request`, where the spec has an empty direction (MSP's `!`): a
    /// frame of that direction that carries the request's command, which refuses it. A
    /// command the spec does not list is written as a listed one whose key is then replaced
    /// by the request's (the responder seals the frame after). Its name and frame; `None`
    /// without an empty direction or when the key does not fit.
    pub(super) fn error_reply(
        &mut self,
        request: &[u8],
        decoded: Option<&Decoded>,
    ) -> Option<(String, Vec<u8>)> {
        let p = self.codec.protocol();
        let empty = p.directions.iter().position(|d| d.empty)?;
        let f = &p.frames[self.format];
        let key = self.rules.packet.key(request).ok()?;
        let known = self.command_of(key);
        let template =
            known.or_else(|| (0..p.commands.len()).find(|&ci| command_key(p, f, ci).is_some()))?;
        let mut header = match decoded {
            Some(d) => swapped(p, d),
            None => zero_header(f),
        };
        set_direction(p, f, &mut header, empty);
        let mut object = Fields::new();
        object.insert("format", Value::from(f.name.clone()));
        object.insert("header", Value::Struct(header));
        object.insert("command", Value::from(p.commands[template].name.clone()));
        object.insert("payload", Value::Struct(Fields::new()));
        let mut frame = self.codec.encode(&Value::Struct(object)).ok()?.bytes;
        if known.is_none() {
            for (i, field) in self.rules.packet.key.iter().enumerate() {
                let v = self.rules.packet.key_value(request, i).ok()?;
                field.write(&mut frame, v)?;
            }
        }
        self.responder.answer(request, &mut frame).ok()?;
        let name = match known {
            Some(ci) => p.commands[ci].name.clone(),
            None => format!("command {key:#x}"),
        };
        Some((name, frame))
    }
}

/// Sets the field of `header` that tells direction `di`, where one value of a header field
/// tells it (MSP's `direction`: `>` for a reply, `!` for an error reply); the request's value
/// would tell the request's direction.
pub(super) fn set_direction(p: &Protocol, f: &Frame, header: &mut Fields, di: usize) {
    let Some(d) = p.directions.get(di) else {
        return;
    };
    if let DirectionRule::Equals { value, equals } = d.rule.in_frame(f)
        && let Some(v) = f.values.get(value)
    {
        header.insert(v.name.clone(), Value::from(equals));
    }
}

/// A header whose every field the sender sets is zero: the header of a frame answered
/// before any request decoded.
pub(super) fn zero_header(f: &Frame) -> Fields {
    let mut zeros = Fields::new();
    for v in f
        .values
        .iter()
        .filter(|v| matches!(v.role, Role::User { .. }))
    {
        zeros.insert(v.name.clone(), Value::from(0u64));
    }
    zeros
}
