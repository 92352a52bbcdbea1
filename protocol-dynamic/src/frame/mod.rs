//! Whole frames between the wire and [`Value`](crate::Value)s: header values, acknowledgements, the dispatch key,
//! byte stuffing, the direction and the payload, in the order the generated packets take them
//! (`Packet::from_frame`, and the `<Name>Packet` of a CAN or message-only frame format, in
//! `protocol-codegen/src/codegen/dispatch/`), so that both report the same error for the same
//! bytes. Encoding lives in [`encode`].
//!
//! This module owns which frame formats carry what ([`Dispatch`]); verifying and sealing frames
//! is the runtime's [`FrameLayout`](protocol_runtime::FrameLayout) business.

mod encode;

pub use encode::encode;

use protocol_runtime::DecodeError;
use protocol_runtime::stuffing::Stuffing;
use protocol_runtime::zeros::zero_filled;
use protocol_spec::ir::{
    DirectionRule, Frame, HeaderValue, Length, PacketKind, Prim, Protocol, Role, Transport,
};

use crate::error::DecodeIssue;
use crate::layout::word_field;
use crate::model::{Fields, Value};
use crate::payload::{ReadFail, read_payload};
use crate::value::truncate;

/// What the frames of a format carry, as generated code decodes them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dispatch {
    /// A command chosen by the header's dispatch key (the first frame format: `Packet`).
    Key,
    /// A command chosen by the CAN id (a CAN frame format after the first: `<Name>Packet`).
    CanId,
    /// One struct (index into the protocol's structs), every frame (`<Name>Packet`).
    Message(usize),
    /// Raw payload bytes: no commands, no struct.
    None,
}

/// What frame format `fi` of `p` carries.
pub fn dispatch_of(p: &Protocol, fi: usize) -> Dispatch {
    let Some(f) = p.frames.get(fi) else {
        return Dispatch::None;
    };
    let keyed = p
        .frames
        .first()
        .is_some_and(|first| !first.dispatch.is_empty());
    if let (Some(si), true) = (f.message, fi > 0 || !keyed) {
        return Dispatch::Message(si);
    }
    if !keyed {
        Dispatch::None
    } else if fi == 0 || f.packet == PacketKind::Commands {
        Dispatch::Key
    } else if matches!(f.transport, Transport::Can { .. }) && p.directions.is_empty() {
        Dispatch::CanId
    } else {
        Dispatch::None
    }
}

/// True for the header value that holds a CAN frame's id: it is shown as the frame's `can_id`.
pub fn is_can_id(f: &Frame, v: &HeaderValue) -> bool {
    matches!(f.transport, Transport::Can { .. }) && v.name == "can_id"
}

/// The value of the acknowledgement flag that marks an acknowledgement.
pub fn ack_value(f: &Frame, flag: usize) -> u64 {
    match f.values.get(flag).map(|v| &v.role) {
        Some(Role::Ack(equals)) => *equals,
        // Validation gives the flag the role `Ack`; 1 is the usual flag.
        _ => 1,
    }
}

/// The largest acknowledgement data.
pub fn ack_max(f: &Frame, ack_header_len: usize) -> usize {
    f.max_len()
        .saturating_sub(ack_header_len)
        .saturating_sub(f.trailer_len)
}

/// The payload's byte stuffing, as the runtime applies it.
pub fn stuffing(f: &Frame) -> Option<Stuffing<'_>> {
    f.stuffing.as_ref().map(|(after, insert)| Stuffing {
        after,
        insert: *insert,
    })
}

/// A header value as generated header structs hold it: `value as T`, or `value != 0`.
fn header_value(v: &HeaderValue, raw: u64) -> Value {
    if v.prim == Prim::Bool {
        Value::Bool(raw != 0)
    } else {
        Value::UInt(truncate(v.prim, raw))
    }
}

/// The HEADER_LEN generated `header_value` reports when a header value is out of the frame.
fn header_truncated(p: &Protocol, frame: &[u8]) -> DecodeIssue {
    DecodeIssue::Frame(DecodeError::Truncated {
        needed: p.frames.first().map_or(0, |f| f.header_len),
        available: frame.len(),
    })
}

/// The user-set header values of a frame, in wire order.
fn read_header(p: &Protocol, f: &Frame, frame: &[u8]) -> Result<Fields, DecodeIssue> {
    let mut out = Fields::new();
    for v in f
        .values
        .iter()
        .filter(|v| matches!(v.role, Role::User { .. }))
    {
        let raw = word_field(v)
            .read(frame)
            .ok_or_else(|| header_truncated(p, frame))?;
        if !is_can_id(f, v) {
            out.insert(v.name.clone(), header_value(v, raw));
        }
    }
    if let Some(t) = &f.flag_trailer {
        let present = flag_trailer_len(f, frame);
        let bytes = frame.get(frame.len().saturating_sub(present)..);
        let value = match bytes {
            Some(b) if present > 0 => Value::Bytes(b.to_vec()),
            _ => Value::Null,
        };
        out.insert(t.name.clone(), value);
    }
    Ok(out)
}

/// Bytes of the wider length present after the header of `frame` (0 without one, or when the
/// length field does not hold its marker), as generated code's `LAYOUT.extension_len`.
pub fn extension_len(f: &Frame, frame: &[u8]) -> usize {
    match (&f.length_extension, &f.length) {
        (Some(e), Length::Field { value, .. })
            if word_field(&f.values[*value]).read(frame) == Some(e.marker) =>
        {
            e.len
        }
        _ => 0,
    }
}

/// Bytes of the flag trailer present at the end of `frame` (0 without one, or with its flag
/// clear), as generated code's `LAYOUT.flag_trailer_len`.
pub fn flag_trailer_len(f: &Frame, frame: &[u8]) -> usize {
    match &f.flag_trailer {
        Some(t)
            if word_field(&f.values[t.flag])
                .read(frame)
                .is_some_and(|v| v != 0) =>
        {
            t.len
        }
        _ => 0,
    }
}

/// A decoded frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Decoded {
    /// Index of the frame format.
    pub format: usize,
    /// Index of the command (`None` for an acknowledgement or a format without commands).
    pub command: Option<usize>,
    /// Index of the direction (`None` when the spec has none).
    pub direction: Option<usize>,
    /// True for an acknowledgement (a frame without command whose payload is its data).
    pub ack: bool,
    /// The dispatch key's values (the CAN id for a CAN frame).
    pub id: Vec<u64>,
    /// The CAN id, for a CAN frame.
    pub can_id: Option<u64>,
    /// The user-set header values, in wire order.
    pub header: Fields,
    /// The payload: a struct (empty for a command without payload), or bytes (an
    /// acknowledgement's data, a format without commands).
    pub payload: Value,
}

/// Lowercase hex of some bytes.
pub fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// Bytes from hex text: whitespace, `0x` prefixes and `:`/`,` separators are ignored.
pub fn parse_hex(text: &str) -> Option<Vec<u8>> {
    parse_hex_located(text).ok()
}

/// Where hex text stops being hex ([`parse_hex_located`]): a line and a column (both from
/// 1, the column in characters) and what is wrong there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HexError {
    /// Line of the offending character.
    pub line: usize,
    /// Column of the offending character.
    pub column: usize,
    /// What is wrong there.
    pub what: String,
}

impl std::fmt::Display for HexError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "line {}, column {}: {}",
            self.line, self.column, self.what
        )
    }
}

impl std::error::Error for HexError {}

/// Bytes from hex text, as [`parse_hex`], or where and why the text is not hex.
///
/// # Errors
///
/// A [`HexError`] at the first character that is neither a hex digit nor a separator, or at
/// the last digit when the digits do not pair up.
pub fn parse_hex_located(text: &str) -> Result<Vec<u8>, HexError> {
    let mut bytes = Vec::new();
    // The first digit of the pending pair, and where it stands.
    let mut high: Option<(u8, usize, usize)> = None;
    for (l, line) in text.lines().enumerate() {
        let chars: Vec<char> = line.chars().collect();
        let mut c = 0;
        while let Some(&ch) = chars.get(c) {
            let word_start = c == 0 || chars.get(c - 1).is_some_and(|&p| is_separator(p));
            if word_start && ch == '0' && matches!(chars.get(c + 1), Some('x' | 'X')) {
                c += 2;
                continue;
            }
            if !is_separator(ch) {
                let Some(d) = ch.to_digit(16) else {
                    return Err(HexError {
                        line: l + 1,
                        column: c + 1,
                        what: format!("`{ch}` is not a hex digit"),
                    });
                };
                match high.take() {
                    None => high = Some((d as u8, l + 1, c + 1)),
                    Some((h, _, _)) => bytes.push((h << 4) | d as u8),
                }
            }
            c += 1;
        }
    }
    match high {
        None => Ok(bytes),
        Some((_, line, column)) => Err(HexError {
            line,
            column,
            what: "the last hex digit has no pair (an odd number of digits)".into(),
        }),
    }
}

fn is_separator(c: char) -> bool {
    c.is_whitespace() || c == ',' || c == ':'
}

/// The payload bytes of a frame.
fn payload_of<'b>(f: &Frame, frame: &'b [u8]) -> Result<&'b [u8], DecodeIssue> {
    let trailer = f.trailer_len + flag_trailer_len(f, frame);
    let header = f.header_len + extension_len(f, frame);
    frame
        .get(header..frame.len().saturating_sub(trailer))
        .ok_or(DecodeIssue::Frame(DecodeError::Truncated {
            needed: f.header_len + f.trailer_len,
            available: frame.len(),
        }))
}

/// The direction of a header of frame format `f`, testing the rules in order (`request`
/// first), each on `f`'s own direction field.
fn direction_of(p: &Protocol, f: &Frame, raw: &dyn Fn(usize) -> Option<u64>) -> Option<usize> {
    p.directions.iter().position(|d| match &d.rule.in_frame(f) {
        DirectionRule::InSet { value, set } => {
            let (Some(v), Some(a)) = (f.values.get(*value), p.addresses.get(*set)) else {
                return false;
            };
            let x = raw(*value).map(|r| truncate(v.prim, r));
            x.is_some_and(|x| truncate(v.prim, a.first) <= x && x <= truncate(v.prim, a.last))
        }
        // The decoder is given it: no header tells it.
        DirectionRule::Given => false,
        DirectionRule::Equals { value, equals } => {
            let Some(v) = f.values.get(*value) else {
                return false;
            };
            let x = raw(*value).map(|r| {
                if v.prim == Prim::Bool {
                    u64::from(r != 0)
                } else {
                    truncate(v.prim, r)
                }
            });
            x == Some(*equals)
        }
    })
}

/// Decodes the payload of struct `si` (or an empty one) for `command`, as `read_payload` and
/// `from_bytes` do.
fn read_struct_payload(
    p: &Protocol,
    si: Option<usize>,
    command: &str,
    payload: &[u8],
) -> Result<Value, DecodeIssue> {
    let Some(si) = si else {
        if payload.is_empty() {
            return Ok(Value::Struct(Fields::new()));
        }
        return Err(DecodeIssue::PayloadLength {
            command: command.to_string(),
            expected: 0,
            actual: payload.len(),
        });
    };
    read_payload(p, si, payload)
        .map(Value::Struct)
        .map_err(|e| match e {
            ReadFail::Runtime(DecodeError::PayloadLength { expected, actual }) => {
                DecodeIssue::PayloadLength {
                    command: command.to_string(),
                    expected,
                    actual,
                }
            }
            ReadFail::Runtime(other) => DecodeIssue::Frame(other),
            ReadFail::Enum {
                field,
                enum_index,
                value,
            } => DecodeIssue::InvalidEnum {
                command: command.to_string(),
                field,
                enum_name: p.enums[enum_index].name.clone(),
                value,
            },
        })
}

/// Decodes a frame of format `fi` that the engine accepted (for a CAN format: its virtual
/// frame), as the generated packet of the format does; `given` is the direction the decoder is
/// given, for a spec whose header does not tell it (as generated `from_<direction>_frame`).
pub fn decode(
    p: &Protocol,
    fi: usize,
    frame: &[u8],
    given: Option<usize>,
) -> Result<Decoded, DecodeIssue> {
    let f = &p.frames[fi];
    let read = |i: usize| f.values.get(i).and_then(|v| word_field(v).read(frame));
    let mut out = Decoded {
        format: fi,
        command: None,
        direction: None,
        ack: false,
        id: Vec::new(),
        can_id: None,
        header: Fields::new(),
        payload: Value::Null,
    };
    if let Some(v) = f.values.iter().find(|v| is_can_id(f, v)) {
        // The whole identifier word, as generated code takes `CanFrame::id`: bits above the
        // id's width (which no bus delivers) make an unknown command, not another one.
        let mut whole = word_field(v);
        whole.shift = 0;
        whole.width = whole.size.saturating_mul(8);
        out.can_id = whole.read(frame);
    }
    match dispatch_of(p, fi) {
        Dispatch::None => {
            out.header = read_header(p, f, frame)?;
            out.payload = Value::Bytes(payload_of(f, frame)?.to_vec());
        }
        Dispatch::Message(si) => {
            let payload = payload_of(f, frame)?;
            out.header = read_header(p, f, frame)?;
            out.payload = read_struct_payload(p, Some(si), &f.name, payload)?;
        }
        Dispatch::CanId => {
            let can_id = out.can_id.unwrap_or(0);
            out.id = vec![can_id];
            let ci = p
                .commands
                .iter()
                .position(|c| c.can_id == Some(can_id))
                .ok_or(DecodeIssue::UnknownCommand {
                    id: vec![can_id],
                    key: can_id,
                })?;
            out.command = Some(ci);
            let payload = payload_of(f, frame)?;
            out.header = read_header(p, f, frame)?;
            let c = &p.commands[ci];
            out.payload =
                read_struct_payload(p, c.payloads.first().copied().flatten(), &c.name, payload)?;
        }
        Dispatch::Key => {
            out.header = read_header(p, f, frame)?;
            if let Some((flag, ack_header_len)) = f.ack {
                if read(flag).ok_or_else(|| header_truncated(p, frame))? == ack_value(f, flag) {
                    let end = if f.bare_len.is_some() && frame.len() == ack_header_len {
                        frame.len()
                    } else {
                        frame.len().saturating_sub(f.trailer_len)
                    };
                    let data = frame.get(ack_header_len..end).ok_or(DecodeIssue::Frame(
                        DecodeError::Truncated {
                            needed: ack_header_len,
                            available: frame.len(),
                        },
                    ))?;
                    let max = ack_max(f, ack_header_len);
                    if data.len() > max {
                        return Err(DecodeIssue::Frame(DecodeError::PayloadLength {
                            expected: max,
                            actual: data.len(),
                        }));
                    }
                    out.ack = true;
                    out.payload = Value::Bytes(data.to_vec());
                    return Ok(out);
                }
            }
            if p.directions_given() {
                let d = given.filter(|&d| d < p.directions.len()).ok_or_else(|| {
                    DecodeIssue::DirectionNotGiven {
                        directions: p.directions.iter().map(|d| d.name.clone()).collect(),
                    }
                })?;
                out.direction = Some(d);
                if let Some((si, start)) = p.directions[d].message {
                    let payload = frame.get(start..frame.len().saturating_sub(f.trailer_len));
                    let payload = payload.ok_or(DecodeIssue::Frame(DecodeError::Truncated {
                        needed: start + f.trailer_len,
                        available: frame.len(),
                    }))?;
                    out.payload = read_struct_payload(p, Some(si), &p.directions[d].name, payload)?;
                    return Ok(out);
                }
            }
            decode_command(p, f, frame, &read, &mut out)?;
        }
    }
    Ok(out)
}

/// The dispatch key, command, stuffing, direction and payload of a first-format frame.
fn decode_command(
    p: &Protocol,
    f: &Frame,
    frame: &[u8],
    read: &dyn Fn(usize) -> Option<u64>,
    out: &mut Decoded,
) -> Result<(), DecodeIssue> {
    let mut key = 0u64;
    for &vi in &f.dispatch {
        let v = &f.values[vi];
        let raw = read(vi).ok_or_else(|| header_truncated(p, frame))?;
        let x = truncate(v.prim, raw);
        out.id.push(x);
        key = key.checked_shl(v.width).unwrap_or(0) | x;
    }
    // The commands the format carries (a format after the first: those whose id fits).
    let ci = p
        .commands
        .iter()
        .enumerate()
        .position(|(ci, c)| {
            f.commands.contains(&ci)
                && c.id.len() == out.id.len()
                && c.id
                    .iter()
                    .zip(&out.id)
                    .zip(&f.dispatch)
                    .all(|((a, b), &vi)| truncate(f.values[vi].prim, *a) == *b)
        })
        .ok_or_else(|| DecodeIssue::UnknownCommand {
            id: out.id.clone(),
            key,
        })?;
    out.command = Some(ci);
    let c = &p.commands[ci];
    let stuffed = payload_of(f, frame)?;
    let mut unstuffed = vec![0u8; f.payload_max];
    let payload = match stuffing(f) {
        Some(s) => s
            .unstuff(stuffed, &mut unstuffed)
            .map_err(DecodeIssue::Frame)?,
        None => stuffed,
    };
    let slot = if let Some(d) = out.direction.filter(|_| p.directions_given()) {
        d
    } else if p.directions.is_empty() {
        0
    } else {
        let d = direction_of(p, f, read).ok_or_else(|| DecodeIssue::UnknownDirection {
            command: c.name.clone(),
        })?;
        out.direction = Some(d);
        d
    };
    let si = c.payloads.get(slot).copied().flatten();
    // A format without extension fields carries exactly the fields before them, the others
    // read as zero; with trailing-zero truncation a short payload is zero-filled to its
    // struct's size.
    let base = si.and_then(|si| p.structs[si].base_size.filter(|_| !f.extensions));
    if let Some(base) = base.filter(|&b| b != payload.len()) {
        return Err(DecodeIssue::PayloadLength {
            command: c.name.clone(),
            expected: base,
            actual: payload.len(),
        });
    }
    let mut filled = vec![0u8; f.payload_max.max(si.map_or(0, |si| p.structs[si].size))];
    let payload = match si.filter(|_| f.truncate_zeros || base.is_some()) {
        Some(si) => {
            zero_filled(payload, p.structs[si].size, &mut filled).map_err(DecodeIssue::Frame)?
        }
        None => payload,
    };
    out.payload = read_struct_payload(p, si, &c.name, payload)?;
    Ok(())
}
