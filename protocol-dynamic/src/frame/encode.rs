//! Frame values (the shape [`Codec::frame_value`](crate::Codec::frame_value) gives) to frames, as the generated packets'
//! `encode` builds them: the payload written first (its size on the wire decides the frame's
//! length) and stuffed, then the header values, the acknowledgement flag and the dispatch key
//! (or CAN id), then the runtime seals the frame.

use protocol_runtime::zeros::trimmed_len;
use protocol_runtime::{EncodeError, FrameLayout, Writer};
use protocol_spec::ir::{Frame, Protocol, Role};

use super::{
    Dispatch, ack_max, ack_value, direction_of, dispatch_of, is_can_id, parse_hex, stuffing,
};
use crate::error::EncodeIssue;
use crate::layout::word_field;
use crate::model::{Fields, Value};
use crate::payload::{value_bytes, write_payload};
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

/// What the frame carries: a command (its index and payload struct), acknowledgement data, or
/// raw bytes.
enum Body {
    Command(usize, Option<usize>),
    Ack,
    Message(usize),
    /// A struct a direction carries in place of the dispatch key, from this header length.
    Keyless(usize, usize),
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

/// Encodes a frame value of format `fi` with its layout. Returns the frame's bytes (for a CAN
/// format, its virtual frame).
///
/// # Errors
/// [`EncodeIssue`] naming the first missing, ill-typed or out-of-range value, or the runtime's
/// refusal of the frame.
pub fn encode(
    p: &Protocol,
    fi: usize,
    layout: &FrameLayout<'_>,
    obj: &Fields,
    given: Option<usize>,
) -> Result<Vec<u8>, EncodeIssue> {
    let f = &p.frames[fi];
    let dispatch = dispatch_of(p, fi);
    let values = header_values(f, obj)?;
    let raw_of = |i: usize| values.iter().find(|(vi, _)| *vi == i).map(|(_, r)| *r);
    let is_ack = obj.get("ack").and_then(Value::as_bool) == Some(true);
    let body = match dispatch {
        Dispatch::Key if is_ack => {
            if f.ack.is_none() {
                return Err(EncodeIssue::new(
                    "ack",
                    format!("frame `{}` has no acknowledgements", f.name),
                ));
            }
            Body::Ack
        }
        Dispatch::Key if p.directions_given() => {
            let d = given_direction(p, obj, given)?;
            match p.directions[d].message {
                Some((si, start)) => Body::Keyless(si, start),
                None => {
                    let ci = command_of(p, false, obj)?;
                    Body::Command(ci, p.commands[ci].payloads.get(d).copied().flatten())
                }
            }
        }
        Dispatch::Key | Dispatch::CanId => {
            let ci = command_of(p, dispatch == Dispatch::CanId, obj)?;
            // The direction, from the header, as the decoder will see it.
            let slot = if dispatch == Dispatch::Key && !p.directions.is_empty() {
                direction_of(p, f, &raw_of).ok_or_else(|| {
                    EncodeIssue::new("header", "the header matches no direction of the spec")
                })?
            } else {
                0
            };
            // A format of a link carries the commands whose id fits its dispatch key, as
            // generated code's `write_header` refuses the others.
            if dispatch == Dispatch::Key && !f.commands.contains(&ci) {
                return Err(EncodeIssue::new(
                    "command",
                    format!(
                        "{} is not carried by frame `{}`: its id does not fit the dispatch key",
                        p.commands[ci].name, f.name
                    ),
                ));
            }
            Body::Command(ci, p.commands[ci].payloads.get(slot).copied().flatten())
        }
        Dispatch::Message(si) => Body::Message(si),
        Dispatch::None => Body::Raw,
    };
    let start = match (&body, f.ack) {
        (Body::Ack, Some((_, ack_header_len))) => ack_header_len,
        (Body::Keyless(_, start), _) => *start,
        _ => f.header_len,
    };
    // The payload first, in place, in a buffer of the largest frame (as generated code's
    // callers size theirs): its size on the wire decides the frame's length.
    let mut buf = vec![0u8; f.max_len()];
    let region_end = f.max_len().saturating_sub(f.trailer_len).max(start);
    let region = buf
        .get_mut(start..region_end)
        .ok_or_else(|| EncodeIssue::runtime(EncodeError::ValueOutOfRange))?;
    let mut plen = write_body(p, f, &body, obj, region)?;
    // A format without extension fields sends the fields before them.
    if let (false, Body::Command(_, Some(si))) = (f.extensions, &body) {
        if let Some(base) = p.structs[*si].base_size {
            plen = plen.min(base);
        }
    }
    if let (true, Body::Command(..)) = (f.truncate_zeros, &body) {
        plen = trimmed_len(region.get(..plen).unwrap_or_default());
    }
    if let (Some(s), Body::Command(..)) = (stuffing(f), &body) {
        plen = s
            .stuff_in_place(region, plen)
            .map_err(EncodeIssue::runtime)?;
    }
    // A bare header (the header alone) has no trailer either.
    let trailer = if f.bare_len.is_some() && start != f.header_len && plen == 0 {
        0
    } else {
        f.trailer_len
    };
    // A wider length: the payload moves behind it when the frame needs one.
    let start = layout
        .place_payload(&mut buf, start, plen, trailer)
        .map_err(EncodeIssue::runtime)?;
    let flagged = flagged_trailer(f, obj)?;
    let total = start + plen + trailer + flagged.as_ref().map_or(0, Vec::len);
    let frame = buf
        .get_mut(..total)
        .ok_or_else(|| EncodeIssue::runtime(EncodeError::ValueOutOfRange))?;
    for (vi, raw) in &values {
        let v = &f.values[*vi];
        word_field(v).write(frame, *raw).ok_or_else(|| {
            EncodeIssue::new(
                format!("header.{}", v.name),
                format!("{raw} does not fit the field"),
            )
        })?;
    }
    if let Some((flag, _)) = f.ack {
        if dispatch == Dispatch::Key {
            let equals = ack_value(f, flag);
            let value = if matches!(body, Body::Ack) {
                equals
            } else {
                1 - equals.min(1)
            };
            word_field(&f.values[flag])
                .write(frame, value)
                .ok_or_else(|| EncodeIssue::runtime(EncodeError::ValueOutOfRange))?;
        }
    }
    if let Body::Command(ci, _) = body {
        write_key(p, f, dispatch, ci, obj, frame)?;
    }
    if let Some(t) = &f.flag_trailer {
        let runtime = |_| EncodeIssue::runtime(EncodeError::ValueOutOfRange);
        word_field(&f.values[t.flag])
            .write(frame, u64::from(flagged.is_some()))
            .ok_or(EncodeError::ValueOutOfRange)
            .map_err(runtime)?;
        if let Some(bytes) = &flagged {
            let at = frame.len() - bytes.len();
            frame[at..].copy_from_slice(bytes);
        }
    }
    layout.seal(frame).map_err(EncodeIssue::runtime)?;
    Ok(frame.to_vec())
}

/// Writes what the frame carries at the start of `region`; returns its size.
fn write_body(
    p: &Protocol,
    f: &Frame,
    body: &Body,
    obj: &Fields,
    region: &mut [u8],
) -> Result<usize, EncodeIssue> {
    let payload = obj.get("payload");
    let len = region.len();
    let too_large = |e: EncodeError| match e {
        EncodeError::BufferTooSmall { .. } => EncodeIssue::new(
            "payload",
            format!("too large for a `{}` frame ({len} bytes at most)", f.name),
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
    let mut w = Writer::new(region);
    match body {
        Body::Command(ci, None) => {
            let empty = match payload {
                None | Some(Value::Null) => true,
                Some(Value::Struct(m)) => m.is_empty(),
                Some(_) => false,
            };
            if !empty {
                let name = &p.commands[*ci].name;
                return Err(EncodeIssue::new(
                    "payload",
                    format!("{name} carries no payload in this direction"),
                ));
            }
        }
        Body::Command(_, Some(si)) | Body::Message(si) | Body::Keyless(si, _) => {
            let v = payload.ok_or_else(|| EncodeIssue::missing("payload"))?;
            // The only error without a path is the writer's: the payload does not fit.
            write_payload(p, *si, v, &mut w, "payload").map_err(|e| {
                if e.path.is_empty() {
                    too_large(EncodeError::BufferTooSmall {
                        needed: len + 1,
                        available: len,
                    })
                } else {
                    e
                }
            })?;
        }
        Body::Ack => {
            let data = bytes_of("the acknowledgement data")?;
            let max = f.ack.map_or(0, |(_, hl)| ack_max(f, hl));
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
        Body::Raw => {
            let data = bytes_of("the payload")?;
            w.put_bytes(&data).map_err(too_large)?;
        }
    }
    Ok(w.position())
}

/// Writes the dispatch key (or the CAN id) of command `ci`.
fn write_key(
    p: &Protocol,
    f: &Frame,
    dispatch: Dispatch,
    ci: usize,
    obj: &Fields,
    frame: &mut [u8],
) -> Result<(), EncodeIssue> {
    let c = &p.commands[ci];
    let fail = || EncodeIssue::runtime(EncodeError::ValueOutOfRange);
    match dispatch {
        Dispatch::Key => {
            for (&vi, id) in f.dispatch.iter().zip(&c.id) {
                word_field(&f.values[vi])
                    .write(frame, truncate(f.values[vi].prim, *id))
                    .ok_or_else(fail)?;
            }
        }
        Dispatch::CanId => {
            let id = c
                .can_id
                .ok_or_else(|| EncodeIssue::new("command", format!("{} has no CAN id", c.name)))?;
            if let Some(given) = obj.get("can_id").filter(|g| g.as_u64() != Some(id)) {
                return Err(EncodeIssue::new(
                    "can_id",
                    format!("{given} is not the CAN id of {} ({id:#x})", c.name),
                ));
            }
            for v in f.values.iter().filter(|v| is_can_id(f, v)) {
                word_field(v).write(frame, id).ok_or_else(fail)?;
            }
        }
        Dispatch::Message(_) | Dispatch::None => {}
    }
    Ok(())
}
