//! Whole frames between the wire and [`Value`](crate::Value)s, in the order the generated packets
//! take them (`Packet::from_frame`, and the `<Name>Packet` of a CAN or message-only frame format,
//! in `protocol-codegen/src/codegen/dispatch/`), so that both report the same error for the same
//! bytes. Encoding lives in [`encode`].
//!
//! Every packet rule (which bytes are the payload, acknowledgements, the dispatch key, the
//! direction the header tells, stuffing, zero-fill, the fields a format carries) is the
//! runtime's [`PacketRules`], and what a format carries is the IR's packet kind
//! ([`carries`]); verifying and sealing frames is the runtime's
//! [`FrameLayout`](protocol_runtime::FrameLayout) business. This module owns what generated code
//! owns beside them: which command a key names and which struct it carries in a direction, the
//! header values, and the payload's values.

mod encode;

pub use encode::{encode, frame_direction};

use protocol_runtime::DecodeError;
use protocol_runtime::decoder::frame_body;
use protocol_runtime::rules::PacketRules;
use protocol_spec::ir::{Frame, HeaderValue, Prim, Protocol, Role, Transport};
use protocol_spec::rules::{Carries, carries};

use crate::error::DecodeIssue;
use crate::layout::word_field;
use crate::model::{Fields, Value};
use crate::names::Names;
use crate::payload::{ReadFail, carry_of, read_payload};
use crate::value::truncate;

/// True for the header value that holds a CAN frame's id: it is shown as the frame's `can_id`.
pub fn is_can_id(f: &Frame, v: &HeaderValue) -> bool {
    matches!(f.transport, Transport::Can { .. }) && v.name == "can_id"
}

/// The bytes of struct `si` that format `f` carries, for a format without extension fields
/// (`None`: all of them), as [`PacketRules::filled`] and the runtime's `Body::Command` take it.
fn carried(p: &Protocol, f: &Frame, si: Option<usize>) -> Option<usize> {
    si.and_then(|si| p.structs[si].base_size.filter(|_| !f.extensions))
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

/// The user-set header values of a frame of format `fi`, in wire order.
fn read_header(
    p: &Protocol,
    (names, fi, direction): (&Names, usize, Option<usize>),
    f: &Frame,
    rules: &PacketRules<'_>,
    frame: &[u8],
) -> Result<Fields, DecodeIssue> {
    let mut out = Fields::new();
    // Values after the payload lie back from the end of the body (the frame without its flag
    // trailer); the others from its start, the same in the frame and the body.
    let body = frame_body(rules.layout, frame);
    for (vi, v) in f
        .values
        .iter()
        .enumerate()
        .filter(|(_, v)| matches!(v.role, Role::User { .. }))
    {
        let raw = word_field(v)
            .read(body)
            .ok_or_else(|| header_truncated(p, frame))?;
        if !is_can_id(f, v) {
            out.push(names.value(fi, direction, vi), header_value(v, raw));
        }
    }
    if let Some(name) = names.trailer(fi) {
        let present = rules.layout.flag_trailer_len(frame);
        let bytes = frame.get(frame.len().saturating_sub(present)..);
        let value = match bytes {
            Some(b) if present > 0 => Value::Bytes(b.to_vec()),
            _ => Value::Null,
        };
        out.push(name, value);
    }
    Ok(out)
}

/// The CAN id of a frame of a CAN format: the whole identifier word, as generated code takes
/// `CanFrame::id`; for an identifier split into members (`can_id_bits`), the word they share.
fn can_id(f: &Frame, frame: &[u8]) -> Option<u64> {
    if !matches!(f.transport, Transport::Can { .. }) {
        return None;
    }
    let v = f
        .values
        .iter()
        .find(|v| is_can_id(f, v))
        .or_else(|| f.values.first())?;
    let word = word_field(v);
    word.bits(0, word.size.saturating_mul(8)).read(frame)
}

/// Bytes of work room a frame decodes in without a heap buffer: the payload buffers of a
/// format whose payloads fit (MAVLink's 255 bytes, CAN's 64) live on the stack.
const STACK_ROOM: usize = 256;

/// Zeroed room for `len` bytes: `stack` when it is large enough, else `heap`, zeroed to `len`.
fn room<'b>(stack: &'b mut [u8; STACK_ROOM], heap: &'b mut Vec<u8>, len: usize) -> &'b mut [u8] {
    if len <= STACK_ROOM {
        &mut stack[..len]
    } else {
        heap.resize(len, 0);
        heap
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

/// A payload of `command` that is not as long as its struct says, as generated code's
/// `PayloadLength` names it; the runtime's other refusals as they are.
fn payload_issue(command: &str, e: DecodeError) -> DecodeIssue {
    match e {
        DecodeError::PayloadLength { expected, actual } => DecodeIssue::PayloadLength {
            command: command.to_string(),
            expected,
            actual,
        },
        other => DecodeIssue::Frame(other),
    }
}

/// Decodes the payload of struct `si` (or an empty one) for `command`, as `read_payload` and
/// `from_bytes` do, a carried packet shown as read in message `carry`.
pub(crate) fn read_struct_payload(
    p: &Protocol,
    names: &Names,
    si: Option<usize>,
    command: &str,
    payload: &[u8],
    carry: Option<usize>,
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
    read_payload(p, names, si, payload, carry)
        .map(Value::Struct)
        .map_err(|e| match e {
            ReadFail::Runtime(e) => payload_issue(command, e),
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
/// frame) under the format's packet `rules`, as the generated packet of the format does;
/// `given` is the direction the decoder is given, for a spec whose header does not tell it (as
/// generated `from_<direction>_frame`). With `packets`, a carrying field shows the packet it
/// carries, else its bytes.
pub fn decode(
    p: &Protocol,
    (names, packets): (&Names, bool),
    fi: usize,
    rules: &PacketRules<'_>,
    frame: &[u8],
    given: Option<usize>,
) -> Result<Decoded, DecodeIssue> {
    // A direction with fields of its own reads the first format by its own layout, which
    // `rules` hold (the codec chose them by the same direction).
    let own = given.filter(|_| p.directions_given());
    let Some(f) = p.frame_in(fi, own) else {
        return Err(DecodeIssue::Frame(DecodeError::Frame(
            protocol_runtime::Reject::BadHeader,
        )));
    };
    let carry = |direction| carry_of(p, direction).filter(|_| packets);
    let mut out = Decoded {
        format: fi,
        command: None,
        direction: None,
        ack: false,
        id: Vec::new(),
        can_id: can_id(f, frame),
        header: Fields::new(),
        payload: Value::Null,
    };
    let (mut stack, mut heap) = ([0u8; STACK_ROOM], Vec::new());
    let scratch = room(&mut stack, &mut heap, rules.max_payload);
    match carries(f) {
        Carries::Bytes => {
            out.header = read_header(p, (names, fi, own), f, rules, frame)?;
            let payload = rules.payload(frame, scratch).map_err(DecodeIssue::Frame)?;
            out.payload = Value::Bytes(payload.to_vec());
        }
        Carries::Struct(si) => {
            let payload = rules.payload(frame, scratch).map_err(DecodeIssue::Frame)?;
            out.header = read_header(p, (names, fi, own), f, rules, frame)?;
            out.payload = read_struct_payload(p, names, Some(si), &f.name, payload, carry(None))?;
        }
        Carries::CanCommand => {
            let key = rules.key(frame).map_err(DecodeIssue::Frame)?;
            out.id = vec![key];
            let ci = p
                .commands
                .iter()
                .position(|c| c.can_id == Some(key))
                .ok_or(DecodeIssue::UnknownCommand { id: vec![key], key })?;
            out.command = Some(ci);
            let payload = rules.payload(frame, scratch).map_err(DecodeIssue::Frame)?;
            out.header = read_header(p, (names, fi, own), f, rules, frame)?;
            let c = &p.commands[ci];
            out.payload = read_struct_payload(
                p,
                names,
                c.payloads.first().copied().flatten(),
                &c.name,
                payload,
                carry(None),
            )?;
        }
        Carries::Command => {
            out.header = read_header(p, (names, fi, own), f, rules, frame)?;
            if let Some(data) = rules.ack_data(frame).map_err(DecodeIssue::Frame)? {
                out.ack = true;
                out.payload = Value::Bytes(data.to_vec());
                return Ok(out);
            }
            if p.directions_given() {
                let d = given.filter(|&d| d < p.directions.len()).ok_or_else(|| {
                    DecodeIssue::DirectionNotGiven {
                        directions: p.directions.iter().map(|d| d.name.clone()).collect(),
                    }
                })?;
                out.direction = Some(d);
                if let Some((si, start)) = p.directions[d].message {
                    let payload = rules
                        .payload_from(frame, start, scratch)
                        .map_err(DecodeIssue::Frame)?;
                    let name = &p.directions[d].name;
                    out.payload = read_struct_payload(p, names, Some(si), name, payload, None)?;
                    return Ok(out);
                }
            }
            decode_command(p, (names, packets), f, rules, frame, &mut out)?;
        }
    }
    Ok(out)
}

/// The command a frame's dispatch key names, its direction (the given one, or the one its
/// header tells) and its payload, zero-filled as the format's rules say (a carried packet
/// shown with `packets`).
fn decode_command(
    p: &Protocol,
    (names, packets): (&Names, bool),
    f: &Frame,
    rules: &PacketRules<'_>,
    frame: &[u8],
    out: &mut Decoded,
) -> Result<(), DecodeIssue> {
    for i in 0..rules.key.len() {
        out.id
            .push(rules.key_value(frame, i).map_err(DecodeIssue::Frame)?);
    }
    let key = rules.key(frame).map_err(DecodeIssue::Frame)?;
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
    let (mut stack, mut heap) = ([0u8; STACK_ROOM], Vec::new());
    let unstuffed = room(&mut stack, &mut heap, rules.max_payload);
    let payload = rules
        .payload(frame, unstuffed)
        .map_err(DecodeIssue::Frame)?;
    let slot = match out.direction {
        Some(given) => given,
        None if rules.directions.is_empty() => 0,
        None => {
            let d = rules.direction(frame).map_err(|e| match e {
                DecodeError::UnknownDirection => DecodeIssue::UnknownDirection {
                    command: c.name.clone(),
                },
                other => DecodeIssue::Frame(other),
            })?;
            out.direction = Some(d);
            d
        }
    };
    let si = c.payloads.get(slot).copied().flatten();
    let size = rules.max_payload.max(si.map_or(0, |si| p.structs[si].size));
    let (mut stack, mut heap) = ([0u8; STACK_ROOM], Vec::new());
    let filled = room(&mut stack, &mut heap, size);
    let payload = match si {
        Some(si) => rules
            .filled(payload, p.structs[si].size, carried(p, f, Some(si)), filled)
            .map_err(|e| payload_issue(&c.name, e))?,
        None => payload,
    };
    let carry = carry_of(p, out.direction).filter(|_| packets);
    out.payload = read_struct_payload(p, names, si, &c.name, payload, carry)?;
    Ok(())
}
