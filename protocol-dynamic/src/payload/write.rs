//! Writing a payload struct from a [`Value`], as the generated `Payload::write` does. Values that
//! generated code cannot even hold (a number too large for its type, bytes beyond a field's
//! `max`, an unknown variant of a rejecting enum) are refused with the path of the value.

use protocol_runtime::{EncodeError, Writer, field, text};
use protocol_spec::ir::{BitMember, Enum, Prim, Protocol, Scalar, Scale, Struct, ValueType};

use super::{join, kinds, signed_value, variant};
use crate::error::EncodeIssue;
use crate::frame::parse_hex;
use crate::model::{Fields, Value};
use crate::value::{NumError, bits_as_f64, truncate, value_bits, value_f32, value_f64, write_bits};

pub(super) fn issue(path: &str, e: NumError) -> EncodeIssue {
    match e {
        NumError::Type(m) | NumError::Range(m) => EncodeIssue::new(path, m),
    }
}

/// Writes struct `si` from a struct value (a payload, or a nested struct of one); a carrying
/// field may give the packet it carries in message `carry` (`None`: only its bytes).
///
/// # Errors
/// [`EncodeIssue`] naming the first missing, ill-typed, out-of-range or unknown value.
pub fn write_payload(
    p: &Protocol,
    si: usize,
    v: &Value,
    w: &mut Writer<'_>,
    path: &str,
    carry: Option<usize>,
) -> Result<(), EncodeIssue> {
    let s = &p.structs[si];
    let obj = v.as_struct().ok_or_else(|| {
        EncodeIssue::new(path, format!("expected an object (struct `{}`)", s.name))
    })?;
    check_keys(s, obj, path)?;
    let sealed;
    let obj = match carry.filter(|_| !s.carries.is_empty()) {
        Some(carry) => {
            sealed = super::carried::seal(p, s, obj, carry, path)?;
            &sealed
        }
        None => obj,
    };
    let at = kinds::WriteAt {
        obj,
        path,
        owner: obj,
        carry,
    };
    // Per field written: where it starts and ends.
    let mut spans: Vec<(usize, usize)> = Vec::with_capacity(s.fields.len());
    for (i, f) in s.fields.iter().enumerate() {
        let start = w.position();
        kinds::of(&f.kind).write_in(p, s, i, &spans, &at, w)?;
        spans.push((start, w.position()));
    }
    Ok(())
}

/// Every key of `obj` must name a field or bit member of `s`.
pub(super) fn check_keys(s: &Struct, obj: &Fields, path: &str) -> Result<(), EncodeIssue> {
    let known = |k: &str| s.fields.iter().any(|f| super::keys(f).contains(&k));
    match obj.keys().find(|k| !known(k)) {
        Some(k) => Err(EncodeIssue::new(
            join(path, k),
            format!("struct `{}` has no such field", s.name),
        )),
        None => Ok(()),
    }
}

/// Refuses `len` items (`what`: bytes or elements) above the field's `max`, or other than the
/// count its size field (`size_from`, a field of `owner`) states, as generated code does.
pub(super) fn check_len(
    len: usize,
    what: &str,
    max: usize,
    size_from: Option<&str>,
    owner: &Fields,
    path: &str,
) -> Result<(), EncodeIssue> {
    if len > max {
        return Err(EncodeIssue::new(
            path,
            format!("{len} {what}, at most {max} allowed"),
        ));
    }
    if let Some(n) = size_from {
        let stated = owner.get(n).and_then(Value::as_u64);
        if stated.is_none_or(|s| field::check_stated_len(len, s).is_err()) {
            let stated = stated.map_or("nothing".into(), |s| s.to_string());
            return Err(EncodeIssue::new(
                path,
                format!("{len} {what}, but `{n}` says {stated}"),
            ));
        }
    }
    Ok(())
}

/// Bytes from a value: bytes, a hex string, or an array of numbers.
pub(crate) fn value_bytes(v: &Value) -> Option<Vec<u8>> {
    match v {
        Value::Bytes(b) => Some(b.clone()),
        Value::String(s) => parse_hex(s),
        Value::Array(items) => items
            .iter()
            .map(|x| x.as_u64().and_then(|b| u8::try_from(b).ok()))
            .collect(),
        _ => None,
    }
}

/// The raw bits of a bit member; [`field::set_bits`] refuses those that do not fit the
/// member's width, as generated code does.
pub(super) fn member_raw(
    p: &Protocol,
    m: &BitMember,
    v: &Value,
    path: &str,
) -> Result<u64, EncodeIssue> {
    match m.enum_index {
        // `to_raw() as word`: a negative value of a signed enum is sign-extended.
        Some(ei) => {
            let e = &p.enums[ei];
            let raw = enum_raw(e, v, path)?;
            Ok(signed_value(e.prim, raw).map_or(raw, |i| i as u64))
        }
        None => member_number(m, v, path),
    }
}

/// The unsigned bits of member `m` (not an enum) holding `v`: the raw integer of a scaled
/// value, a signed value in two's complement of the member's width; a value that does not fit
/// the member's type, or a signed one its width, is an error (an unsigned one too wide is the
/// caller's, as it sets the bits).
fn member_number(m: &BitMember, v: &Value, path: &str) -> Result<u64, EncodeIssue> {
    let wide = |prim| Scalar {
        prim,
        endian: protocol_spec::ir::ByteOrder::Little,
    };
    let raw = match (&m.scale, m.is_signed()) {
        (Some(sc), true) => scaled_raw(wide(Prim::I64), sc, v, path)?,
        (Some(sc), false) => scaled_raw(wide(Prim::U64), sc, v, path)?,
        (None, _) => value_bits(v, m.prim).map_err(|e| issue(path, e))?,
    };
    if !m.is_signed() {
        return Ok(raw);
    }
    let value = match m.scale {
        Some(_) => raw as i64,
        None => protocol_runtime::bitstream::sign_extend(raw, m.prim.bits()),
    };
    protocol_runtime::bitstream::signed_bits(value, m.width).map_err(|_| {
        EncodeIssue::new(
            path,
            format!("{value} does not fit {} bits of two's complement", m.width),
        )
    })
}

pub(super) fn write_elem(
    p: &Protocol,
    ty: &ValueType,
    v: &Value,
    w: &mut Writer<'_>,
    path: &str,
    carry: Option<usize>,
) -> Result<(), EncodeIssue> {
    let buffer = |e| EncodeIssue::runtime(e);
    match ty {
        ValueType::Scalar {
            scalar,
            scale: None,
        } => {
            let bits = value_bits(v, scalar.prim).map_err(|e| issue(path, e))?;
            write_bits(w, *scalar, bits).map_err(buffer)
        }
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => {
            let bits = scaled_raw(*scalar, sc, v, path)?;
            write_bits(w, *scalar, bits).map_err(buffer)
        }
        ValueType::Struct(si) => write_payload(p, *si, v, w, path, carry),
        ValueType::Enum(ei, scalar) => {
            let raw = enum_raw(&p.enums[*ei], v, path)?;
            write_bits(w, *scalar, raw).map_err(buffer)
        }
        ValueType::Text(n) => {
            let bytes = text_bytes(v, *n, path)?;
            w.put_bytes(&bytes).map_err(buffer)
        }
    }
}

/// The `n` bytes of a NUL-padded text: a string padded by the runtime's `text::pad_text`, or
/// exactly `n` bytes as numbers.
fn text_bytes(v: &Value, n: usize, path: &str) -> Result<Vec<u8>, EncodeIssue> {
    let mut out = vec![0u8; n];
    match v {
        Value::String(s) => text::pad_text(s.as_bytes(), &mut out).ok_or_else(|| {
            EncodeIssue::new(
                path,
                format!("a text of {} bytes does not fit char[{n}]", s.len()),
            )
        })?,
        Value::Array(items) if items.len() == n => {
            for (o, item) in out.iter_mut().zip(items) {
                *o = value_bits(item, Prim::U8).map_err(|e| issue(path, e))? as u8;
            }
        }
        _ => {
            return Err(EncodeIssue::new(
                path,
                format!("expected a string, or an array of {n} bytes"),
            ));
        }
    }
    Ok(out)
}

/// The raw integer of a scaled field's physical value, by the runtime's field rules (as
/// generated code computes it): the value in its Rust type, clamped, quantized, fitted to the
/// raw type; a value the raw type cannot hold is refused.
pub(super) fn scaled_raw(
    scalar: Scalar,
    sc: &Scale,
    v: &Value,
    path: &str,
) -> Result<u64, EncodeIssue> {
    if scalar.prim.is_float() {
        return scaled_float_bits(scalar, sc, v, path);
    }
    let shown;
    // In the field's Rust type, as generated code computes it.
    let q = match sc.physical {
        Prim::F32 => {
            let value = value_f32(v).map_err(|e| issue(path, e))?;
            shown = f64::from(value);
            let (factor, offset) = (sc.factor as f32, sc.offset as f32);
            let physical = match sc.clamp {
                Some((lo, hi)) => field::clamp(value, lo as f32, hi as f32),
                None => value,
            };
            fit_bits(
                scalar.prim,
                field::quantize(physical, factor, offset, sc.rounding),
            )
        }
        _ => {
            let value = value_f64(v).map_err(|e| issue(path, e))?;
            shown = value;
            let physical = match sc.clamp {
                Some((lo, hi)) => field::clamp(value, lo, hi),
                None => value,
            };
            fit_bits(
                scalar.prim,
                field::quantize(physical, sc.factor, sc.offset, sc.rounding),
            )
        }
    };
    let raw = q.map_err(|_| {
        EncodeIssue::new(
            path,
            format!(
                "{shown} does not fit the raw type {}",
                scalar.prim.spec_name()
            ),
        )
    })?;
    Ok(truncate(scalar.prim, raw))
}

/// The raw bits (for [`write_bits`]) of a scaled field whose wire type is a float: the value
/// in its Rust type, clamped, unscaled by the runtime's [`field::unscale`], then converted to
/// the wire's type as generated code's `as` casts do (an `f16` through `f32`); a value
/// beyond the largest half is refused.
fn scaled_float_bits(
    scalar: Scalar,
    sc: &Scale,
    v: &Value,
    path: &str,
) -> Result<u64, EncodeIssue> {
    // The raw value in the wire's width: an `f64` wire takes it widened, the others narrowed.
    let wire = |wide: f64, narrow: f32| match scalar.prim {
        Prim::F64 => wide.to_bits(),
        _ => u64::from(narrow.to_bits()),
    };
    let bits = match sc.physical {
        Prim::F32 => {
            let value = value_f32(v).map_err(|e| issue(path, e))?;
            let (factor, offset) = (sc.factor as f32, sc.offset as f32);
            let physical = match sc.clamp {
                Some((lo, hi)) => field::clamp(value, lo as f32, hi as f32),
                None => value,
            };
            let raw = field::unscale(physical, factor, offset);
            wire(f64::from(raw), raw)
        }
        _ => {
            let value = value_f64(v).map_err(|e| issue(path, e))?;
            let physical = match sc.clamp {
                Some((lo, hi)) => field::clamp(value, lo, hi),
                None => value,
            };
            let raw = field::unscale(physical, sc.factor, sc.offset);
            wire(raw, raw as f32)
        }
    };
    if scalar.prim == Prim::F16
        && protocol_runtime::wire::f32_to_f16(f32::from_bits(bits as u32)).is_none()
    {
        return Err(EncodeIssue::new(
            path,
            format!("{v} does not fit the raw type f16 once scaled"),
        ));
    }
    Ok(bits)
}

/// [`field::fit`] for the raw type `prim`, as two's complement bits.
fn fit_bits(prim: Prim, q: impl field::Float) -> Result<u64, EncodeError> {
    use field::fit;
    use protocol_runtime::wire::{fit_i24, fit_signed, fit_u24, fit_unsigned};
    Ok(match prim {
        Prim::U8 => u64::from(fit::<u8>(q)?),
        Prim::U16 => u64::from(fit::<u16>(q)?),
        Prim::U24 => u64::from(fit_u24(fit::<u32>(q)?)?),
        Prim::U32 => u64::from(fit::<u32>(q)?),
        Prim::U64 => fit::<u64>(q)?,
        Prim::I8 => fit::<i8>(q)? as u64,
        Prim::I16 => fit::<i16>(q)? as u64,
        Prim::I24 => fit_i24(fit::<i32>(q)?)? as u64,
        Prim::I32 => fit::<i32>(q)? as u64,
        Prim::I64 => fit::<i64>(q)? as u64,
        Prim::U40 | Prim::U48 | Prim::U56 => fit_unsigned(fit::<u64>(q)?, prim.bits())?,
        Prim::I40 | Prim::I48 | Prim::I56 => fit_signed(fit::<i64>(q)?, prim.bits())? as u64,
        // A float wire value is not fitted (`scaled_float_bits`); a bool takes no scale.
        Prim::F16 | Prim::F32 | Prim::F64 | Prim::Bool | Prim::BoolInverted => {
            return Err(EncodeError::ValueOutOfRange {
                place: protocol_runtime::error::Place::NONE,
            });
        }
    })
}

/// The raw bits (truncated to the enum's type) of an enum value: a variant's spec or Rust
/// name, or a number that is a variant's value (any number when unknown values are kept).
fn enum_raw(e: &Enum, v: &Value, path: &str) -> Result<u64, EncodeIssue> {
    if let Value::String(name) = v {
        return e
            .variants
            .iter()
            .find(|x| x.name == *name || x.rust_name == *name)
            .map(|x| truncate(e.prim, x.value))
            .ok_or_else(|| {
                let names: Vec<&str> = e.variants.iter().map(|x| x.name.as_str()).collect();
                EncodeIssue::new(
                    path,
                    format!(
                        "`{name}` is no variant of `{}` (variants: {})",
                        e.name,
                        names.join(", ")
                    ),
                )
            });
    }
    let raw = value_bits(v, e.prim).map_err(|err| match err {
        NumError::Type(_) => EncodeIssue::new(
            path,
            format!("expected a variant name of `{}` or its value", e.name),
        ),
        NumError::Range(m) => EncodeIssue::new(path, m),
    })?;
    if e.unknown.encode(variant(e, raw).is_some()).is_ok() {
        Ok(raw)
    } else {
        Err(EncodeIssue::new(
            path,
            format!(
                "{} is no variant of `{}`, which rejects unknown values",
                bits_as_f64(e.prim, raw),
                e.name
            ),
        ))
    }
}
