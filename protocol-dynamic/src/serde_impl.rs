//! `Serialize` and `Deserialize` for [`Value`] (the `serde` feature): the JSON Lines shape of
//! `protocol decode`, and what `protocol encode` reads.
//!
//! Serializing writes an `f32` as an `f32` (which `serde_json` prints as the shortest decimal
//! that reads back as the same `f32`: `0.48`, `1.803067e14`), as serde writes the `f32` fields
//! of generated types (`protocol!(..., derive(serde))`), so that both print the same JSON and
//! a binary format keeps four bytes; an `f64` as itself, a non-finite float as the string `"inf"`, `"-inf"`, `"NaN"` or
//! `"NaN(0x..)"`, bytes as a lowercase hex string, a struct as a map in field order and `Null`
//! as a unit (`null`). Deserializing keeps what the format gives: numbers as `UInt`, `Int` or
//! `F64`, strings as `String` (the codec reads hex, enum names and non-finite floats from
//! them when it encodes), maps as structs in their order (a repeated key keeps its first place
//! and its last value). With `serde_json`, enable its `float_roundtrip` feature so that a
//! printed float reads back as the same bits.

use std::fmt;

use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde::ser::{Serialize, SerializeMap, SerializeSeq, Serializer};

use crate::model::{Fields, Value};
use crate::value::{f32_text, f64_text};

impl Serialize for Value {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let float = |text: Result<f64, String>, s: S| match text {
            Ok(x) => s.serialize_f64(x),
            Err(t) => s.serialize_str(&t),
        };
        match self {
            Value::Null => s.serialize_unit(),
            Value::Bool(b) => s.serialize_bool(*b),
            Value::UInt(u) => s.serialize_u64(*u),
            Value::Int(i) => s.serialize_i64(*i),
            Value::F32(x) => match f32_text(*x) {
                Ok(_) => s.serialize_f32(*x),
                Err(t) => s.serialize_str(&t),
            },
            Value::F64(x) => float(f64_text(*x), s),
            Value::String(t) => s.serialize_str(t),
            Value::Bytes(b) => s.serialize_str(&crate::hex(b)),
            Value::Array(items) => {
                let mut seq = s.serialize_seq(Some(items.len()))?;
                for v in items {
                    seq.serialize_element(v)?;
                }
                seq.end()
            }
            Value::Struct(fields) => fields.serialize(s),
        }
    }
}

impl Serialize for Fields {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.len()))?;
        for (k, v) in self.iter() {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}

struct ValueVisitor;

impl<'de> Visitor<'de> for ValueVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a value")
    }

    fn visit_bool<E>(self, b: bool) -> Result<Value, E> {
        Ok(Value::Bool(b))
    }

    fn visit_u64<E>(self, u: u64) -> Result<Value, E> {
        Ok(Value::UInt(u))
    }

    fn visit_i64<E>(self, i: i64) -> Result<Value, E> {
        Ok(match u64::try_from(i) {
            Ok(u) => Value::UInt(u),
            Err(_) => Value::Int(i),
        })
    }

    fn visit_f64<E>(self, x: f64) -> Result<Value, E> {
        Ok(Value::F64(x))
    }

    fn visit_str<E>(self, t: &str) -> Result<Value, E> {
        Ok(Value::String(t.to_string()))
    }

    fn visit_string<E>(self, t: String) -> Result<Value, E> {
        Ok(Value::String(t))
    }

    fn visit_bytes<E>(self, b: &[u8]) -> Result<Value, E> {
        Ok(Value::Bytes(b.to_vec()))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<Value, D::Error> {
        Value::deserialize(d)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(v) = seq.next_element()? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut fields = Fields::new();
        while let Some((k, v)) = map.next_entry::<String, Value>()? {
            fields.insert(k, v);
        }
        Ok(Value::Struct(fields))
    }
}

impl<'de> Deserialize<'de> for Value {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Value, D::Error> {
        d.deserialize_any(ValueVisitor)
    }
}

impl<'de> Deserialize<'de> for Fields {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Fields, D::Error> {
        match Value::deserialize(d)? {
            Value::Struct(fields) => Ok(fields),
            other => Err(de::Error::invalid_type(
                de::Unexpected::Other(&other.describe()),
                &"a map",
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::value::value_f32;

    fn json(v: &Value) -> String {
        serde_json::to_string(v).expect("a value serializes")
    }

    fn read(text: &str) -> Value {
        serde_json::from_str(text).expect("JSON reads")
    }

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
            let text = json(&Value::F32(x));
            let y = value_f32(&read(&text)).expect("f32");
            assert_eq!(y.to_bits(), x.to_bits(), "{x} printed as {text}");
        }
        assert_eq!(json(&Value::F32(0.48)), "0.48");
    }

    #[test]
    fn every_f32_bit_pattern_of_a_sample_round_trips() {
        let mut bits = 0x1234_5678u32;
        for _ in 0..20_000 {
            bits ^= bits << 13;
            bits ^= bits >> 17;
            bits ^= bits << 5;
            let text = json(&Value::F32(f32::from_bits(bits)));
            assert_eq!(
                value_f32(&read(&text)).map(f32::to_bits),
                Ok(bits),
                "{text}"
            );
        }
    }

    #[test]
    fn special_floats_are_strings() {
        assert_eq!(json(&Value::F32(f32::INFINITY)), r#""inf""#);
        assert_eq!(json(&Value::F64(f64::NEG_INFINITY)), r#""-inf""#);
        assert_eq!(json(&Value::F32(f32::NAN)), r#""NaN""#);
        let odd = f32::from_bits(0x7fc0_0001);
        let text = json(&Value::F32(odd));
        assert_eq!(text, r#""NaN(0x7fc00001)""#);
        assert_eq!(value_f32(&read(&text)).map(f32::to_bits), Ok(0x7fc0_0001));
    }

    #[test]
    fn the_json_shape_is_serde_jsons_own() {
        let v = Value::Struct(
            [
                ("n", Value::UInt(u64::MAX)),
                ("i", Value::Int(i64::MIN)),
                ("x", Value::F64(0.1)),
                ("b", Value::Bytes(vec![0x0a, 0xff])),
                ("none", Value::Null),
                (
                    "list",
                    Value::Array(vec![Value::Bool(true), Value::from("A")]),
                ),
            ]
            .into_iter()
            .collect(),
        );
        let text = json(&v);
        let reference = serde_json::json!({
            "n": u64::MAX, "i": i64::MIN, "x": 0.1, "b": "0aff", "none": null, "list": [true, "A"],
        });
        assert_eq!(text, reference.to_string());
        let back = read(&text);
        assert_eq!(back["n"], Value::UInt(u64::MAX));
        assert_eq!(back["i"], Value::Int(i64::MIN));
        assert_eq!(back["b"], Value::from("0aff"));
        assert_eq!(json(&back), text);
    }

    #[test]
    fn a_repeated_key_keeps_its_place_and_its_last_value() {
        let v = read(r#"{"a": 1, "b": 2, "a": 3}"#);
        assert_eq!(json(&v), r#"{"a":3,"b":2}"#);
    }
}
