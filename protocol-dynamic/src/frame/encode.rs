//! Frame values (the shape [`Codec::frame_value`](crate::Codec::frame_value) gives) to frames,
//! as the generated packets' `encode` builds them: the payload written first (its size on the
//! wire decides the frame's length), then the runtime's [`PacketRules::assemble`] places it
//! (trimmed, stuffed, behind a wider length), writes the header values this module gives it,
//! the acknowledgement flag and the dispatch key (or CAN id), and seals the frame.
//!
//! This module owns reading the frame value: which command and payload struct it names, the
//! header values and the payload's bytes, and the errors that name a value's path.

use protocol_runtime::EncodeError;
use protocol_runtime::Writer;
use protocol_runtime::decoder::frame_body_mut;
use protocol_runtime::rules::{Body, PacketRules};
use protocol_spec::ir::{Frame, Protocol, Role};
use protocol_spec::rules::{Carries, carries};

use super::{carried, is_can_id, parse_hex};
use crate::error::EncodeIssue;
use crate::layout::word_field;
use crate::model::{Fields, Value};
use crate::payload::{carry_of, value_bytes, write_payload};
use crate::value::{NumError, truncate, value_bits};

/// The command a frame value names: `command` (spec or Rust name), else its `id` or `can_id`.
fn command_of(p: &Protocol, by_can: bool, obj: &Fields) -> Result<usize, EncodeIssue> {
    if let Some(name) = obj.get("command") {
        let name = name
            .as_str()
            .ok_or_else(|| EncodeIssue::new("command", "expected a command name"))?;
        return p
            .commands
            .iter()
            .position(|c| c.name == name || c.rust_name == name)
            .ok_or_else(|| {
                EncodeIssue::new("command", format!("no command `{name}` in the spec"))
            });
    }
    let (key, value) = match (obj.get("id"), obj.get("can_id")) {
        (Some(v), _) => ("id", v),
        (None, Some(v)) => ("can_id", v),
        (None, None) => return Err(EncodeIssue::missing("command")),
    };
    let ids: Vec<u64> = match value {
        Value::Array(items) => items.iter().filter_map(Value::as_u64).collect(),
        other => other.as_u64().into_iter().collect(),
    };
    p.commands
        .iter()
        .position(|c| {
            if by_can || key == "can_id" {
                ids.len() == 1 && c.can_id == ids.first().copied()
            } else {
                c.id == ids
            }
        })
        .ok_or_else(|| EncodeIssue::new(key, format!("no command has the id {value}")))
}

/// The user-set header values of a frame value, checked against their types: (value index,
/// raw value).
fn header_values(f: &Frame, obj: &Fields) -> Result<Vec<(usize, u64)>, EncodeIssue> {
    let empty = Fields::new();
    let header = match obj.get("header") {
        Some(Value::Struct(h)) => h,
        Some(Value::Null) | None => &empty,
        Some(_) => return Err(EncodeIssue::new("header", "expected an object")),
    };
    // Values the spec computes (a length, a command id) may be given: they are ignored.
    if let Some(k) = header
        .keys()
        .find(|k| !f.values.iter().any(|v| v.name == **k && !is_can_id(f, v)))
        .filter(|k| f.flag_trailer.as_ref().is_none_or(|t| t.name != **k))
    {
        return Err(EncodeIssue::new(
            format!("header.{k}"),
            format!("frame `{}` has no such header field", f.name),
        ));
    }
    let mut values = Vec::new();
    for (vi, v) in f.values.iter().enumerate() {
        if !matches!(v.role, Role::User { .. }) {
            continue;
        }
        let path = format!("header.{}", v.name);
        let given = header
            .get(&v.name)
            .ok_or_else(|| EncodeIssue::missing(&path))?;
        let raw = value_bits(given, v.prim).map_err(|e| match e {
            NumError::Type(m) | NumError::Range(m) => EncodeIssue::new(&path, m),
        })?;
        values.push((vi, raw));
    }
    Ok(values)
}

/// The bytes of the frame's flag trailer the header gives (`header.NAME`: bytes, a hex string
/// or an array of numbers, of exactly its length), or `None` when it gives none (or `null`).
fn flagged_trailer(f: &Frame, obj: &Fields) -> Result<Option<Vec<u8>>, EncodeIssue> {
    let Some(t) = &f.flag_trailer else {
        return Ok(None);
    };
    let given = match obj.get("header") {
        Some(Value::Struct(h)) => h.get(&t.name),
        _ => None,
    };
    let path = format!("header.{}", t.name);
    match given {
        None | Some(Value::Null) => Ok(None),
        Some(v) => match value_bytes(v) {
            Some(b) if b.len() == t.len => Ok(Some(b)),
            _ => Err(EncodeIssue::new(
                path,
                format!("expected {} bytes (or null: no {})", t.len, t.name),
            )),
        },
    }
}

/// What a frame value carries: a command (its index, payload struct, the direction its
/// header tells and the message its payload is in), acknowledgement data, a struct, or raw
/// bytes.
enum Carried {
    Command {
        ci: usize,
        si: Option<usize>,
        direction: Option<usize>,
        carry: Option<usize>,
    },
    Ack,
    /// A struct, and the message a packet it carries is in.
    Message(usize, Option<usize>),
    /// A struct a direction carries in place of the dispatch key, from this header length (a
    /// packet it carries is in no message: validation keeps carriers from such specs).
    Keyless(usize, usize, Option<usize>),
    Raw,
}

/// The direction of a frame value of a spec whose directions are given: its `direction`, else
/// `default` (the codec's).
fn given_direction(
    p: &Protocol,
    obj: &Fields,
    default: Option<usize>,
) -> Result<usize, EncodeIssue> {
    let names = || {
        let n: Vec<&str> = p.directions.iter().map(|d| d.name.as_str()).collect();
        n.join(", ")
    };
    match obj.get("direction") {
        Some(Value::String(name)) => {
            p.directions
                .iter()
                .position(|d| &d.name == name)
                .ok_or_else(|| {
                    EncodeIssue::new(
                        "direction",
                        format!("no direction `{name}` in the spec (it has {})", names()),
                    )
                })
        }
        Some(Value::Null) | None => default.ok_or_else(|| {
            EncodeIssue::new(
                "direction",
                format!(
                    "missing: no header field tells this spec's directions, so a frame names one ({})",
                    names()
                ),
            )
        }),
        Some(_) => Err(EncodeIssue::new("direction", "expected a direction name")),
    }
}

/// The direction a frame value of a spec whose directions are given is encoded in (its
/// `direction`, else `given`, the codec's); `None` for another spec or a value that names no
/// direction of the spec (whose encoding then says why).
pub fn frame_direction(p: &Protocol, obj: &Fields, given: Option<usize>) -> Option<usize> {
    p.directions_given()
        .then(|| given_direction(p, obj, given).ok())
        .flatten()
}

/// Encodes a frame value of format `fi` under the format's packet `rules`. Returns the frame's
/// bytes (for a CAN format, its virtual frame).
///
/// # Errors
/// [`EncodeIssue`] naming the first missing, ill-typed or out-of-range value, or the runtime's
/// refusal of the frame.
pub fn encode(
    p: &Protocol,
    fi: usize,
    rules: &PacketRules<'_>,
    obj: &Fields,
    given: Option<usize>,
) -> Result<Vec<u8>, EncodeIssue> {
    // A direction with fields of its own writes the first format by its own layout, which
    // `rules` hold (the codec chose them by `frame_direction`).
    let own = frame_direction(p, obj, given);
    let f = p
        .frame_in(fi, own)
        .ok_or_else(|| EncodeIssue::new("format", "no such frame format"))?;
    let values = header_values(f, obj)?;
    let what = carried_by(p, f, rules, &values, obj, given)?;
    let key = match what {
        Carried::Command { ci, .. } => key_of(p, f, ci, obj),
        _ => Ok(Vec::new()),
    };
    let body = match what {
        Carried::Command { si, direction, .. } => Body::Command {
            key: key.as_deref().unwrap_or_default(),
            carried: carried(p, f, si),
            direction,
        },
        Carried::Ack => Body::Ack,
        Carried::Keyless(_, start, _) => Body::Struct { start },
        Carried::Message(..) | Carried::Raw => Body::Struct {
            start: rules.header_len,
        },
    };
    // The payload first, into the room a buffer of the largest frame leaves it (as generated
    // code's callers size theirs).
    let start = rules.start(&body);
    let room = rules
        .layout
        .max_len
        .saturating_sub(rules.trailer_len)
        .saturating_sub(start);
    let written = write_body(p, f, rules, &what, obj, room)?;
    let flagged = flagged_trailer(f, obj);
    let flag_trailer = match &flagged {
        Ok(Some(bytes)) => bytes.len(),
        _ => 0,
    };
    let len = rules.frame_len(&body, rules.wire_len(&body, &written), flag_trailer);
    // (Escaping may double a frame: the flags aside, every byte may go as two.)
    let escaped = if rules.layout.escape.is_some() { 2 } else { 1 };
    let mut buf = vec![0u8; rules.layout.max_len.saturating_mul(escaped)];
    let mut aside = vec![0u8; written.len()];
    // What the header writer refuses, named by the value's path: a flag trailer, a header
    // value, then the key, as the frame is written in that order.
    let mut refused = None;
    let header = |frame: &mut [u8]| {
        let flagged = flagged.clone()?;
        write_header(f, rules, &values, flagged.as_deref(), frame)?;
        key.as_ref().map(|_| ()).map_err(Clone::clone)
    };
    let n = rules
        .assemble(
            &mut buf,
            &mut aside,
            &body,
            || len,
            flag_trailer,
            |w| w.put_bytes(&written),
            |frame| {
                header(frame).map_err(|issue| {
                    refused = Some(issue);
                    EncodeError::ValueOutOfRange {
                        place: protocol_runtime::error::Place::NONE,
                    }
                })
            },
        )
        .map_err(|e| refused.take().unwrap_or_else(|| EncodeIssue::runtime(e)))?;
    buf.truncate(n);
    Ok(buf)
}

/// What frame value `obj` of format `f` carries, refused when the format does not carry it.
fn carried_by(
    p: &Protocol,
    f: &Frame,
    rules: &PacketRules<'_>,
    values: &[(usize, u64)],
    obj: &Fields,
    given: Option<usize>,
) -> Result<Carried, EncodeIssue> {
    let carries = carries(f);
    let is_ack = obj.get("ack").and_then(Value::as_bool) == Some(true);
    match carries {
        Carries::Command if is_ack => {
            if rules.ack.is_none() {
                return Err(EncodeIssue::new(
                    "ack",
                    format!("frame `{}` has no acknowledgements", f.name),
                ));
            }
            Ok(Carried::Ack)
        }
        Carries::Command if p.directions_given() => {
            let d = given_direction(p, obj, given)?;
            Ok(match p.directions[d].message {
                Some((si, start)) => Carried::Keyless(si, start, None),
                None => {
                    let ci = command_of(p, false, obj)?;
                    let si = p.commands[ci].payloads.get(d).copied().flatten();
                    Carried::Command {
                        ci,
                        si,
                        direction: None,
                        carry: Some(d),
                    }
                }
            })
        }
        Carries::Command | Carries::CanCommand => {
            let ci = command_of(p, carries == Carries::CanCommand, obj)?;
            // The direction, from the header, as the decoder will see it.
            let direction = if rules.directions.is_empty() {
                None
            } else {
                let d = header_direction(f, rules, values).ok_or_else(|| {
                    EncodeIssue::new("header", "the header matches no direction of the spec")
                })?;
                Some(d)
            };
            // A format of a link carries the commands whose id fits its dispatch key, as
            // generated code's `write_header` refuses the others.
            if carries == Carries::Command && !f.commands.contains(&ci) {
                return Err(EncodeIssue::new(
                    "command",
                    format!(
                        "{} is not carried by frame `{}`: its id does not fit the dispatch key",
                        p.commands[ci].name, f.name
                    ),
                ));
            }
            let si = p.commands[ci]
                .payloads
                .get(direction.unwrap_or(0))
                .copied()
                .flatten();
            Ok(Carried::Command {
                ci,
                si,
                direction,
                carry: carry_of(p, direction),
            })
        }
        Carries::Struct(si) => Ok(Carried::Message(si, carry_of(p, None))),
        Carries::Bytes => Ok(Carried::Raw),
    }
}

/// The direction a header of `values` tells, by the rules' own test on a header written with
/// them; `None` when it tells none.
fn header_direction(f: &Frame, rules: &PacketRules<'_>, values: &[(usize, u64)]) -> Option<usize> {
    let mut header = vec![0u8; rules.layout.max_len];
    for &(vi, raw) in values {
        // A value that does not fit its field stays out of this header: writing the frame
        // refuses it, once the payload is written.
        let _ = word_field(&f.values[vi]).write(&mut header, raw);
    }
    rules.direction(&header).ok()
}

/// Writes the header values and the flag trailer (its flag, and its bytes at the end) into
/// `frame`: the flag first, since it decides where the body (the frame without the flag
/// trailer) ends, back from which the values after the payload lie.
fn write_header(
    f: &Frame,
    rules: &PacketRules<'_>,
    values: &[(usize, u64)],
    flagged: Option<&[u8]>,
    frame: &mut [u8],
) -> Result<(), EncodeIssue> {
    let runtime = || {
        EncodeIssue::runtime(EncodeError::ValueOutOfRange {
            place: protocol_runtime::error::Place::NONE,
        })
    };
    if let Some(t) = &f.flag_trailer {
        word_field(&f.values[t.flag])
            .write(frame, u64::from(flagged.is_some()))
            .ok_or_else(runtime)?;
    }
    let body = frame_body_mut(rules.layout, frame);
    for &(vi, raw) in values {
        let v = &f.values[vi];
        word_field(v).write(body, raw).ok_or_else(|| {
            EncodeIssue::new(
                format!("header.{}", v.name),
                format!("{raw} does not fit the field"),
            )
        })?;
    }
    if let Some(bytes) = flagged {
        let at = frame.len().saturating_sub(bytes.len());
        frame
            .get_mut(at..)
            .filter(|end| end.len() == bytes.len())
            .ok_or_else(runtime)?
            .copy_from_slice(bytes);
    }
    Ok(())
}

/// The payload's bytes as the frame value gives them, before the rules trim or stuff them:
/// written into `room` bytes at most, the room a frame of the format leaves it.
fn write_body(
    p: &Protocol,
    f: &Frame,
    rules: &PacketRules<'_>,
    what: &Carried,
    obj: &Fields,
    room: usize,
) -> Result<Vec<u8>, EncodeIssue> {
    let payload = obj.get("payload");
    let too_large = |e: EncodeError| match e {
        EncodeError::BufferTooSmall { .. } => EncodeIssue::new(
            "payload",
            format!("too large for a `{}` frame ({room} bytes at most)", f.name),
        ),
        other => EncodeIssue::runtime(other),
    };
    let bytes_of = |what: &str| -> Result<Vec<u8>, EncodeIssue> {
        if let Some(Value::Bytes(b)) = payload {
            return Ok(b.clone());
        }
        let text = payload
            .and_then(Value::as_str)
            .ok_or_else(|| EncodeIssue::new("payload", format!("expected {what} as hex")))?;
        parse_hex(text).ok_or_else(|| EncodeIssue::new("payload", "invalid hex"))
    };
    let mut region = vec![0u8; room];
    let mut w = Writer::new(&mut region);
    match *what {
        Carried::Command { ci, si: None, .. } => {
            let empty = match payload {
                None | Some(Value::Null) => true,
                Some(Value::Struct(m)) => m.is_empty(),
                Some(_) => false,
            };
            if !empty {
                let name = &p.commands[ci].name;
                return Err(EncodeIssue::new(
                    "payload",
                    format!("{name} carries no payload in this direction"),
                ));
            }
        }
        Carried::Command {
            si: Some(si),
            carry,
            ..
        }
        | Carried::Message(si, carry)
        | Carried::Keyless(si, _, carry) => {
            let v = payload.ok_or_else(|| EncodeIssue::missing("payload"))?;
            // The only error without a path is the writer's: the payload does not fit.
            write_payload(p, si, v, &mut w, "payload", carry).map_err(|e| {
                if e.path.is_empty() {
                    too_large(EncodeError::BufferTooSmall {
                        needed: room + 1,
                        available: room,
                    })
                } else {
                    e
                }
            })?;
        }
        Carried::Ack => {
            let data = bytes_of("the acknowledgement data")?;
            let max = rules.ack_max();
            if data.len() > max {
                return Err(EncodeIssue::new(
                    "payload",
                    format!(
                        "{} bytes of acknowledgement data, at most {max}",
                        data.len()
                    ),
                ));
            }
            w.put_bytes(&data).map_err(too_large)?;
        }
        Carried::Raw => {
            let data = bytes_of("the payload")?;
            w.put_bytes(&data).map_err(too_large)?;
        }
    }
    let len = w.position();
    region.truncate(len);
    Ok(region)
}

/// The key values of command `ci` in format `f`: its id in the dispatch fields, or its CAN id
/// (which a frame value's `can_id`, if it gives one, must be).
fn key_of(p: &Protocol, f: &Frame, ci: usize, obj: &Fields) -> Result<Vec<u64>, EncodeIssue> {
    let c = &p.commands[ci];
    if carries(f) != Carries::CanCommand {
        return Ok(f
            .dispatch
            .iter()
            .zip(&c.id)
            .map(|(&vi, &id)| truncate(f.values[vi].prim, id))
            .collect());
    }
    let id = c
        .can_id
        .ok_or_else(|| EncodeIssue::new("command", format!("{} has no CAN id", c.name)))?;
    if let Some(given) = obj.get("can_id").filter(|g| g.as_u64() != Some(id)) {
        return Err(EncodeIssue::new(
            "can_id",
            format!("{given} is not the CAN id of {} ({id:#x})", c.name),
        ));
    }
    Ok(vec![id])
}
