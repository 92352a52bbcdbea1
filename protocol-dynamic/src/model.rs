//! The value model: what the codec decodes a frame into and encodes a frame from.
//!
//! A [`Value`] holds what the IR can put on the wire, without loss: integers as `u64` or `i64`
//! (a spec's integers are at most 64 bits wide), floats with their exact bits (`f32` kept as
//! an `f32`, NaN payloads included), strings for enum variant names, bytes, arrays, structs as
//! their fields in spec order ([`Fields`]), and `Null` for an absent optional field.
//!
//! What the codec produces, per IR type:
//!
//! | IR | decoded as | also accepted when encoding |
//! | --- | --- | --- |
//! | unsigned integer | [`Value::UInt`] | `Int` that fits, integral `F64`, `"0x.."` string |
//! | signed integer | [`Value::Int`] | `UInt` that fits, integral `F64`, `"-0x.."` string |
//! | `bool` | [`Value::Bool`] | `UInt` 0 or 1 |
//! | `f32`, `f64`, scaled physical value | [`Value::F32`], [`Value::F64`] | any number; `"inf"`, `"-inf"`, `"NaN"`, `"NaN(0x..)"` |
//! | enum | [`Value::String`] (the spec name) | the Rust name; the number (any, when unknown values are kept) |
//! | unknown enum value that is kept | [`Value::UInt`] or [`Value::Int`] | |
//! | bytes, ack data, raw payload | [`Value::Bytes`] | a hex string, an array of numbers 0..=255 |
//! | array, repeated group | [`Value::Array`] | |
//! | struct, header | [`Value::Struct`] | |
//! | absent optional field | [`Value::Null`] | a missing key |
//!
//! The looser forms on the right are what a value read from text (JSON) carries. The `serde`
//! feature adds `Serialize` and `Deserialize` (the JSON form: floats as their shortest
//! round-trip decimal, non-finite floats and bytes as strings).

use std::fmt;
use std::ops::Index;
use std::sync::Arc;

use crate::value::{f32_text, f64_text};

/// A dynamic value of a spec's type. See the [module documentation](self) for the mapping.
///
/// `PartialEq` compares floats as floats (a NaN is unequal to itself); compare
/// [`F32`](Value::F32) and [`F64`](Value::F64) bits with `to_bits` when that matters.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Value {
    /// An absent optional field (or a JSON `null`).
    #[default]
    Null,
    /// A `bool`.
    Bool(bool),
    /// An unsigned integer.
    UInt(u64),
    /// A signed integer.
    Int(i64),
    /// An `f32`, with its exact bits.
    F32(f32),
    /// An `f64`, with its exact bits.
    F64(f64),
    /// An enum variant's name, or text (a hex number, a non-finite float) read from JSON.
    String(String),
    /// Bytes.
    Bytes(Vec<u8>),
    /// An array or a repeated group.
    Array(Vec<Value>),
    /// A struct: its fields in order.
    Struct(Fields),
}

/// The fields of a struct, in order, each name once.
///
/// A name is shared text: a decoded struct's names are the interpreter's own, made once per
/// spec, so decoding a field copies no text and cloning a struct copies none either.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Fields(Vec<(Arc<str>, Value)>);

impl Fields {
    /// No fields.
    pub fn new() -> Self {
        Fields(Vec::new())
    }

    /// No fields, with room for `n`.
    pub fn with_capacity(n: usize) -> Self {
        Fields(Vec::with_capacity(n))
    }

    /// The value of field `name`.
    pub fn get(&self, name: &str) -> Option<&Value> {
        self.0.iter().find(|(k, _)| **k == *name).map(|(_, v)| v)
    }

    /// Sets field `name`: in its place when it exists, else last.
    pub fn insert(&mut self, name: impl Into<String>, value: Value) {
        let name = name.into();
        match self.0.iter_mut().find(|(k, _)| **k == *name) {
            Some((_, v)) => *v = value,
            None => self.0.push((Arc::from(name), value)),
        }
    }

    /// The fields in order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &Value)> {
        self.0.iter().map(|(k, v)| (&**k, v))
    }

    /// Appends field `name`, which the caller knows is not there yet (a spec's struct names
    /// each field once): the decoder's insert, without [`insert`](Self::insert)'s search.
    pub(crate) fn push(&mut self, name: &Arc<str>, value: Value) {
        self.0.push((Arc::clone(name), value));
    }

    /// The field names in order.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.0.iter().map(|(k, _)| &**k)
    }

    /// The number of fields.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// True when there are no fields.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

impl<K: Into<String>> FromIterator<(K, Value)> for Fields {
    fn from_iter<I: IntoIterator<Item = (K, Value)>>(iter: I) -> Self {
        let mut fields = Fields::new();
        for (k, v) in iter {
            fields.insert(k, v);
        }
        fields
    }
}

impl IntoIterator for Fields {
    type Item = (String, Value);
    type IntoIter = FieldsIntoIter;

    fn into_iter(self) -> Self::IntoIter {
        FieldsIntoIter(self.0.into_iter())
    }
}

/// The fields of a struct by value, in order ([`Fields::into_iter`]).
#[derive(Debug)]
pub struct FieldsIntoIter(std::vec::IntoIter<(Arc<str>, Value)>);

impl Iterator for FieldsIntoIter {
    type Item = (String, Value);

    fn next(&mut self) -> Option<(String, Value)> {
        self.0.next().map(|(k, v)| (k.to_string(), v))
    }
}

static NULL: Value = Value::Null;

impl Index<&str> for Fields {
    type Output = Value;

    /// The value of field `name`, [`Value::Null`] when there is none.
    fn index(&self, name: &str) -> &Value {
        self.get(name).unwrap_or(&NULL)
    }
}

impl Index<&str> for Value {
    type Output = Value;

    /// The value of field `name` of a struct, [`Value::Null`] for anything else.
    fn index(&self, name: &str) -> &Value {
        self.get(name).unwrap_or(&NULL)
    }
}

impl Value {
    /// Field `name` of a struct; `None` for a missing field or a value that is no struct.
    pub fn get(&self, name: &str) -> Option<&Value> {
        self.as_struct().and_then(|f| f.get(name))
    }

    /// The fields of a struct.
    pub fn as_struct(&self) -> Option<&Fields> {
        match self {
            Value::Struct(f) => Some(f),
            _ => None,
        }
    }

    /// The items of an array.
    pub fn as_array(&self) -> Option<&[Value]> {
        match self {
            Value::Array(items) => Some(items),
            _ => None,
        }
    }

    /// A string's text.
    pub fn as_str(&self) -> Option<&str> {
        match self {
            Value::String(s) => Some(s),
            _ => None,
        }
    }

    /// Bytes.
    pub fn as_bytes(&self) -> Option<&[u8]> {
        match self {
            Value::Bytes(b) => Some(b),
            _ => None,
        }
    }

    /// A `bool`.
    pub fn as_bool(&self) -> Option<bool> {
        match self {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }

    /// An integer that is not negative.
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Value::UInt(u) => Some(*u),
            Value::Int(i) => u64::try_from(*i).ok(),
            _ => None,
        }
    }

    /// An integer that fits an `i64`.
    pub fn as_i64(&self) -> Option<i64> {
        match self {
            Value::UInt(u) => i64::try_from(*u).ok(),
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }

    /// Any number as an `f64` (integers rounded to the nearest `f64`, an `f32` exactly).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::UInt(u) => Some(*u as f64),
            Value::Int(i) => Some(*i as f64),
            Value::F32(x) => Some(f64::from(*x)),
            Value::F64(x) => Some(*x),
            _ => None,
        }
    }

    /// True for [`Value::Null`].
    pub fn is_null(&self) -> bool {
        matches!(self, Value::Null)
    }

    /// The value as a message names it: `null`, `true`, a number, `the string "x"`, `an array`.
    pub(crate) fn describe(&self) -> String {
        match self {
            Value::String(s) => format!("the string {s:?}"),
            Value::Bytes(_) => "bytes".into(),
            Value::Array(_) => "an array".into(),
            Value::Struct(_) => "an object".into(),
            other => other.to_string(),
        }
    }
}

/// Compact JSON-like text, for messages: numbers (an `f32` as its shortest decimal), quoted
/// strings, non-finite floats and bytes as quoted text, `[..]` and `{"name":..}`.
impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Null => f.write_str("null"),
            Value::Bool(b) => write!(f, "{b}"),
            Value::UInt(u) => write!(f, "{u}"),
            Value::Int(i) => write!(f, "{i}"),
            Value::F32(x) => float(f, f32_text(*x)),
            Value::F64(x) => float(f, f64_text(*x)),
            Value::String(s) => write!(f, "{s:?}"),
            Value::Bytes(b) => write!(f, "\"{}\"", crate::hex(b)),
            Value::Array(items) => {
                f.write_str("[")?;
                for (i, v) in items.iter().enumerate() {
                    if i > 0 {
                        f.write_str(",")?;
                    }
                    write!(f, "{v}")?;
                }
                f.write_str("]")
            }
            Value::Struct(fields) => {
                f.write_str("{")?;
                for (i, (k, v)) in fields.iter().enumerate() {
                    if i > 0 {
                        f.write_str(",")?;
                    }
                    write!(f, "{k:?}:{v}")?;
                }
                f.write_str("}")
            }
        }
    }
}

fn float(f: &mut fmt::Formatter<'_>, text: Result<f64, String>) -> fmt::Result {
    match text {
        Ok(x) => write!(f, "{x:?}"),
        Err(t) => write!(f, "{t:?}"),
    }
}

impl From<bool> for Value {
    fn from(b: bool) -> Self {
        Value::Bool(b)
    }
}

impl From<u64> for Value {
    fn from(u: u64) -> Self {
        Value::UInt(u)
    }
}

impl From<usize> for Value {
    fn from(u: usize) -> Self {
        Value::UInt(u as u64)
    }
}

impl From<i64> for Value {
    fn from(i: i64) -> Self {
        Value::Int(i)
    }
}

impl From<f32> for Value {
    fn from(x: f32) -> Self {
        Value::F32(x)
    }
}

impl From<f64> for Value {
    fn from(x: f64) -> Self {
        Value::F64(x)
    }
}

impl From<&str> for Value {
    fn from(s: &str) -> Self {
        Value::String(s.to_string())
    }
}

impl From<String> for Value {
    fn from(s: String) -> Self {
        Value::String(s)
    }
}

impl From<Vec<u8>> for Value {
    fn from(b: Vec<u8>) -> Self {
        Value::Bytes(b)
    }
}

impl From<Vec<Value>> for Value {
    fn from(items: Vec<Value>) -> Self {
        Value::Array(items)
    }
}

impl From<Fields> for Value {
    fn from(f: Fields) -> Self {
        Value::Struct(f)
    }
}
