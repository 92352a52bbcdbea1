//! Reading a payload struct into a [`Value`], as the generated `Payload::read` and `from_bytes` do.

use protocol_runtime::{DecodeError, Reader, bitstream, field, packed, text};
use protocol_spec::ir::{BitMember, BitOrder, Enum, Prim, Protocol, Scale, ValueType};

use super::{kinds, signed_value, variant};
use crate::model::{Fields, Value};
use crate::names::Names;
use crate::value::{read_scalar, truncate};

/// Why a payload could not be read.
#[derive(Debug, Clone, PartialEq)]
pub enum ReadFail {
    /// A runtime error (the payload ended early, sizes that disagree, ...).
    Runtime(DecodeError),
    /// A field holds no variant of its enum.
    Enum {
        /// Path of the field.
        field: String,
        /// Index of the enum.
        enum_index: usize,
        /// The value as the runtime reports it (`raw as u64`).
        value: u64,
    },
}

impl From<DecodeError> for ReadFail {
    fn from(e: DecodeError) -> Self {
        ReadFail::Runtime(e)
    }
}

/// Reads exactly `bytes` as struct `si`, as generated `Payload::from_bytes` does: an early
/// end is a `PayloadLength` with the struct's smallest size, bytes left over a
/// `PayloadLength` with the bytes read. A carrying field shows the packet it carries in
/// message `carry` (`None`: its bytes).
///
/// # Errors
/// [`ReadFail`] as generated code fails on the same bytes.
pub fn read_payload(
    p: &Protocol,
    names: &Names,
    si: usize,
    bytes: &[u8],
    carry: Option<usize>,
) -> Result<Fields, ReadFail> {
    let mut r = Reader::new(bytes);
    let value = read_struct(p, (names, carry), si, &mut r, &Path::Root).map_err(|e| match e {
        ReadFail::Runtime(DecodeError::Truncated { .. }) => {
            ReadFail::Runtime(DecodeError::PayloadLength {
                expected: p.structs[si].min_size,
                actual: bytes.len(),
            })
        }
        other => other,
    })?;
    r.finish()?;
    Ok(value)
}

/// Where a value stands in the payload (`att.q[2]`), built on the stack as the read descends
/// and spelled out only for an error that names it: a read that succeeds formats no path.
#[derive(Clone, Copy)]
pub(super) enum Path<'a> {
    /// The payload struct itself.
    Root,
    /// Field `name` of the struct at the parent path.
    Field(&'a Path<'a>, &'a str),
    /// Element `i` of the array at the parent path.
    Index(&'a Path<'a>, usize),
}

impl std::fmt::Display for Path<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Path::Root => Ok(()),
            Path::Field(Path::Root, name) => f.write_str(name),
            Path::Field(parent, name) => write!(f, "{parent}.{name}"),
            Path::Index(parent, i) => write!(f, "{parent}[{i}]"),
        }
    }
}

/// Reads struct `si` at the reader's position (`Payload::read`), its carrying fields shown as
/// the packets they carry in message `carry`.
fn read_struct(
    p: &Protocol,
    (names, carry): (&Names, Option<usize>),
    si: usize,
    r: &mut Reader<'_>,
    path: &Path<'_>,
) -> Result<Fields, ReadFail> {
    let s = &p.structs[si];
    let mut out = Fields::with_capacity(s.fields.len());
    // Per field read: a copy of the reader at its start, and the position after it.
    let mut spans: Vec<(Reader<'_>, usize)> = Vec::with_capacity(s.fields.len());
    let at = kinds::ReadAt {
        names,
        size: s.size,
        path,
        owner: None,
        carry,
    };
    for ((i, f), fnames) in s.fields.iter().enumerate().zip(names.fields(si)) {
        let start = r.clone();
        kinds::of(&f.kind).read_in(p, s, i, fnames, &spans, r, &at, &mut out)?;
        spans.push((start, r.position()));
    }
    if let Some(carry) = carry.filter(|_| !s.carries.is_empty()) {
        super::carried::show(p, names, s, carry, &mut out);
    }
    Ok(out)
}

/// Every byte left but the last `keep`, at most `max` (`Bytes::<max>::read_rest_but`).
pub(super) fn read_rest_bytes(
    r: &mut Reader<'_>,
    max: usize,
    keep: usize,
) -> Result<Vec<u8>, ReadFail> {
    let start = r.position();
    let rest = field::rest_but(r, keep);
    if rest.len() > max {
        return Err(ReadFail::Runtime(DecodeError::PayloadLength {
            expected: start + max + keep,
            actual: start + r.remaining(),
        }));
    }
    r.skip(rest.len())?;
    Ok(rest.to_vec())
}

pub(super) fn read_member(
    p: &Protocol,
    m: &BitMember,
    word: u64,
    path: &Path<'_>,
) -> Result<Value, ReadFail> {
    read_member_bits(p, m, field::get_bits(word, m.shift, m.width), path)
}

/// Member `m` from its unsigned `bits` (of a word or a bit stream): a flag, an enum, an
/// integer (sign-extended from the member's width when signed), or a scaled value's physical
/// value computed from that integer.
pub(super) fn read_member_bits(
    p: &Protocol,
    m: &BitMember,
    bits: u64,
    path: &Path<'_>,
) -> Result<Value, ReadFail> {
    let signed = m.is_signed().then(|| bitstream::sign_extend(bits, m.width));
    Ok(match (m.enum_index, &m.scale, signed) {
        (Some(ei), _, _) => {
            let e = &p.enums[ei];
            enum_value(e, ei, truncate(e.prim, bits), path)?
        }
        (None, Some(sc), Some(i)) => physical_value(i as f64, sc)?,
        (None, Some(sc), None) => physical_value(bits as f64, sc)?,
        (None, None, _) if m.prim == Prim::Bool => Value::Bool(bits != 0),
        (None, None, Some(i)) => Value::Int(i),
        (None, None, None) => Value::from(truncate(m.prim, bits)),
    })
}

pub(super) fn read_elem(
    p: &Protocol,
    (names, carry): (&Names, Option<usize>),
    ty: &ValueType,
    r: &mut Reader<'_>,
    path: &Path<'_>,
) -> Result<Value, ReadFail> {
    Ok(match ty {
        ValueType::Scalar {
            scalar,
            scale: None,
        } => read_scalar(r, *scalar)?.to_value(),
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => physical_value(read_scalar(r, *scalar)?.as_f64(), sc)?,
        ValueType::Struct(si) => Value::Struct(read_struct(p, (names, carry), *si, r, path)?),
        ValueType::Enum(ei, scalar) => {
            let raw = read_scalar(r, *scalar)?;
            enum_value(
                &p.enums[*ei],
                *ei,
                truncate(scalar.prim, raw.as_u64()),
                path,
            )?
        }
        ValueType::Text(n) => text_value(r.take(*n)?),
    })
}

/// A NUL-padded text's value: its text as a string when the bytes are canonical (the
/// runtime's `text::is_canonical`), else every byte, so that encoding gives them back.
fn text_value(bytes: &[u8]) -> Value {
    match core::str::from_utf8(text::text_of(bytes)) {
        Ok(s) if text::is_canonical(bytes) => Value::from(s.to_string()),
        _ => Value::Array(bytes.iter().map(|&b| Value::UInt(u64::from(b))).collect()),
    }
}

/// The physical value of a scaled raw value, by the runtime's field rules, in the field's
/// Rust type (as generated code computes it).
fn physical_value(raw: f64, sc: &Scale) -> Result<Value, ReadFail> {
    Ok(match sc.physical {
        Prim::F32 => {
            let mut physical = field::to_physical(raw as f32, sc.factor as f32, sc.offset as f32);
            if let Some((lo, hi)) = sc.clamp {
                physical = field::check_clamp(physical, lo as f32, hi as f32)?;
            }
            Value::F32(physical)
        }
        _ => {
            let mut physical = field::to_physical(raw, sc.factor, sc.offset);
            if let Some((lo, hi)) = sc.clamp {
                physical = field::check_clamp(physical, lo, hi)?;
            }
            Value::F64(physical)
        }
    })
}

/// A bit-packed array's elements, each read by the runtime's `get_packed` from the array's
/// bytes.
pub(super) fn read_packed(
    r: &mut Reader<'_>,
    size: usize,
    count: usize,
    bits: u32,
    order: BitOrder,
    scale: Option<&Scale>,
) -> Result<Value, ReadFail> {
    let bytes = r.take(size)?;
    let mut items = Vec::with_capacity(count);
    for i in 0..count {
        let raw = packed::get_packed(bytes, i, bits, order);
        items.push(match scale {
            None => Value::UInt(raw),
            Some(sc) => physical_value(raw as f64, sc)?,
        });
    }
    Ok(Value::Array(items))
}

/// The value of an enum's raw value (bits truncated to the enum's type).
fn enum_value(e: &Enum, ei: usize, raw: u64, path: &Path<'_>) -> Result<Value, ReadFail> {
    if let Some(v) = variant(e, raw) {
        return Ok(Value::from(v.name.clone()));
    }
    let signed = signed_value(e.prim, raw);
    if e.unknown.unknown(raw).is_ok() {
        return Ok(match signed {
            Some(i) => Value::Int(i),
            None => Value::UInt(raw),
        });
    }
    Err(ReadFail::Enum {
        field: path.to_string(),
        enum_index: ei,
        // Generated code reports `raw as u64`, which sign-extends a signed raw value.
        value: signed.map_or(raw, |i| i as u64),
    })
}

/// A register's value from exactly its bytes, read as a struct field of its type is (a
/// scalar, scaled or not); `None` for bytes of another length.
pub(crate) fn read_register(ty: &ValueType, bytes: &[u8]) -> Option<Value> {
    let ValueType::Scalar { scalar, scale } = ty else {
        return None;
    };
    let mut r = Reader::new(bytes);
    let raw = read_scalar(&mut r, *scalar).ok()?;
    r.finish().ok()?;
    match scale {
        None => Some(raw.to_value()),
        Some(sc) => physical_value(raw.as_f64(), sc).ok(),
    }
}
