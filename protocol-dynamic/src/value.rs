//! Numbers between the wire and [`Value`]: every primitive read and written with the runtime's
//! cursors ([`Reader`], [`Writer`]), and converted to and from values so that decoding then
//! encoding gives the same bits back, also through text.
//!
//! This module owns the text form of a float. A float is written as the shortest decimal that
//! reads back as the same float (`0.48`, not `0.47999998927116394`); when a decimal (an `f64`)
//! is encoded into an `f32`, the float whose shortest decimal is that number is preferred, so a
//! value printed by `decode` always encodes to its original bits. Non-finite floats, which JSON
//! cannot hold, are the strings `"inf"`, `"-inf"` and `"NaN"` (or `"NaN(0x7fc00001)"`, with its
//! bits, for a NaN other than the default one).

use protocol_runtime::{DecodeError, EncodeError, Reader, Writer};
use protocol_spec::ir::{ByteOrder, Prim, Scalar};

use crate::model::Value;

/// A primitive value as read from the wire.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Num {
    /// An unsigned integer.
    U(u64),
    /// A signed integer.
    I(i64),
    /// An `f32`.
    F32(f32),
    /// An `f64`.
    F64(f64),
    /// A `bool`.
    Bool(bool),
}

impl Num {
    /// The raw integer bits as generated code's `value as u64` gives them (sign-extended for
    /// signed integers); floats give their bits.
    pub fn as_u64(self) -> u64 {
        match self {
            Num::U(v) => v,
            Num::I(v) => v as u64,
            Num::F32(v) => u64::from(v.to_bits()),
            Num::F64(v) => v.to_bits(),
            Num::Bool(b) => u64::from(b),
        }
    }

    /// The value as generated code's `value as f64` gives it.
    pub fn as_f64(self) -> f64 {
        match self {
            Num::U(v) => v as f64,
            Num::I(v) => v as f64,
            Num::F32(v) => f64::from(v),
            Num::F64(v) => v,
            Num::Bool(b) => f64::from(u8::from(b)),
        }
    }

    /// The value.
    pub fn to_value(self) -> Value {
        match self {
            Num::U(v) => Value::UInt(v),
            Num::I(v) => Value::Int(v),
            Num::F32(v) => Value::F32(v),
            Num::F64(v) => Value::F64(v),
            Num::Bool(b) => Value::Bool(b),
        }
    }
}

macro_rules! by_order {
    ($r:expr, $e:expr, $le:ident, $be:ident) => {
        match $e {
            ByteOrder::Little => $r.$le(),
            ByteOrder::Big => $r.$be(),
        }
    };
}

/// Reads one primitive.
///
/// # Errors
/// [`DecodeError::Truncated`] when too few bytes remain.
pub fn read_scalar(r: &mut Reader<'_>, s: Scalar) -> Result<Num, DecodeError> {
    Ok(match s.prim {
        Prim::U8 => Num::U(u64::from(r.u8()?)),
        Prim::I8 => Num::I(i64::from(r.i8()?)),
        Prim::Bool => Num::Bool(r.bool()?),
        Prim::BoolInverted => Num::Bool(r.bool_inverted()?),
        Prim::U16 => Num::U(u64::from(by_order!(r, s.endian, u16_le, u16_be)?)),
        Prim::I16 => Num::I(i64::from(by_order!(r, s.endian, i16_le, i16_be)?)),
        Prim::U24 => Num::U(u64::from(by_order!(r, s.endian, u24_le, u24_be)?)),
        Prim::I24 => Num::I(i64::from(by_order!(r, s.endian, i24_le, i24_be)?)),
        Prim::U32 => Num::U(u64::from(by_order!(r, s.endian, u32_le, u32_be)?)),
        Prim::I32 => Num::I(i64::from(by_order!(r, s.endian, i32_le, i32_be)?)),
        Prim::U40 => Num::U(by_order!(r, s.endian, u40_le, u40_be)?),
        Prim::I40 => Num::I(by_order!(r, s.endian, i40_le, i40_be)?),
        Prim::U48 => Num::U(by_order!(r, s.endian, u48_le, u48_be)?),
        Prim::I48 => Num::I(by_order!(r, s.endian, i48_le, i48_be)?),
        Prim::U56 => Num::U(by_order!(r, s.endian, u56_le, u56_be)?),
        Prim::I56 => Num::I(by_order!(r, s.endian, i56_le, i56_be)?),
        Prim::F16 => Num::F32(by_order!(r, s.endian, f16_le, f16_be)?),
        Prim::U64 => Num::U(by_order!(r, s.endian, u64_le, u64_be)?),
        Prim::I64 => Num::I(by_order!(r, s.endian, i64_le, i64_be)?),
        Prim::F32 => Num::F32(by_order!(r, s.endian, f32_le, f32_be)?),
        Prim::F64 => Num::F64(by_order!(r, s.endian, f64_le, f64_be)?),
    })
}

macro_rules! put_by_order {
    ($w:expr, $e:expr, $le:ident, $be:ident, $v:expr) => {
        match $e {
            ByteOrder::Little => $w.$le($v),
            ByteOrder::Big => $w.$be($v),
        }
    };
}

/// Writes one primitive from raw bits: integers as `bits as T` (what generated code's `as`
/// casts keep), floats from their bit pattern (an `f16` from its `f32`'s, rounded to the
/// nearest half), `bool` as 0 or 1 (the bits of `true` are 1, which an inverted `bool` writes
/// as 0).
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] when the writer has too little room;
/// [`EncodeError::ValueOutOfRange`] for an `f16` beyond the largest half (callers that fit
/// the value first, as [`value_bits`] does, never see it).
pub fn write_bits(w: &mut Writer<'_>, s: Scalar, bits: u64) -> Result<(), EncodeError> {
    let low = |n: u32| bits & (u64::MAX >> (64 - n));
    match s.prim {
        Prim::U8 | Prim::I8 => w.put_u8(bits as u8),
        Prim::Bool => w.put_u8(u8::from(bits != 0)),
        Prim::BoolInverted => w.put_u8(u8::from(bits == 0)),
        Prim::U16 | Prim::I16 => put_by_order!(w, s.endian, put_u16_le, put_u16_be, bits as u16),
        // Callers have fitted the value to 24 bits (`value_bits`, `fit_u24`/`fit_i24`); the
        // low 24 bits are the wire bytes of either sign.
        Prim::U24 | Prim::I24 => {
            put_by_order!(w, s.endian, put_u24_le, put_u24_be, bits as u32 & 0xFF_FFFF)
        }
        Prim::U32 | Prim::I32 | Prim::F32 => {
            put_by_order!(w, s.endian, put_u32_le, put_u32_be, bits as u32)
        }
        Prim::U64 | Prim::I64 | Prim::F64 => {
            put_by_order!(w, s.endian, put_u64_le, put_u64_be, bits)
        }
        // As the 24-bit types: fitted by the callers, the low bytes of either sign.
        Prim::U40 | Prim::I40 => put_by_order!(w, s.endian, put_u40_le, put_u40_be, low(40)),
        Prim::U48 | Prim::I48 => put_by_order!(w, s.endian, put_u48_le, put_u48_be, low(48)),
        Prim::U56 | Prim::I56 => put_by_order!(w, s.endian, put_u56_le, put_u56_be, low(56)),
        Prim::F16 => {
            let x = f32::from_bits(bits as u32);
            put_by_order!(w, s.endian, put_f16_le, put_f16_be, x)
        }
    }
}

/// The value of raw bits of a signed integer type, its sign bit extended (what generated
/// code's reads give); `None` for the other types.
pub fn sign_extended(prim: Prim, bits: u64) -> Option<i64> {
    let shift = 64 - prim.bits();
    prim.is_signed().then(|| ((bits << shift) as i64) >> shift)
}

/// `raw & mask` of the primitive's width: what `value as T` keeps of an unsigned value.
pub fn truncate(prim: Prim, value: u64) -> u64 {
    match prim.size() {
        8 => value,
        n => value & ((1u64 << (8 * n)) - 1),
    }
}

/// The shortest decimal that reads back as `x`, as an `f64` (what JSON prints for it), or
/// the text of a non-finite `x`.
pub fn f32_text(x: f32) -> Result<f64, String> {
    if x.is_nan() {
        return Err(nan_text(
            u64::from(x.to_bits()),
            u64::from(f32::NAN.to_bits()),
            8,
        ));
    }
    if x.is_infinite() {
        return Err(infinite_text(x > 0.0));
    }
    // `Display` prints the shortest decimal that reads back as the same f32; as an f64 it
    // prints the same way again, so the JSON text is that decimal.
    Ok(x.to_string().parse().unwrap_or(f64::from(x)))
}

/// `x` itself, or the text of a non-finite `x`.
pub fn f64_text(x: f64) -> Result<f64, String> {
    if x.is_nan() {
        return Err(nan_text(x.to_bits(), f64::NAN.to_bits(), 16));
    }
    if x.is_infinite() {
        return Err(infinite_text(x > 0.0));
    }
    Ok(x)
}

fn infinite_text(positive: bool) -> String {
    (if positive { "inf" } else { "-inf" }).to_string()
}

fn nan_text(bits: u64, default: u64, digits: usize) -> String {
    if bits == default {
        "NaN".to_string()
    } else {
        format!("NaN(0x{bits:0digits$x})")
    }
}

/// A float written as a string: `inf`, `-inf`, `NaN`, `NaN(0x...)`.
fn special_float(text: &str) -> Option<SpecialFloat> {
    match text {
        "inf" | "+inf" | "Infinity" => Some(SpecialFloat::Inf(false)),
        "-inf" | "-Infinity" => Some(SpecialFloat::Inf(true)),
        "NaN" | "nan" => Some(SpecialFloat::Nan(None)),
        _ => {
            let hex = text.strip_prefix("NaN(0x")?.strip_suffix(')')?;
            u64::from_str_radix(hex, 16)
                .ok()
                .map(|b| SpecialFloat::Nan(Some(b)))
        }
    }
}

enum SpecialFloat {
    Inf(bool),
    Nan(Option<u64>),
}

/// Why a value could not be read as a number of some type.
#[derive(Debug, Clone, PartialEq)]
pub enum NumError {
    /// The value has the wrong type; the text says what was expected.
    Type(String),
    /// The value does not fit the type.
    Range(String),
}

/// An `f32` from a value: an `f32` as it is; another number preferring the float whose
/// shortest decimal is that number.
///
/// # Errors
/// [`NumError::Type`] for anything but a number or a non-finite float's string.
pub fn value_f32(v: &Value) -> Result<f32, NumError> {
    if let Value::F32(x) = v {
        return Ok(*x);
    }
    if let Value::String(s) = v {
        return match special_float(s) {
            Some(SpecialFloat::Inf(neg)) => Ok(if neg {
                f32::NEG_INFINITY
            } else {
                f32::INFINITY
            }),
            Some(SpecialFloat::Nan(None)) => Ok(f32::NAN),
            Some(SpecialFloat::Nan(Some(bits))) => u32::try_from(bits)
                .map(f32::from_bits)
                .ok()
                .filter(|x| x.is_nan())
                .ok_or_else(|| NumError::Range(format!("{s} is not an f32 NaN"))),
            None => Err(NumError::Type(format!(
                "expected a number (f32), got {}",
                v.describe()
            ))),
        };
    }
    let d = v
        .as_f64()
        .ok_or_else(|| NumError::Type(format!("expected a number (f32), got {}", v.describe())))?;
    let near = d as f32;
    if !near.is_finite() {
        return Err(NumError::Range(format!("{d} does not fit an f32")));
    }
    // Among the nearest float and its two neighbours, the one that `decode` prints as `d`.
    let bits = near.to_bits();
    let candidates = [
        near,
        f32::from_bits(bits.wrapping_add(1)),
        f32::from_bits(bits.wrapping_sub(1)),
    ];
    let printed_as_d = |x: &&f32| {
        x.is_finite() && x.to_string().parse::<f64>().ok() == Some(d) && x.signum() == near.signum()
    };
    Ok(candidates
        .iter()
        .find(printed_as_d)
        .copied()
        .unwrap_or(near))
}

/// An `f64` from a value.
///
/// # Errors
/// [`NumError::Type`] for anything but a number or a non-finite float's string.
pub fn value_f64(v: &Value) -> Result<f64, NumError> {
    if let Value::String(s) = v {
        return match special_float(s) {
            Some(SpecialFloat::Inf(neg)) => Ok(if neg {
                f64::NEG_INFINITY
            } else {
                f64::INFINITY
            }),
            Some(SpecialFloat::Nan(None)) => Ok(f64::NAN),
            Some(SpecialFloat::Nan(Some(bits))) => Some(f64::from_bits(bits))
                .filter(|x| x.is_nan())
                .ok_or_else(|| NumError::Range(format!("{s} is not an f64 NaN"))),
            None => Err(NumError::Type(format!(
                "expected a number (f64), got {}",
                v.describe()
            ))),
        };
    }
    v.as_f64()
        .ok_or_else(|| NumError::Type(format!("expected a number (f64), got {}", v.describe())))
}

/// An integer from a value: an integer, a float without a fraction, or a `"0x..."` string.
fn value_integer(v: &Value, prim: Prim) -> Result<i128, NumError> {
    let name = prim.spec_name();
    let wrong = || {
        NumError::Type(format!(
            "expected an integer ({name}), got {}",
            v.describe()
        ))
    };
    match v {
        Value::UInt(u) => Ok(i128::from(*u)),
        Value::Int(i) => Ok(i128::from(*i)),
        Value::F32(_) | Value::F64(_) => match v.as_f64() {
            Some(f) if f.fract() == 0.0 && f.abs() < 1.8e19 => Ok(f as i128),
            _ => Err(wrong()),
        },
        Value::String(s) => {
            let (neg, body) = match s.strip_prefix('-') {
                Some(rest) => (true, rest),
                None => (false, s.as_str()),
            };
            let hex = body
                .strip_prefix("0x")
                .or_else(|| body.strip_prefix("0X"))
                .ok_or_else(wrong)?;
            let magnitude = u64::from_str_radix(&hex.replace('_', ""), 16).map_err(|_| wrong())?;
            Ok(if neg {
                -i128::from(magnitude)
            } else {
                i128::from(magnitude)
            })
        }
        _ => Err(wrong()),
    }
}

/// The range of an integer primitive.
fn int_range(prim: Prim) -> (i128, i128) {
    match prim {
        Prim::U8 => (0, i128::from(u8::MAX)),
        Prim::I8 => (i128::from(i8::MIN), i128::from(i8::MAX)),
        Prim::U16 => (0, i128::from(u16::MAX)),
        Prim::I16 => (i128::from(i16::MIN), i128::from(i16::MAX)),
        Prim::U24 => (0, 0xFF_FFFF),
        Prim::I24 => (-0x80_0000, 0x7F_FFFF),
        Prim::U32 => (0, i128::from(u32::MAX)),
        Prim::I32 => (i128::from(i32::MIN), i128::from(i32::MAX)),
        Prim::U40 | Prim::U48 | Prim::U56 => (0, (1i128 << prim.bits()) - 1),
        Prim::I40 | Prim::I48 | Prim::I56 => {
            let half = 1i128 << (prim.bits() - 1);
            (-half, half - 1)
        }
        Prim::I64 => (i128::from(i64::MIN), i128::from(i64::MAX)),
        _ => (0, i128::from(u64::MAX)),
    }
}

/// A primitive from a value, as raw bits for [`write_bits`] (two's complement for signed
/// integers, the bit pattern for floats).
///
/// # Errors
/// [`NumError`] when the value has the wrong type or does not fit.
pub fn value_bits(v: &Value, prim: Prim) -> Result<u64, NumError> {
    match prim {
        Prim::F32 => value_f32(v).map(|x| u64::from(x.to_bits())),
        // The `f32`'s bits, once it is known to round to a half.
        Prim::F16 => {
            let x = value_f32(v)?;
            match protocol_runtime::wire::f32_to_f16(x) {
                Some(_) => Ok(u64::from(x.to_bits())),
                None => Err(NumError::Range(format!(
                    "{x} does not fit f16 (at most 65504 in magnitude)"
                ))),
            }
        }
        Prim::F64 => value_f64(v).map(f64::to_bits),
        Prim::Bool | Prim::BoolInverted => match v {
            Value::Bool(b) => Ok(u64::from(*b)),
            Value::UInt(n @ (0 | 1)) => Ok(*n),
            Value::Int(n @ (0 | 1)) => Ok(*n as u64),
            _ => Err(NumError::Type(format!(
                "expected true or false, got {}",
                v.describe()
            ))),
        },
        _ => {
            let x = value_integer(v, prim)?;
            let (lo, hi) = int_range(prim);
            if x < lo || x > hi {
                return Err(NumError::Range(format!(
                    "{x} does not fit {} ({lo}..={hi})",
                    prim.spec_name()
                )));
            }
            // Two's complement bits of a signed value, truncated to the type.
            Ok(truncate(prim, x as i64 as u64))
        }
    }
}

/// The value of raw bits of an integer primitive as an `f64` (`raw as f64` in generated code).
pub fn bits_as_f64(prim: Prim, bits: u64) -> f64 {
    match sign_extended(prim, bits) {
        Some(i) => i as f64,
        None => bits as f64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_values_have_short_decimals_that_encode_to_their_bits() {
        for x in [
            0.48f32,
            std::f32::consts::PI,
            -0.0,
            1e-45,
            f32::MAX,
            f32::MIN_POSITIVE,
            12.3,
            0.1,
        ] {
            let d = f32_text(x).expect("finite");
            let y = value_f32(&Value::F64(d)).expect("f32");
            assert_eq!(y.to_bits(), x.to_bits(), "{x} written as {d}");
        }
        assert_eq!(f32_text(0.48), Ok(0.48));
    }

    #[test]
    fn special_floats_are_text() {
        assert_eq!(f32_text(f32::INFINITY), Err("inf".to_string()));
        assert_eq!(f64_text(f64::NEG_INFINITY), Err("-inf".to_string()));
        assert_eq!(f32_text(f32::NAN), Err("NaN".to_string()));
        let odd = f32::from_bits(0x7fc0_0001);
        let text = f32_text(odd).expect_err("not finite");
        assert_eq!(text, "NaN(0x7fc00001)");
        assert_eq!(
            value_f32(&Value::String(text)).map(f32::to_bits),
            Ok(0x7fc0_0001)
        );
        assert_eq!(
            value_f32(&Value::F32(odd)).map(f32::to_bits),
            Ok(0x7fc0_0001)
        );
    }

    #[test]
    fn integers_are_range_checked() {
        assert_eq!(value_bits(&Value::from(255u64), Prim::U8), Ok(255));
        assert!(matches!(
            value_bits(&Value::from(256u64), Prim::U8),
            Err(NumError::Range(_))
        ));
        assert_eq!(value_bits(&Value::from(-1i64), Prim::I16), Ok(0xFFFF));
        assert_eq!(value_bits(&Value::from("0x1F"), Prim::U8), Ok(0x1F));
        assert!(matches!(
            value_bits(&Value::from(1.5f64), Prim::U8),
            Err(NumError::Type(_))
        ));
        assert!(matches!(
            value_bits(&Value::from("7"), Prim::U8),
            Err(NumError::Type(_))
        ));
    }
}
