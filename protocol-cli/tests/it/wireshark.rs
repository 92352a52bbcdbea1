//! The Wireshark dissector of `protocol gen wireshark`, run headless in `tshark`, against the
//! run-time codec (`protocol decode`) on the same bytes: for every bundled spec, the golden
//! vectors' frames (one capture of them all, cut into 64-byte packets, so frames straddle
//! packets) and the vector files' noisy streams (cut into 7-byte packets). Both sides must find
//! the same frames (same bytes, same command), and every value `decode` prints must be the
//! value of the dissector's field of that name (floats to the 6 or 15 significant digits that
//! tshark prints them with).
//!
//! The test needs `tshark`. Without it, it says so and checks nothing more, unless
//! `PROTOCOL_REQUIRE_TSHARK` is set, as CI sets it: then a missing tshark fails the test.

use crate::support;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use protocol_spec::ir::{FieldKind, Protocol, ValueType};
use serde_json::Value;
use support::{interpreter, json_lines, protocol, root, text};

/// Each spec, its vector file and the directions it is decoded in (a spec whose header does not
/// tell them is decoded in each).
const SPECS: &[(&str, &str, &[&str])] = &[
    ("crsf", "crsf.json", &[]),
    ("dynamixel", "dynamixel_protocol2.json", &[]),
    (
        "dynamixel1",
        "dynamixel_protocol1.json",
        &["request", "response"],
    ),
    ("hflink", "hflink.json", &[]),
    ("ibus", "ibus.json", &[]),
    ("mavlink", "mavlink.json", &[]),
    ("msp", "msp.json", &[]),
    ("referee", "robomaster_referee.json", &[]),
    ("referee2018", "robomaster_referee.json", &[]),
    ("roborts", "roborts_sdk.json", &[]),
    ("sbus", "sbus.json", &[]),
    ("scout", "agilex_scout.json", &[]),
    ("ubx", "ubx.json", &[]),
];

fn tshark_available() -> bool {
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

/// One frame as the dissector shows it: its bytes, and every field's `show` values in order.
#[derive(Debug, Default)]
struct Shown {
    hex: String,
    fields: BTreeMap<String, Vec<String>>,
}

/// The value of an XML attribute on a PDML line, unescaped.
fn attr(line: &str, name: &str) -> Option<String> {
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
fn frames_of(pdml: &str, name: &str) -> Vec<Shown> {
    let mut out: Vec<Shown> = Vec::new();
    let prefix = format!("{name}.");
    for line in pdml.lines() {
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
            let shown = if line.contains("type=\"bytes\"") {
                attr(line, "value")
            } else {
                attr(line, "show")
            };
            frame
                .fields
                .entry(field)
                .or_default()
                .push(shown.unwrap_or_default());
        }
    }
    out
}

/// What `decode` says of one frame, as (field name, value, exactness) the dissector must show.
struct Expected<'p> {
    p: &'p Protocol,
    /// The dissector's protocol name.
    name: &'p str,
    out: Vec<(String, Value, Option<u32>)>,
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
                    (Some(_), _) | (None, protocol_spec::ir::Prim::F64) => 15,
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
            FieldKind::Optional(inner) => self.field(name, abbrev, inner, v, whole),
            FieldKind::Bits { members, .. } => {
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
                    self.push(format!("{owner}.{}", m.name), &n, None);
                }
            }
            FieldKind::Packed { scale, .. } => {
                for item in v[name].as_array().into_iter().flatten() {
                    self.push(abbrev.to_string(), item, scale.map(|_| 15));
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

/// Whether the dissector's `shown` text is the value `decode` printed.
fn same(shown: &str, v: &Value, digits: Option<u32>) -> bool {
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
        (Value::String(s), _) => shown == s || shown.replace(':', "").eq_ignore_ascii_case(s),
        (Value::Array(items), _) => {
            let hex: String = items
                .iter()
                .map(|b| format!("{:02x}", b.as_u64().unwrap_or(0)))
                .collect();
            shown.replace(':', "") == hex
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
struct Tally {
    frames: usize,
    fields: usize,
}

/// Runs the dissector and `decode` over `bytes`, cut into packets of `chunk` bytes, and
/// compares them frame by frame and field by field.
fn compare(
    spec: &str,
    lua: &Path,
    bytes: &[u8],
    chunk: usize,
    direction: Option<&str>,
    label: &str,
) -> Tally {
    let p = interpreter(spec);
    let p = p.protocol();
    let dir = lua.parent().expect("dir");
    let hex: String = bytes.iter().map(|b| format!("{b:02x}")).collect();
    let pcap = dir.join(format!("{label}.pcap"));
    let pcap_s = pcap.to_str().expect("utf-8 path");
    let out = protocol(
        &[
            "export",
            "pcap",
            "--hex",
            "--chunk",
            &chunk.to_string(),
            "-o",
            pcap_s,
        ],
        hex.as_bytes(),
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let spec_path = format!("specs/{spec}.toml");
    let mut args = vec!["decode", spec_path.as_str(), "--hex", "--format", "json"];
    if let Some(d) = direction {
        args.extend(["--direction", d]);
    }
    let decoded = protocol(&args, hex.as_bytes());
    let frames: Vec<Value> = json_lines(&decoded.stdout)
        .into_iter()
        .filter(|f| f.get("hex").is_some())
        .collect();
    let mut tshark = Command::new("tshark");
    tshark
        .arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .args(["-r", pcap_s, "-T", "pdml"]);
    if let Some(d) = direction {
        tshark.args(["-o", &format!("{spec}.direction:{d}")]);
    }
    let run = tshark.output().expect("tshark runs");
    let err = text(&run.stderr);
    assert!(
        run.status.success() && !err.contains("Lua"),
        "{label}: tshark: {err}"
    );
    let pdml = text(&run.stdout);
    // The dissector of a spec whose name Wireshark has already is `NAME_spec`.
    let name = if pdml.contains(&format!("<proto name=\"{spec}_spec\"")) {
        format!("{spec}_spec")
    } else {
        spec.to_string()
    };
    let shown = frames_of(&pdml, &name);
    let got: Vec<&str> = shown.iter().map(|s| s.hex.as_str()).collect();
    let want: Vec<&str> = frames
        .iter()
        .map(|f| f["hex"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(
        got, want,
        "{label}: the dissector and decode find other frames"
    );
    let mut tally = Tally {
        frames: frames.len(),
        fields: 0,
    };
    for (frame, shown) in frames.iter().zip(&shown) {
        let mut expected = Expected {
            p,
            name: &name,
            out: Vec::new(),
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
            tally.fields += 1;
        }
    }
    tally
}

/// The serial frames of a vector file, and its streams.
fn vector_bytes(file: &str) -> (Vec<u8>, Vec<Vec<u8>>) {
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

#[test]
fn every_spec_dissects_as_decode_decodes() {
    if !tshark_available() {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("wireshark");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut total = Tally::default();
    let failed = std::cell::RefCell::new(Vec::new());
    for (spec, file, directions) in SPECS {
        let out = protocol(
            &[
                "gen",
                "wireshark",
                &format!("specs/{spec}.toml"),
                "-o",
                dir.to_str().expect("utf-8"),
            ],
            b"",
        );
        assert!(out.status.success(), "{spec}: {}", text(&out.stderr));
        let lua = dir.join(format!("{spec}.lua"));
        let (frames, streams) = vector_bytes(file);
        let passes: Vec<Option<&str>> = if directions.is_empty() {
            vec![None]
        } else {
            directions.iter().map(|d| Some(*d)).collect()
        };
        for d in passes {
            let tag = format!("{spec}{}", d.map_or(String::new(), |d| format!("-{d}")));
            let run = |bytes: &[u8], chunk: usize, label: String| {
                std::panic::catch_unwind(|| compare(spec, &lua, bytes, chunk, d, &label))
                    .unwrap_or_else(|_| {
                        failed.borrow_mut().push(label);
                        Tally::default()
                    })
            };
            let vectors = run(&frames, 64, format!("{tag}-vectors"));
            let mut noisy = Tally::default();
            for (k, s) in streams.iter().enumerate() {
                let t = run(s, 7, format!("{tag}-stream{k}"));
                noisy.frames += t.frames;
                noisy.fields += t.fields;
            }
            println!(
                "{tag}: vectors {} frames, {} fields; noisy streams {} frames, {} fields",
                vectors.frames, vectors.fields, noisy.frames, noisy.fields
            );
            if vectors.frames == 0 {
                failed
                    .borrow_mut()
                    .push(format!("{tag}: no vector frame compared"));
            }
            total.frames += vectors.frames + noisy.frames;
            total.fields += vectors.fields + noisy.fields;
        }
    }
    println!(
        "total: {} frames, {} fields compared",
        total.frames, total.fields
    );
    assert!(failed.borrow().is_empty(), "failed: {:?}", failed.borrow());
}
