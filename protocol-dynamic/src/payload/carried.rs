//! A packet carried inside a payload (the IR's `Carried`): the run-time codec's counterpart
//! of the `<field>_<direction>()` and `set_<field>_<direction>(..)` accessors generated code
//! has (`protocol-codegen/src/codegen/dispatch/carried.rs`), executed where a carrying struct
//! is read or written in a frame's payload.
//!
//! A carrying field's value is the carried packet, read one level (a carrier inside it keeps
//! its bytes, as generated code reads one level at a time), in the direction of the frame
//! around it: `{"command": NAME, "payload": {...}}`. A carried packet generated code cannot
//! read (an unknown command, a payload that is not its command's) keeps its bytes, with the
//! error naming the carrying field: `{"bytes": HEX, "error": TEXT}`; the frame around it still
//! decodes. Writing takes either form, or the bytes alone; the packet form is sealed as
//! `set_<field>_<direction>` seals it: the key field takes the command's id and the size field
//! the payload's length (the runtime's `field::carried_key`), and the bytes are the payload.
//!
//! Where a carried packet is read, the codec passes a `carry`: the index of the message a
//! command's payload is in (the direction's index, or 0 for a spec without directions), or
//! `None` inside a carried packet and where the frame names no direction.

use protocol_runtime::Writer;
use protocol_runtime::field::{carried_command, carried_key};
use protocol_spec::ir::{FieldKind, Prim, Protocol, Struct, ValueType};

use super::join;
use super::write::{value_bytes, write_payload};
use crate::error::{DecodeIssue, EncodeIssue};
use crate::frame::Decoded;
use crate::model::{Fields, Value};
use crate::names::Names;

/// The message index (`carry`) a frame's carried packets are read in: its direction's, or 0
/// for a spec without directions (its one `Message` enum); `None` when the spec has
/// directions and the frame names none.
pub(crate) fn carry_of(p: &Protocol, direction: Option<usize>) -> Option<usize> {
    if p.directions.is_empty() {
        Some(0)
    } else {
        direction
    }
}

/// Replaces the bytes of each carrying field of struct `s`, read into `out`, by the packet
/// they carry in message `carry`, or by the bytes and the error of reading them.
pub(super) fn show(p: &Protocol, names: &Names, s: &Struct, carry: usize, out: &mut Fields) {
    for c in &s.carries {
        let (field, key) = (&s.fields[c.field].name, &s.fields[c.key].name);
        let key = out.get(key).and_then(Value::as_u64).unwrap_or(0);
        let Some(bytes) = out.get(field).and_then(Value::as_bytes) else {
            continue;
        };
        let shown = match read_carried(p, names, carry, key, bytes) {
            Ok((ci, payload)) => Fields::from_iter([
                ("command", Value::from(p.commands[ci].name.as_str())),
                ("payload", payload),
            ]),
            Err(issue) => Fields::from_iter([
                ("bytes", Value::Bytes(bytes.to_vec())),
                (
                    "error",
                    Value::from(format!("`{}.{field}`: {issue}", s.name)),
                ),
            ]),
        };
        out.insert(field.as_str(), Value::Struct(shown));
    }
}

/// The packets the payload of decoded frame `d` carries in its carrying fields' bytes (see
/// [`Codec::carried_packets`](crate::Codec::carried_packets)).
pub(crate) fn carried_packets(
    p: &Protocol,
    names: &Names,
    d: &Decoded,
) -> Vec<Result<(usize, Value), DecodeIssue>> {
    let si = d.command.and_then(|ci| {
        let slot = d.direction.unwrap_or(0);
        p.commands[ci].payloads.get(slot).copied().flatten()
    });
    let (Some(si), Some(carry), Some(fields)) =
        (si, carry_of(p, d.direction), d.payload.as_struct())
    else {
        return Vec::new();
    };
    let s = &p.structs[si];
    s.carries
        .iter()
        .filter_map(|c| {
            let key = fields.get(&s.fields[c.key].name).and_then(Value::as_u64)?;
            let bytes = fields
                .get(&s.fields[c.field].name)
                .and_then(Value::as_bytes)?;
            Some(read_carried(p, names, carry, key, bytes))
        })
        .collect()
}

/// The command whose id `key` is and its payload read from `bytes` in message `carry`, as
/// generated code's `carried_command` and `read_payload` give them.
fn read_carried(
    p: &Protocol,
    names: &Names,
    carry: usize,
    key: u64,
    bytes: &[u8],
) -> Result<(usize, Value), DecodeIssue> {
    let ci = carried_command(key, |id: u64| p.commands.iter().position(|c| c.id == [id]))
        .map_err(|_| DecodeIssue::UnknownCommand { id: vec![key], key })?;
    let c = &p.commands[ci];
    let si = c.payloads.get(carry).copied().flatten();
    let payload = crate::frame::read_struct_payload(p, names, si, &c.name, bytes, None)?;
    Ok((ci, payload))
}

/// The object of struct `s` to write: `obj`, with each carrying field given as a packet
/// sealed into its bytes, key and size, as `set_<field>_<direction>` seals it in message
/// `carry`; the `{"bytes", "error"}` form gives its bytes.
///
/// # Errors
/// [`EncodeIssue`] naming the carrying field's path: an unknown command, a payload that its
/// command's struct refuses, an id or a length that does not fit its field, more bytes than
/// the field holds.
pub(super) fn seal(
    p: &Protocol,
    s: &Struct,
    obj: &Fields,
    carry: usize,
    path: &str,
) -> Result<Fields, EncodeIssue> {
    let mut out = obj.clone();
    for c in &s.carries {
        let field = &s.fields[c.field];
        let fpath = join(path, &field.name);
        let Some(Value::Struct(given)) = obj.get(&field.name) else {
            continue;
        };
        if given.get("command").is_none() {
            let bytes = only_bytes(given, &fpath)?;
            out.insert(field.name.as_str(), Value::Bytes(bytes));
            continue;
        }
        let max = match field.kind {
            FieldKind::Bytes { max, .. } => max,
            _ => 0,
        };
        let (id, bytes) = seal_packet(p, given, carry, max, &fpath)?;
        if bytes.len() > max {
            let n = bytes.len();
            let why = format!("a carried payload of {n} bytes, at most {max} allowed");
            return Err(EncodeIssue::new(&fpath, why));
        }
        let key = &s.fields[c.key];
        let id = fit(s, &key.name, id, &fpath)?;
        out.insert(key.name.as_str(), Value::UInt(id));
        if let FieldKind::Bytes {
            size_from: Some(n), ..
        } = &field.kind
        {
            let len = fit(s, n, bytes.len() as u64, &fpath)?;
            out.insert(n.as_str(), Value::UInt(len));
        }
        out.insert(field.name.as_str(), Value::Bytes(bytes));
    }
    Ok(out)
}

/// The bytes of the form a carried packet that could not be read takes (`bytes`, with its
/// `error` ignored).
fn only_bytes(given: &Fields, fpath: &str) -> Result<Vec<u8>, EncodeIssue> {
    if let Some(k) = given.keys().find(|k| !matches!(*k, "bytes" | "error")) {
        let why = "a carried packet is `command` and `payload`, or `bytes`";
        return Err(EncodeIssue::new(join(fpath, k), why));
    }
    let bytes = given
        .get("bytes")
        .ok_or_else(|| EncodeIssue::missing(join(fpath, "command")))?;
    value_bytes(bytes).ok_or_else(|| {
        EncodeIssue::new(
            join(fpath, "bytes"),
            "expected bytes: a hex string or an array of numbers 0..=255",
        )
    })
}

/// The id of the command a packet object names and its payload's bytes, written as its
/// command's struct in message `carry` (no bytes for a command without one there), in room
/// for the carrying field's `max` bytes and more, so that a payload too long is told by its
/// length.
fn seal_packet(
    p: &Protocol,
    given: &Fields,
    carry: usize,
    max: usize,
    fpath: &str,
) -> Result<(u64, Vec<u8>), EncodeIssue> {
    let cpath = join(fpath, "command");
    if let Some(k) = given.keys().find(|k| !matches!(*k, "command" | "payload")) {
        let why = "a carried packet is `command` and `payload`, or `bytes`";
        return Err(EncodeIssue::new(join(fpath, k), why));
    }
    let name = given
        .get("command")
        .and_then(Value::as_str)
        .ok_or_else(|| EncodeIssue::new(&cpath, "expected a command name"))?;
    let c = p
        .commands
        .iter()
        .find(|c| c.name == name || c.rust_name == name)
        .ok_or_else(|| EncodeIssue::new(&cpath, format!("no command `{name}` in the spec")))?;
    let id = c.id.first().copied().unwrap_or(0);
    let ppath = join(fpath, "payload");
    let payload = given.get("payload");
    let Some(si) = c.payloads.get(carry).copied().flatten() else {
        return match payload {
            None | Some(Value::Null) => Ok((id, Vec::new())),
            Some(Value::Struct(m)) if m.is_empty() => Ok((id, Vec::new())),
            Some(_) => {
                let why = format!("{name} carries no payload in this direction");
                Err(EncodeIssue::new(&ppath, why))
            }
        };
    };
    let v = payload.ok_or_else(|| EncodeIssue::missing(&ppath))?;
    let mut buf = vec![0u8; p.structs[si].size.max(max) + 1];
    let mut w = Writer::new(&mut buf);
    write_payload(p, si, v, &mut w, &ppath, None)?;
    let len = w.position();
    buf.truncate(len);
    Ok((id, buf))
}

/// `value` in the key or size field `name` of `s`, by the runtime's
/// `carried_key` on the field's width.
fn fit(s: &Struct, name: &str, value: u64, fpath: &str) -> Result<u64, EncodeIssue> {
    let bits = s
        .fields
        .iter()
        .find(|f| f.name == name)
        .and_then(|f| match &f.kind {
            FieldKind::Value {
                ty: ValueType::Scalar { scalar, .. },
                ..
            } => Some(scalar.prim.bits()),
            _ => None,
        })
        .unwrap_or(Prim::U64.bits());
    carried_key::<u64>(value, bits).map_err(|_| {
        EncodeIssue::new(
            fpath,
            format!("{value} does not fit `{name}` ({bits} bits), which the carried packet sets"),
        )
    })
}
