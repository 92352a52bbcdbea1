//! Numbers between the wire and JSON: every primitive read and written with the runtime's
//! cursors ([`Reader`], [`Writer`]), and converted to and from [`serde_json::Value`] so that
//! decoding then encoding gives the same bits back.
//!
//! This module owns the JSON form of a number. Floats are written as the shortest decimal that
//! reads back as the same float (`0.48`, not `0.47999998927116394`); when a JSON number is
//! encoded into an `f32`, the float whose shortest decimal is that number is preferred, so a
//! value printed by `decode` always encodes to its original bits. Non-finite floats, which JSON
//! cannot hold, are the strings `"inf"`, `"-inf"` and `"NaN"` (or `"NaN(0x7fc00001)"`, with its
//! bits, for a NaN other than the default one).

use protocol_codegen::ir::{ByteOrder, Prim, Scalar};
use protocol_runtime::{DecodeError, EncodeError, Reader, Writer};
use serde_json::Value;

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

    /// The JSON form of the value.
    pub fn to_json(self) -> Value {
        match self {
            Num::U(v) => Value::from(v),
            Num::I(v) => Value::from(v),
            Num::F32(v) => f32_json(v),
            Num::F64(v) => f64_json(v),
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
        Prim::U16 => Num::U(u64::from(by_order!(r, s.endian, u16_le, u16_be)?)),
        Prim::I16 => Num::I(i64::from(by_order!(r, s.endian, i16_le, i16_be)?)),
        Prim::U32 => Num::U(u64::from(by_order!(r, s.endian, u32_le, u32_be)?)),
        Prim::I32 => Num::I(i64::from(by_order!(r, s.endian, i32_le, i32_be)?)),
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
/// casts keep), floats from their bit pattern, `bool` as 0 or 1.
///
/// # Errors
/// [`EncodeError::BufferTooSmall`] when the writer has too little room.
pub fn write_bits(w: &mut Writer<'_>, s: Scalar, bits: u64) -> Result<(), EncodeError> {
    match s.prim {
        Prim::U8 | Prim::I8 => w.put_u8(bits as u8),
        Prim::Bool => w.put_u8(u8::from(bits != 0)),
        Prim::U16 | Prim::I16 => put_by_order!(w, s.endian, put_u16_le, put_u16_be, bits as u16),
        Prim::U32 | Prim::I32 | Prim::F32 => {
            put_by_order!(w, s.endian, put_u32_le, put_u32_be, bits as u32)
        }
        Prim::U64 | Prim::I64 | Prim::F64 => {
            put_by_order!(w, s.endian, put_u64_le, put_u64_be, bits)
        }
    }
}

/// `raw & mask` of the primitive's width: what `value as T` keeps of an unsigned value.
pub fn truncate(prim: Prim, value: u64) -> u64 {
    match prim.size() {
        8 => value,
        n => value & ((1u64 << (8 * n)) - 1),
    }
}

/// The JSON form of an `f32`: its shortest decimal, or a string when it is not finite.
pub fn f32_json(x: f32) -> Value {
    if x.is_nan() {
        return nan_json(u64::from(x.to_bits()), u64::from(f32::NAN.to_bits()), 8);
    }
    if x.is_infinite() {
        return Value::from(if x > 0.0 { "inf" } else { "-inf" });
    }
    // `Display` prints the shortest decimal that reads back as the same f32; as an f64 it
    // prints the same way again, so the JSON text is that decimal.
    let shortest: f64 = x.to_string().parse().unwrap_or(f64::from(x));
    Value::from(shortest)
}

/// The JSON form of an `f64`: itself, or a string when it is not finite.
pub fn f64_json(x: f64) -> Value {
    if x.is_nan() {
        return nan_json(x.to_bits(), f64::NAN.to_bits(), 16);
    }
    if x.is_infinite() {
        return Value::from(if x > 0.0 { "inf" } else { "-inf" });
    }
    Value::from(x)
}

fn nan_json(bits: u64, default: u64, digits: usize) -> Value {
    if bits == default {
        Value::from("NaN")
    } else {
        Value::from(format!("NaN(0x{bits:0digits$x})"))
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

/// Why a JSON value could not be read as a number of some type.
#[derive(Debug, Clone, PartialEq)]
pub enum NumError {
    /// The value has the wrong JSON type; the text says what was expected.
    Type(String),
    /// The value does not fit the type.
    Range(String),
}

fn describe(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.to_string(),
        Value::String(s) => format!("the string {s:?}"),
        Value::Array(_) => "an array".into(),
        Value::Object(_) => "an object".into(),
    }
}

/// An `f32` from JSON, preferring the float whose shortest decimal is the number written.
///
/// # Errors
/// [`NumError::Type`] for anything but a number or a non-finite float's string.
pub fn json_f32(v: &Value) -> Result<f32, NumError> {
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
                describe(v)
            ))),
        };
    }
    let d = v
        .as_f64()
        .ok_or_else(|| NumError::Type(format!("expected a number (f32), got {}", describe(v))))?;
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

/// An `f64` from JSON.
///
/// # Errors
/// [`NumError::Type`] for anything but a number or a non-finite float's string.
pub fn json_f64(v: &Value) -> Result<f64, NumError> {
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
                describe(v)
            ))),
        };
    }
    v.as_f64()
        .ok_or_else(|| NumError::Type(format!("expected a number (f64), got {}", describe(v))))
}

/// An integer from JSON: a number without a fraction, or a `"0x..."` string.
fn json_integer(v: &Value, prim: Prim) -> Result<i128, NumError> {
    let name = prim.rust_name();
    let wrong = || NumError::Type(format!("expected an integer ({name}), got {}", describe(v)));
    match v {
        Value::Number(n) => {
            if let Some(u) = n.as_u64() {
                Ok(i128::from(u))
            } else if let Some(i) = n.as_i64() {
                Ok(i128::from(i))
            } else {
                match n.as_f64() {
                    Some(f) if f.fract() == 0.0 && f.abs() < 1.8e19 => Ok(f as i128),
                    _ => Err(wrong()),
                }
            }
        }
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
        Prim::U32 => (0, i128::from(u32::MAX)),
        Prim::I32 => (i128::from(i32::MIN), i128::from(i32::MAX)),
        Prim::I64 => (i128::from(i64::MIN), i128::from(i64::MAX)),
        _ => (0, i128::from(u64::MAX)),
    }
}

/// A primitive from JSON, as raw bits for [`write_bits`] (two's complement for signed
/// integers, the bit pattern for floats).
///
/// # Errors
/// [`NumError`] when the value has the wrong type or does not fit.
pub fn json_bits(v: &Value, prim: Prim) -> Result<u64, NumError> {
    match prim {
        Prim::F32 => json_f32(v).map(|x| u64::from(x.to_bits())),
        Prim::F64 => json_f64(v).map(f64::to_bits),
        Prim::Bool => match v {
            Value::Bool(b) => Ok(u64::from(*b)),
            Value::Number(n) if n.as_u64() == Some(0) || n.as_u64() == Some(1) => {
                Ok(n.as_u64().unwrap_or(0))
            }
            _ => Err(NumError::Type(format!(
                "expected true or false, got {}",
                describe(v)
            ))),
        },
        _ => {
            let x = json_integer(v, prim)?;
            let (lo, hi) = int_range(prim);
            if x < lo || x > hi {
                return Err(NumError::Range(format!(
                    "{x} does not fit {} ({lo}..={hi})",
                    prim.rust_name()
                )));
            }
            // Two's complement bits of a signed value, truncated to the type.
            Ok(truncate(prim, x as i64 as u64))
        }
    }
}

/// The value of raw bits of an integer primitive as an `f64` (`raw as f64` in generated code).
pub fn bits_as_f64(prim: Prim, bits: u64) -> f64 {
    match prim {
        Prim::I8 => f64::from(bits as u8 as i8),
        Prim::I16 => f64::from(bits as u16 as i16),
        Prim::I32 => f64::from(bits as u32 as i32),
        Prim::I64 => bits as i64 as f64,
        _ => bits as f64,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn f32_values_print_short_and_encode_to_their_bits() {
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
            let v = f32_json(x);
            let text = v.to_string();
            let back: Value = serde_json::from_str(&text).expect("json");
            let y = json_f32(&back).expect("f32");
            assert_eq!(y.to_bits(), x.to_bits(), "{x} printed as {text}");
        }
        assert_eq!(f32_json(0.48).to_string(), "0.48");
    }

    #[test]
    fn every_f32_bit_pattern_of_a_sample_round_trips() {
        let mut bits = 0x1234_5678u32;
        for _ in 0..20_000 {
            bits ^= bits << 13;
            bits ^= bits >> 17;
            bits ^= bits << 5;
            let x = f32::from_bits(bits);
            let text = f32_json(x).to_string();
            let back: Value = serde_json::from_str(&text).expect("json");
            assert_eq!(json_f32(&back).map(f32::to_bits), Ok(bits), "{text}");
        }
    }

    #[test]
    fn special_floats_are_strings() {
        assert_eq!(f32_json(f32::INFINITY), Value::from("inf"));
        assert_eq!(f64_json(f64::NEG_INFINITY), Value::from("-inf"));
        assert_eq!(f32_json(f32::NAN), Value::from("NaN"));
        let odd = f32::from_bits(0x7fc0_0001);
        assert_eq!(f32_json(odd), Value::from("NaN(0x7fc00001)"));
        assert_eq!(json_f32(&f32_json(odd)).map(f32::to_bits), Ok(0x7fc0_0001));
    }

    #[test]
    fn integers_are_range_checked() {
        assert_eq!(json_bits(&Value::from(255), Prim::U8), Ok(255));
        assert!(matches!(
            json_bits(&Value::from(256), Prim::U8),
            Err(NumError::Range(_))
        ));
        assert_eq!(json_bits(&Value::from(-1), Prim::I16), Ok(0xFFFF));
        assert_eq!(json_bits(&Value::from("0x1F"), Prim::U8), Ok(0x1F));
        assert!(matches!(
            json_bits(&Value::from(1.5), Prim::U8),
            Err(NumError::Type(_))
        ));
        assert!(matches!(
            json_bits(&Value::from("7"), Prim::U8),
            Err(NumError::Type(_))
        ));
    }
}
