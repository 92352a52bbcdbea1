//! What a spec's packets hold, as the C code lays them out: what the frames of a format carry
//! (the packet rules' [`Carries`]), the payloads a packet can carry ([`Slot`]), the header
//! values a sender sets. The header's types, the decoders, the encoders and the text form all
//! walk these, so that they agree on every member of a packet.

use std::fmt::Write as _;

use crate::ir::{FieldKind, Frame, HeaderValue, Protocol, Role, Transport};
use crate::rules::Carries;

use super::names::{Fx, Names};

/// The header values of frame format `x` a packet holds: those the sender sets (a CAN frame's
/// id is the command's, not a header value).
pub fn user_values(f: &Frame) -> impl Iterator<Item = &HeaderValue> {
    f.values.iter().filter(move |v| {
        matches!(v.role, Role::User { .. })
            && !(matches!(f.transport, Transport::Can { .. }) && v.name == "can_id")
    })
}

/// What the frames of format `x` carry: its packet rules' ([`RulesPlan::carries`]), except
/// that a format with a `message` whose rules give raw bytes (one without a packet type of its
/// own: a format of a spec of several whose first has no dispatch key) carries that struct, as
/// the C gives every such format a packet of its message.
///
/// [`RulesPlan::carries`]: crate::rules::RulesPlan::carries
pub fn carries(p: &Protocol, x: &Fx) -> Carries {
    match (x.rules.carries, p.frames[x.fi].message) {
        (Carries::Bytes, Some(si)) => Carries::Struct(si),
        (carries, _) => carries,
    }
}

/// A payload a packet can carry: a command's in a direction, or the struct every frame of a
/// format without dispatch key carries (its `message`).
pub struct Slot {
    /// The command (`None` for the message of a format without dispatch key).
    pub command: Option<usize>,
    /// The direction (index into [`Protocol::directions`]; 0 when the spec has none).
    pub direction: usize,
    /// The payload struct (`None`: the payload is empty).
    pub si: Option<usize>,
    /// The name of the packet's union member and of the encoder's suffix: `set_robot_speed`,
    /// `set_robot_speed_request`, `message`, `response` (the message of a direction the decoder
    /// is given).
    pub name: String,
    /// For the message of a direction the decoder is given, where its payload starts (the
    /// header without the dispatch key, whose bytes the message takes).
    pub keyless: Option<usize>,
}

impl Slot {
    /// The C condition under which `packet` (a pointer) holds this slot's payload.
    pub fn test(&self, p: &Protocol, n: &Names, packet: &str) -> String {
        let Some(ci) = self.command else {
            return match (self.keyless, p.directions.get(self.direction)) {
                (Some(_), Some(d)) => {
                    format!("{packet}->direction == {}{}", n.up, d.name.to_uppercase())
                }
                _ => "1".into(),
            };
        };
        let mut out = format!("{packet}->command == {}{}", n.up, p.commands[ci].name);
        if let Some(d) = p.directions.get(self.direction) {
            let _ = write!(
                out,
                " && {packet}->direction == {}{}",
                n.up,
                d.name.to_uppercase()
            );
        }
        out
    }

    /// `if (TEST) ` before a statement for this slot only, or nothing for the one slot of a
    /// format without dispatch key.
    pub fn guard(&self, p: &Protocol, n: &Names, packet: &str) -> String {
        if self.command.is_some() || self.keyless.is_some() {
            format!("if ({}) ", self.test(p, n, packet))
        } else {
            String::new()
        }
    }
}

/// Whether the frames of format `x` carry commands.
pub fn keyed_format(p: &Protocol, x: &Fx) -> bool {
    matches!(carries(p, x), Carries::Command | Carries::CanCommand)
}

/// Every payload a packet of format `x` can carry, commands in spec order, then directions:
/// the commands the format carries (a CAN format: those with a CAN id), or its message.
pub fn slots_of(p: &Protocol, x: &Fx) -> Vec<Slot> {
    let f = &p.frames[x.fi];
    let can = match carries(p, x) {
        Carries::Struct(si) => {
            return vec![Slot {
                command: None,
                direction: 0,
                si: Some(si),
                name: "message".into(),
                keyless: None,
            }];
        }
        Carries::Bytes => return Vec::new(),
        Carries::CanCommand => true,
        Carries::Command => false,
    };
    let mut out = Vec::new();
    // A direction the decoder is given may carry one struct instead of commands.
    let keyless = |di: usize| p.directions.get(di).and_then(|d| d.message);
    for (ci, c) in p.commands.iter().enumerate() {
        let carried = if can {
            c.can_id.is_some()
        } else {
            f.commands.contains(&ci)
        };
        if !carried {
            continue;
        }
        // A CAN format's frames carry the first direction's payload (its specs have none).
        let directions = if can { 1 } else { c.payloads.len() };
        for (di, si) in c.payloads.iter().enumerate().take(directions) {
            if keyless(di).is_some() {
                continue;
            }
            let name = c.name.to_lowercase();
            out.push(Slot {
                command: Some(ci),
                direction: di,
                si: *si,
                name: match p.directions.get(di).filter(|_| !can) {
                    Some(dir) => format!("{name}_{}", dir.name),
                    None => name,
                },
                keyless: None,
            });
        }
    }
    if !can {
        for (di, d) in p.directions.iter().enumerate() {
            if let Some((si, start)) = keyless(di) {
                out.push(Slot {
                    command: None,
                    direction: di,
                    si: Some(si),
                    name: d.name.clone(),
                    keyless: Some(start),
                });
            }
        }
    }
    out
}

/// Whether a field of a struct of `p` is a `kind` (or an optional field holds one): the
/// helpers only some fields need are printed for the specs that have them.
pub fn any_field(p: &Protocol, kind: fn(&FieldKind) -> bool) -> bool {
    fn holds(k: &FieldKind, kind: fn(&FieldKind) -> bool) -> bool {
        match k {
            FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => holds(inner, kind),
            k => kind(k),
        }
    }
    p.structs
        .iter()
        .any(|s| s.fields.iter().any(|f| holds(&f.kind, kind)))
}
