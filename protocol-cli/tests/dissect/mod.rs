//! What the dissector tests share: the bundled specs with their vector files, reading frames
//! out of `tshark -T pdml`, and comparing each with the frame object `protocol decode` prints.
//!
//! PDML is read element by element, not line by line: a text field's `show` attribute may hold
//! a newline. Text is compared by its bytes (the `value` attribute, the field's bytes in hex)
//! where the shown string cannot say them: `decode` prints text that is not UTF-8 as its bytes,
//! and the dissector shows it with replacement characters and escapes.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::process::Command;

use protocol_spec::ir::{FieldKind, Protocol, ValueType};
use serde_json::Value;

use crate::support::{self, root};

/// Each spec, its vector file and the directions it is decoded in (a spec whose header does not
/// tell them is decoded in each): the registry's `dissector` suite (`tests/catalogue.toml`).
pub const SPECS: support::Listed<(&str, &str, &[&str])> = support::Listed(specs);

fn specs() -> &'static [(&'static str, &'static str, &'static [&'static str])] {
    type Spec = (&'static str, &'static str, &'static [&'static str]);
    static SPECS: std::sync::OnceLock<Vec<Spec>> = std::sync::OnceLock::new();
    SPECS.get_or_init(|| support::vector_specs("dissector"))
}

pub fn tshark_available() -> bool {
    let found = Command::new("tshark").arg("--version").output().is_ok();
    if !found {
        assert!(
            std::env::var_os("PROTOCOL_REQUIRE_TSHARK").is_none(),
            "PROTOCOL_REQUIRE_TSHARK is set and no tshark is on the PATH"
        );
        eprintln!("no tshark on the PATH: the dissectors are not run");
    }
    found
}

/// One frame as the dissector shows it: its bytes, and every field's values in order.
#[derive(Debug, Default)]
pub struct Shown {
    pub hex: String,
    pub fields: BTreeMap<String, Vec<FieldShown>>,
}

/// One field as the dissector shows it.
#[derive(Debug, Default)]
pub struct FieldShown {
    /// The text shown (for a `bytes` field, its bytes in hex).
    pub show: String,
    /// The field's bytes in hex (PDML's `value`), empty where PDML gives none.
    pub value: String,
}

/// The value of an XML attribute in a PDML element's start tag, unescaped.
pub fn attr(line: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let start = line.find(&key)? + key.len();
    let end = line[start..].find('"')? + start;
    Some(
        line[start..end]
            .replace("&quot;", "\"")
            .replace("&lt;", "<")
            .replace("&gt;", ">")
            .replace("&apos;", "'")
            .replace("&amp;", "&"),
    )
}

/// The frames of a PDML document: each starts at its `NAME.format` field.
pub fn frames_of(pdml: &str, name: &str) -> Vec<Shown> {
    let mut out: Vec<Shown> = Vec::new();
    let prefix = format!("{name}.");
    // Each `<field` element's start tag whole, attribute values with newlines included (a
    // `<` inside an attribute value is escaped, so the next element starts at the next `<`).
    for line in pdml.split("<field").skip(1) {
        let line = line.split('<').next().unwrap_or_default();
        let Some(field) = attr(line, "name") else {
            continue;
        };
        if field == format!("{name}.format") {
            out.push(Shown::default());
            continue;
        }
        let Some(frame) = out.last_mut() else {
            continue;
        };
        if field == format!("{name}.frame") {
            frame.hex = attr(line, "value").unwrap_or_default();
        } else if field.starts_with(&prefix) {
            let value = attr(line, "value");
            let show = if line.contains("type=\"bytes\"") {
                value.clone()
            } else {
                attr(line, "show")
            };
            frame.fields.entry(field).or_default().push(FieldShown {
                show: show.unwrap_or_default(),
                value: value.unwrap_or_default(),
            });
        }
    }
    out
}

/// What `decode` says of one frame, as (field name, value, exactness) the dissector must show.
pub struct Expected<'p> {
    p: &'p Protocol,
    /// The dissector's protocol name.
    name: &'p str,
    out: Vec<(String, Value, Option<u32>)>,
    /// The direction a carried packet is read in (0 for a spec without directions).
    carry: usize,
}

impl Expected<'_> {
    fn push(&mut self, abbrev: String, v: &Value, digits: Option<u32>) {
        if !v.is_null() {
            self.out.push((abbrev, v.clone(), digits));
        }
    }

    /// A value of type `ty`: a struct is walked, an enum variant becomes its number.
    fn elem(&mut self, ty: &ValueType, abbrev: &str, v: &Value) {
        match ty {
            ValueType::Struct(si) => self.structure(*si, v),
            ValueType::Enum(ei, _) => {
                let n = match v.as_str() {
                    Some(name) => {
                        let e = &self.p.enums[*ei];
                        let var = e.variants.iter().find(|x| x.name == name).expect("variant");
                        Value::from(var.value)
                    }
                    None => v.clone(),
                };
                self.push(abbrev.to_string(), &n, None);
            }
            ValueType::Scalar { scalar, scale } => {
                let float = scale.is_some() || scalar.prim.is_float();
                let digits = match (scale, scalar.prim) {
                    (Some(s), _) => scaled_digits(s),
                    (None, protocol_spec::ir::Prim::F64) => 15,
                    _ => 6,
                };
                self.push(abbrev.to_string(), v, float.then_some(digits));
            }
            ValueType::Text(_) => self.push(abbrev.to_string(), v, None),
        }
    }

    fn field(&mut self, name: &str, abbrev: &str, kind: &FieldKind, v: &Value, whole: &Value) {
        match kind {
            FieldKind::Padding | FieldKind::Check(_) => {}
            FieldKind::Value { ty, count: None } => self.elem(ty, abbrev, &v[name]),
            FieldKind::Value { ty, .. } | FieldKind::Array { ty, .. } => {
                for item in v[name].as_array().into_iter().flatten() {
                    self.elem(ty, abbrev, item);
                }
            }
            FieldKind::Optional(inner) | FieldKind::When { kind: inner, .. } => {
                self.field(name, abbrev, inner, v, whole)
            }
            FieldKind::Bits { members, .. } | FieldKind::BitStream { members } => {
                let owner = abbrev.rsplit_once('.').expect("owner").0;
                for m in members {
                    let n = match (&whole[&m.name], m.enum_index) {
                        (Value::String(s), Some(ei)) => Value::from(
                            self.p.enums[ei]
                                .variants
                                .iter()
                                .find(|x| x.name == *s)
                                .expect("variant")
                                .value,
                        ),
                        (other, _) => other.clone(),
                    };
                    // A scaled member is its physical value, computed as a scaled field's is.
                    let digits = m.scale.as_ref().filter(|_| m.enum_index.is_none());
                    self.push(format!("{owner}.{}", m.name), &n, digits.map(scaled_digits));
                }
            }
            FieldKind::Packed { scale, .. } => {
                for item in v[name].as_array().into_iter().flatten() {
                    self.push(abbrev.to_string(), item, scale.as_ref().map(scaled_digits));
                }
            }
            // A carried packet `decode` read: its command and payload, which the dissector shows
            // in a subtree; one it could not read, its bytes.
            FieldKind::Bytes { .. } if v[name].is_object() => {
                let carried = &v[name];
                match carried["command"].as_str() {
                    Some(c) => {
                        self.push(format!("{}.command", self.name), &carried["command"], None);
                        let ci = self.p.commands.iter().position(|x| x.name == c);
                        let si = ci.and_then(|ci| {
                            self.p.commands[ci]
                                .payloads
                                .get(self.carry)
                                .copied()
                                .flatten()
                        });
                        if let Some(si) = si {
                            self.structure(si, &carried["payload"]);
                        }
                    }
                    None => self.push(abbrev.to_string(), &carried["bytes"], None),
                }
            }
            FieldKind::Bytes { .. } | FieldKind::NulText { .. } => {
                self.push(abbrev.to_string(), &v[name], None)
            }
            FieldKind::Group { elem, .. } => {
                for item in v[name].as_array().into_iter().flatten() {
                    self.structure(*elem, item);
                }
            }
        }
    }

    fn structure(&mut self, si: usize, v: &Value) {
        let s = &self.p.structs[si];
        for f in &s.fields {
            let abbrev = format!("{}.{}.{}", self.name, s.name, f.name);
            self.field(&f.name, &abbrev, &f.kind, v, v);
        }
    }
}

/// The significant digits a scaled value is compared to: the dissector computes
/// `raw * factor + offset` in double precision, the codec in the physical type, so an `f32`
/// value (`40 * 0.015` is `0.59999996`) agrees to the 7 digits an `f32` holds.
fn scaled_digits(scale: &protocol_spec::ir::Scale) -> u32 {
    if scale.physical == protocol_spec::ir::Prim::F32 {
        7
    } else {
        15
    }
}

/// Whether the dissector's field is the value `decode` printed.
pub fn same(field: &FieldShown, v: &Value, digits: Option<u32>) -> bool {
    let shown = field.show.as_str();
    // Text by its bytes: the field's bytes in hex are those of the string, or the byte list.
    let bytes_are = |bytes: &mut dyn Iterator<Item = u64>| {
        !field.value.is_empty()
            && bytes.map(|b| format!("{b:02x}")).collect::<String>() == field.value
    };
    match (v, digits) {
        (Value::Number(n), Some(d)) => {
            let (Some(want), Ok(got)) = (n.as_f64(), shown.parse::<f64>()) else {
                return false;
            };
            let tolerance = want.abs().max(f64::MIN_POSITIVE) * 10f64.powi(1 - d as i32);
            (got - want).abs() <= tolerance
        }
        (Value::Number(n), None) => {
            shown.parse::<i128>().ok().map(|x| x.to_string()) == Some(n.to_string())
        }
        (Value::Bool(b), _) => matches!((shown, b), ("1" | "True", true) | ("0" | "False", false)),
        (Value::String(s), _) => {
            shown == s
                || shown.replace(':', "").eq_ignore_ascii_case(s)
                || bytes_are(&mut s.bytes().map(u64::from))
        }
        (Value::Array(items), _) => {
            let hex: String = items
                .iter()
                .map(|b| format!("{:02x}", b.as_u64().unwrap_or(0)))
                .collect();
            shown.replace(':', "") == hex
                || bytes_are(&mut items.iter().map(|b| b.as_u64().unwrap_or(256)))
                || items.iter().all(|b| b.as_u64().is_some_and(|b| b < 0x80))
                    && shown
                        .as_bytes()
                        .iter()
                        .zip(items)
                        .all(|(c, b)| u64::from(*c) == b.as_u64().unwrap_or(0))
        }
        _ => false,
    }
}

/// Counts of one comparison.
#[derive(Debug, Default, Clone, Copy)]
pub struct Tally {
    pub frames: usize,
    pub fields: usize,
}

/// The direction of a frame `decode` printed: the one it names (a direction the decoder is
/// given), else the one whose header value equals its constant.
fn frame_direction(p: &Protocol, frame: &Value) -> Option<usize> {
    if let Some(d) = frame.get("direction").and_then(Value::as_str) {
        return p.directions.iter().position(|x| x.name == d);
    }
    p.directions.iter().position(|d| match d.rule {
        protocol_spec::ir::DirectionRule::Equals { value, equals } => p
            .frames
            .first()
            .and_then(|f| f.values.get(value))
            .is_some_and(|v| frame["header"][&v.name].as_u64() == Some(equals)),
        _ => false,
    })
}

/// Compares one frame `decode` printed with the frame the dissector (protocol `name`) showed:
/// every value `decode` prints must be the value of the dissector's field of that name, in order.
/// `direction` is the direction given to both. Returns the number of values compared.
pub fn check_frame(
    p: &Protocol,
    name: &str,
    direction: Option<&str>,
    frame: &Value,
    shown: &Shown,
    label: &str,
) -> usize {
    let mut fields = 0;
    let mut expected = Expected {
        p,
        name,
        out: Vec::new(),
        carry: 0,
    };
    let format = frame["format"].as_str().unwrap_or("");
    for (k, v) in frame["header"].as_object().into_iter().flatten() {
        expected.push(format!("{name}.{format}.{k}"), v, None);
    }
    if let Some(c) = frame.get("command") {
        expected.push(format!("{name}.command"), c, None);
    }
    let si = frame.get("command").and_then(Value::as_str).and_then(|c| {
        let ci = p.commands.iter().position(|x| x.name == c)?;
        let slot = frame
            .get("direction")
            .and_then(Value::as_str)
            .and_then(|d| p.directions.iter().position(|x| x.name == d))
            .unwrap_or(0);
        p.commands[ci].payloads.get(slot).copied().flatten()
    });
    expected.carry = frame_direction(p, frame).unwrap_or(0);
    // A format without dispatch key carries one struct in every frame.
    let si = si.or_else(|| {
        p.frames
            .iter()
            .find(|f| f.name == format)
            .and_then(|f| f.message)
    });
    let message = direction
        .and_then(|d| p.directions.iter().find(|x| x.name == d))
        .and_then(|d| d.message);
    if let Some(si) = message
        .map(|m| m.0)
        .or(si)
        .filter(|_| frame.get("ack").is_none())
    {
        expected.structure(si, &frame["payload"]);
    }
    // Each name's values in order: the i-th value decode prints is the i-th the dissector shows.
    let mut seen: BTreeMap<&str, usize> = BTreeMap::new();
    for (abbrev, v, digits) in &expected.out {
        let i = seen.entry(abbrev).or_default();
        let shown_v = shown.fields.get(abbrev).and_then(|l| l.get(*i));
        assert!(
            shown_v.is_some_and(|s| same(s, v, *digits)),
            "{label}: frame {}: {abbrev}[{i}]: decode {v}, dissector {shown_v:?}",
            frame["hex"]
        );
        *i += 1;
        fields += 1;
    }
    fields
}

/// The dissector's protocol name in a PDML document: `NAME`, or `NAME_spec` for a spec whose
/// name Wireshark has already.
pub fn dissector_name(pdml: &str, spec: &str) -> String {
    if pdml.contains(&format!("<proto name=\"{spec}_spec\"")) {
        format!("{spec}_spec")
    } else {
        spec.to_string()
    }
}

/// The serial frames of a vector file, and its streams.
pub fn vector_bytes(file: &str) -> (Vec<u8>, Vec<Vec<u8>>) {
    let path = root().join("tests/vectors").join(file);
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("vectors")).expect("JSON");
    let mut frames = Vec::new();
    for f in v["frames"].as_array().into_iter().flatten() {
        if let Some(h) = f["hex"].as_str().or(f["uart"]["hex"].as_str()) {
            frames.extend(support::unhex(h));
        }
    }
    let streams = v["streams"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|s| s["hex"].as_str().map(support::unhex))
        .collect();
    (frames, streams)
}
