//! What a spec's packets hold, as the C code lays them out: what the frames of a format carry
//! ([`Carries`]), the payloads a packet can carry ([`Slot`]), the header values a sender sets.
//! The header's types, the decoders, the encoders and the text form all walk these, so that
//! they agree on every member of a packet.

use std::fmt::Write as _;

use crate::ir::{FieldKind, Frame, HeaderValue, PacketKind, Protocol, Role, Transport};

use super::names::Names;

/// The header values of frame format `x` a packet holds: those the sender sets (a CAN frame's
/// id is the command's, not a header value).
pub fn user_values(f: &Frame) -> impl Iterator<Item = &HeaderValue> {
    f.values.iter().filter(move |v| {
        matches!(v.role, Role::User { .. })
            && !(matches!(f.transport, Transport::Can { .. }) && v.name == "can_id")
    })
}

/// What the frames of a format carry: a command's payload found from the dispatch key (the
/// first format with a key, and the formats that carry the commands too), a command's payload
/// found from the CAN id, or the one struct of a format without dispatch key.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Carries {
    /// A command, from the format's dispatch key.
    Commands,
    /// A command, from the CAN id.
    Can,
    /// The struct (index into [`Protocol::structs`]) every frame carries.
    Message(Option<usize>),
    /// The payload's bytes as they are: a format without dispatch key or message.
    Bytes,
}

/// What the frames of format `fi` carry (the IR's [`PacketKind`]; the first format's from its
/// dispatch key).
pub fn carries(p: &Protocol, fi: usize) -> Carries {
    let f = &p.frames[fi];
    if fi == 0 {
        return match (f.dispatch.is_empty(), f.message) {
            (false, _) => Carries::Commands,
            (true, Some(si)) => Carries::Message(Some(si)),
            (true, None) => Carries::Bytes,
        };
    }
    match f.packet {
        PacketKind::Commands | PacketKind::Command => Carries::Commands,
        PacketKind::Can => Carries::Can,
        PacketKind::Message(si) => Carries::Message(Some(si)),
        PacketKind::None => f
            .message
            .map_or(Carries::Bytes, |si| Carries::Message(Some(si))),
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

/// Whether the frames of format `fi` carry commands.
pub fn keyed_format(p: &Protocol, fi: usize) -> bool {
    matches!(carries(p, fi), Carries::Commands | Carries::Can)
}

/// Every payload a packet of format `fi` can carry, commands in spec order, then directions:
/// the commands the format carries (a CAN format: those with a CAN id), or its message.
pub fn slots_of(p: &Protocol, fi: usize) -> Vec<Slot> {
    let f = &p.frames[fi];
    let can = match carries(p, fi) {
        Carries::Message(si) => {
            return vec![Slot {
                command: None,
                direction: 0,
                si,
                name: "message".into(),
                keyless: None,
            }];
        }
        Carries::Bytes => return Vec::new(),
        Carries::Can => true,
        Carries::Commands => false,
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
            FieldKind::Optional(inner) => holds(inner, kind),
            k => kind(k),
        }
    }
    p.structs
        .iter()
        .any(|s| s.fields.iter().any(|f| holds(&f.kind, kind)))
}
