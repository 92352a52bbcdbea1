//! Floats of generated fields as the run-time codec writes them: a number when finite, else
//! the string `"inf"`, `"-inf"`, `"NaN"` (the default NaN) or `"NaN(0x..)"` with its bits, so
//! that every float reads back as the same bits (serde's own impls write a non-finite float as
//! `null` in JSON, which reads back as no float at all). Generated fields of type `f32` and
//! `f64` name [`float`](self) (`#[serde(with = ...)]`), arrays of them [`floats`] and optional
//! ones [`optional`].

use core::fmt;
use core::marker::PhantomData;

use serde::de::{self, Deserializer, Visitor};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

/// An `f32` or an `f64`.
pub trait SpecFloat: Copy + 'static {
    /// Hex digits of the bits in the text of a NaN.
    const DIGITS: usize;
    /// The bits of the default NaN, written `"NaN"`.
    const DEFAULT_NAN: u64;
    /// Positive or negative infinity.
    fn infinity(negative: bool) -> Self;
    /// The float of these bits, if they fit.
    fn from_bits_u64(bits: u64) -> Option<Self>;
    /// The float nearest a number.
    fn from_f64(x: f64) -> Self;
    /// Its bits.
    fn bits(self) -> u64;
    /// Whether it is a NaN, whether it is infinite, and whether its sign is negative.
    fn class(self) -> (bool, bool, bool);
    /// Writes a finite value as a number.
    ///
    /// # Errors
    /// The serializer's.
    fn serialize_number<S: Serializer>(self, s: S) -> Result<S::Ok, S::Error>;
}

impl SpecFloat for f32 {
    const DIGITS: usize = 8;
    const DEFAULT_NAN: u64 = f32::NAN.to_bits() as u64;
    fn infinity(negative: bool) -> Self {
        if negative {
            f32::NEG_INFINITY
        } else {
            f32::INFINITY
        }
    }
    fn from_bits_u64(bits: u64) -> Option<Self> {
        u32::try_from(bits).ok().map(f32::from_bits)
    }
    #[allow(clippy::cast_possible_truncation)]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
    fn bits(self) -> u64 {
        u64::from(self.to_bits())
    }
    fn class(self) -> (bool, bool, bool) {
        (self.is_nan(), self.is_infinite(), self.is_sign_negative())
    }
    fn serialize_number<S: Serializer>(self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f32(self)
    }
}

impl SpecFloat for f64 {
    const DIGITS: usize = 16;
    const DEFAULT_NAN: u64 = f64::NAN.to_bits();
    fn infinity(negative: bool) -> Self {
        if negative {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    }
    fn from_bits_u64(bits: u64) -> Option<Self> {
        Some(f64::from_bits(bits))
    }
    fn from_f64(x: f64) -> Self {
        x
    }
    fn bits(self) -> u64 {
        self.to_bits()
    }
    fn class(self) -> (bool, bool, bool) {
        (self.is_nan(), self.is_infinite(), self.is_sign_negative())
    }
    fn serialize_number<S: Serializer>(self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_f64(self)
    }
}

/// A float that serializes as the codec writes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Float<F>(pub F);

/// The text of a NaN other than the default one.
struct NanText<F>(F);

impl<F: SpecFloat> fmt::Display for NanText<F> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "NaN(0x{:01$x})", self.0.bits(), F::DIGITS)
    }
}

impl<F: SpecFloat> Serialize for Float<F> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let x = self.0;
        match x.class() {
            (true, _, _) if x.bits() == F::DEFAULT_NAN => s.serialize_str("NaN"),
            (true, _, _) => s.collect_str(&NanText(x)),
            (false, true, true) => s.serialize_str("-inf"),
            (false, true, false) => s.serialize_str("inf"),
            (false, false, _) => x.serialize_number(s),
        }
    }
}

struct FloatVisitor<F>(PhantomData<F>);

impl<F: SpecFloat> Visitor<'_> for FloatVisitor<F> {
    type Value = Float<F>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number, or \"inf\", \"-inf\", \"NaN\" or \"NaN(0x..)\"")
    }

    fn visit_f64<E: de::Error>(self, x: f64) -> Result<Float<F>, E> {
        Ok(Float(F::from_f64(x)))
    }

    #[allow(clippy::cast_precision_loss)]
    fn visit_u64<E: de::Error>(self, x: u64) -> Result<Float<F>, E> {
        Ok(Float(F::from_f64(x as f64)))
    }

    #[allow(clippy::cast_precision_loss)]
    fn visit_i64<E: de::Error>(self, x: i64) -> Result<Float<F>, E> {
        Ok(Float(F::from_f64(x as f64)))
    }

    fn visit_str<E: de::Error>(self, text: &str) -> Result<Float<F>, E> {
        let bits = match text {
            "inf" | "+inf" | "Infinity" => return Ok(Float(F::infinity(false))),
            "-inf" | "-Infinity" => return Ok(Float(F::infinity(true))),
            "NaN" | "nan" => Some(F::DEFAULT_NAN),
            _ => text
                .strip_prefix("NaN(0x")
                .and_then(|t| t.strip_suffix(')'))
                .and_then(|hex| u64::from_str_radix(hex, 16).ok()),
        };
        bits.and_then(F::from_bits_u64)
            .filter(|x| x.class().0)
            .map(Float)
            .ok_or_else(|| E::invalid_value(de::Unexpected::Str(text), &self))
    }
}

impl<'de, F: SpecFloat> Deserialize<'de> for Float<F> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FloatVisitor(PhantomData))
    }
}

/// Writes a float as the codec does.
///
/// # Errors
/// The serializer's.
pub fn serialize<F: SpecFloat, S: Serializer>(x: &F, s: S) -> Result<S::Ok, S::Error> {
    Float(*x).serialize(s)
}

/// Reads a float as the codec writes it.
///
/// # Errors
/// The deserializer's, and an error for a string that is no float.
pub fn deserialize<'de, F: SpecFloat, D: Deserializer<'de>>(d: D) -> Result<F, D::Error> {
    Float::deserialize(d).map(|f| f.0)
}

/// Arrays of floats, of any length.
pub mod floats {
    use super::{Float, SpecFloat};
    use serde::{Deserializer, Serializer};

    /// Writes the array's floats as the codec does.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<F: SpecFloat, S: Serializer, const N: usize>(
        xs: &[F; N],
        s: S,
    ) -> Result<S::Ok, S::Error> {
        super::super::array::serialize(&xs.map(Float), s)
    }

    /// Reads exactly `N` floats (`N` > 0).
    ///
    /// # Errors
    /// The deserializer's, and a length error for fewer or more than `N`.
    pub fn deserialize<'de, F: SpecFloat, D: Deserializer<'de>, const N: usize>(
        d: D,
    ) -> Result<[F; N], D::Error> {
        super::super::array::deserialize::<Float<F>, D, N>(d).map(|xs| xs.map(|x| x.0))
    }
}

/// Optional floats: `null` when absent.
pub mod optional {
    use super::{Float, SpecFloat};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// Writes the float as the codec does, or `null`.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<F: SpecFloat, S: Serializer>(x: &Option<F>, s: S) -> Result<S::Ok, S::Error> {
        x.map(Float).serialize(s)
    }

    /// Reads a float or `null`.
    ///
    /// # Errors
    /// The deserializer's.
    pub fn deserialize<'de, F: SpecFloat, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<F>, D::Error> {
        Option::<Float<F>>::deserialize(d).map(|x| x.map(|f| f.0))
    }
}
