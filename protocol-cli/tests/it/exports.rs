//! `protocol export csv` and `protocol export mcap`, read back with the `csv` and `mcap`
//! crates and compared with `protocol decode --format json` on the same input: every bundled
//! capture (`examples/captures/`, the CAN log among them) and every spec's golden vectors (one
//! stream of them all). Each side must have the same frames in the same order: the CSV file of
//! a command has one row per frame of that command, each value in the column its path names;
//! each MCAP message is the frame's object, on the channel of its command, and fits the
//! channel's JSON Schema.

use crate::support;

use std::path::{Path, PathBuf};

use serde_json::Value;
use support::{CAPTURES, json_lines, protocol, root, text};

/// Each spec and its vector file, as the Wireshark test pairs them (the registry's `exports`
/// suite, `tests/catalogue.toml`), with the options decode needs (a direction for a spec whose
/// header does not tell it: the first it is given).
const VECTORS: support::Listed<(&str, &str, &[&str])> = support::Listed(vectors);

fn vectors() -> &'static [(&'static str, &'static str, &'static [&'static str])] {
    type Vectors = (&'static str, &'static str, &'static [&'static str]);
    static VECTORS: std::sync::OnceLock<Vec<Vectors>> = std::sync::OnceLock::new();
    VECTORS.get_or_init(|| {
        support::vector_specs("exports")
            .into_iter()
            .map(|(spec, file, directions)| {
                let opts: &'static [&'static str] = match directions.first() {
                    Some(d) => Box::leak(vec!["--direction", *d].into_boxed_slice()),
                    None => &[],
                };
                (spec, file, opts)
            })
            .collect()
    })
}

/// What one comparison covered.
#[derive(Debug, Default, Clone, Copy)]
struct Tally {
    frames: usize,
    values: usize,
}

/// The frames `decode --format json` prints for an input (its events left out).
fn decoded(spec: &str, input: &[&str], opts: &[&str]) -> Vec<Value> {
    let mut args = vec!["decode", spec];
    args.extend(input);
    args.extend(["--format", "json"]);
    args.extend(opts);
    let out = protocol(&args, b"");
    assert!(
        out.status.success(),
        "decode {args:?}: {}",
        text(&out.stderr)
    );
    json_lines(&out.stdout)
        .into_iter()
        .filter(|v| v.get("event").is_none())
        .collect()
}

fn export(what: &str, spec: &str, input: &[&str], opts: &[&str], output: &Path) {
    let mut args = vec!["export", what, spec];
    args.extend(input);
    args.extend(opts);
    let output = output.to_str().expect("utf-8");
    args.extend(["-o", output]);
    let out = protocol(&args, b"");
    assert!(
        out.status.success(),
        "export {args:?}: {}",
        text(&out.stderr)
    );
}

/// A frame's file or channel name: its command, else its frame format.
fn key(frame: &Value) -> String {
    frame
        .get("command")
        .or_else(|| frame.get("format"))
        .and_then(Value::as_str)
        .expect("a frame has a command or a format")
        .to_string()
}

/// Every leaf of a JSON value with its path, written as the test expects a column name
/// (`a.b`, `a[2].c`) and a cell (a string as is, `null` empty, anything else as JSON).
fn leaves(v: &Value, path: &str, out: &mut Vec<(String, String)>) {
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                leaves(x, &p, out);
            }
        }
        Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                leaves(x, &format!("{path}[{i}]"), out);
            }
        }
        Value::String(s) => out.push((path.to_string(), s.clone())),
        Value::Null => out.push((path.to_string(), String::new())),
        other => out.push((path.to_string(), other.to_string())),
    }
}

/// The CSV files of `dir` against the frames: one file per command, a row per frame, each
/// value in its column and no value where the frame has none.
fn compare_csv(label: &str, frames: &[Value], dir: &Path, times: Option<&[String]>) -> usize {
    let mut keys: Vec<String> = Vec::new();
    for f in frames {
        if !keys.contains(&key(f)) {
            keys.push(key(f));
        }
    }
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .expect("the export's directory")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    let mut want_files: Vec<String> = keys.iter().map(|k| format!("{k}.csv")).collect();
    want_files.sort();
    assert_eq!(files, want_files, "{label}: CSV files");
    let mut values = 0;
    for k in &keys {
        let mut reader = csv::Reader::from_path(dir.join(format!("{k}.csv"))).expect("CSV");
        let columns: Vec<String> = reader
            .headers()
            .expect("header")
            .iter()
            .map(String::from)
            .collect();
        let rows: Vec<csv::StringRecord> = reader.records().map(|r| r.expect("row")).collect();
        let mine: Vec<&Value> = frames.iter().filter(|f| key(f) == *k).collect();
        assert_eq!(rows.len(), mine.len(), "{label}: rows of {k}.csv");
        for (row, frame) in rows.iter().zip(&mine) {
            let mut want = Vec::new();
            let mut object = frame.as_object().expect("object").clone();
            object.remove("command");
            object.remove("hex");
            leaves(&Value::Object(object), "", &mut want);
            if let Some(times) = times {
                let i = frame["offset"].as_u64().expect("offset") as usize;
                let cell = row.get(column(&columns, "time", label)).expect("time cell");
                assert_eq!(
                    trim_zeros(cell),
                    trim_zeros(&times[i]),
                    "{label}: time of record {i}"
                );
                values += 1;
            }
            for (path, cell) in &want {
                let got = row.get(column(&columns, path, label)).expect("cell");
                assert_eq!(
                    got, cell,
                    "{label}: {k} at offset {}: `{path}`",
                    frame["offset"]
                );
                values += 1;
            }
            let filled = row.iter().filter(|c| !c.is_empty()).count();
            let expected =
                want.iter().filter(|(_, c)| !c.is_empty()).count() + usize::from(times.is_some());
            assert_eq!(
                filled, expected,
                "{label}: {k}: a row holds a value decode does not print"
            );
        }
    }
    values
}

fn column(columns: &[String], name: &str, label: &str) -> usize {
    columns
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("{label}: no column `{name}` in {columns:?}"))
}

fn trim_zeros(t: &str) -> &str {
    if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.')
    } else {
        t
    }
}

/// Whether `v` fits `schema`, for the keywords the export's schemas use.
fn fits(schema: &Value, v: &Value) -> bool {
    let Some(s) = schema.as_object() else {
        return true;
    };
    if let Some(any) = s.get("anyOf").and_then(Value::as_array) {
        if !any.iter().any(|alt| fits(alt, v)) {
            return false;
        }
    }
    if let Some(c) = s.get("const") {
        if c != v {
            return false;
        }
    }
    if let Some(names) = s.get("enum").and_then(Value::as_array) {
        if !names.contains(v) {
            return false;
        }
    }
    let types: Vec<&str> = match s.get("type") {
        Some(Value::String(t)) => vec![t.as_str()],
        Some(Value::Array(ts)) => ts.iter().filter_map(Value::as_str).collect(),
        _ => Vec::new(),
    };
    let type_of = match v {
        Value::Null => "null",
        Value::Bool(_) => "boolean",
        Value::Number(n) if n.is_f64() => "number",
        Value::Number(_) => "integer",
        Value::String(_) => "string",
        Value::Array(_) => "array",
        Value::Object(_) => "object",
    };
    let type_ok = types.is_empty()
        || types.contains(&type_of)
        || (type_of == "integer" && types.contains(&"number"));
    if !type_ok {
        return false;
    }
    match v {
        Value::Object(m) => {
            let props = s.get("properties").and_then(Value::as_object);
            let required = s.get("required").and_then(Value::as_array);
            required
                .into_iter()
                .flatten()
                .all(|r| m.contains_key(r.as_str().unwrap_or("")))
                && m.iter().all(|(k, x)| match props {
                    // Every key the frame has is declared, with a type it fits.
                    Some(p) => p.get(k).is_some_and(|ps| fits(ps, x)),
                    None => true,
                })
        }
        Value::Array(items) => {
            let max = s
                .get("maxItems")
                .and_then(Value::as_u64)
                .unwrap_or(u64::MAX);
            items.len() as u64 <= max
                && s.get("items")
                    .is_none_or(|is| items.iter().all(|x| fits(is, x)))
        }
        _ => true,
    }
}

/// The MCAP file against the frames: a message per frame in order, on its command's channel,
/// equal to the frame's object and fitting the channel's schema.
fn compare_mcap(label: &str, frames: &[Value], file: &Path, times: Option<&[String]>) -> usize {
    let bytes = std::fs::read(file).expect("the MCAP file");
    let messages: Vec<mcap::Message> = mcap::MessageStream::new(&bytes)
        .expect("an MCAP file")
        .map(|m| m.expect("a message"))
        .collect();
    assert_eq!(messages.len(), frames.len(), "{label}: MCAP messages");
    let mut values = 0;
    let mut last = 0;
    for (m, frame) in messages.iter().zip(frames) {
        assert_eq!(
            m.channel.topic,
            format!("/{}", key(frame)),
            "{label}: topic"
        );
        assert_eq!(m.channel.message_encoding, "json", "{label}: encoding");
        let schema = m.channel.schema.as_ref().expect("a schema");
        assert_eq!(schema.encoding, "jsonschema", "{label}: schema encoding");
        let schema: Value = serde_json::from_slice(&schema.data).expect("a JSON schema");
        let got: Value = serde_json::from_slice(&m.data).expect("a JSON message");
        assert_eq!(
            &got, frame,
            "{label}: message at offset {}",
            frame["offset"]
        );
        assert!(
            fits(&schema, &got),
            "{label}: {got} does not fit its schema {schema}"
        );
        assert!(
            m.log_time >= last,
            "{label}: log times go back at offset {}",
            frame["offset"]
        );
        last = m.log_time;
        if let Some(times) = times {
            let i = frame["offset"].as_u64().expect("offset") as usize;
            let want = protocol_cli::export::time_ns(&times[i]).expect("a time");
            assert_eq!(m.log_time, want, "{label}: log time of record {i}");
        }
        let mut all = Vec::new();
        leaves(frame, "", &mut all);
        values += all.len();
    }
    values
}

/// Exports an input both ways and compares both with decode.
fn round_trip(
    label: &str,
    spec: &str,
    input: &[&str],
    opts: &[&str],
    times: Option<&[String]>,
) -> (Tally, Tally) {
    let frames = decoded(spec, input, opts);
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("exports")
        .join(label);
    let _ = std::fs::remove_dir_all(&dir);
    export("csv", spec, input, opts, &dir.join("csv"));
    let csv = compare_csv(label, &frames, &dir.join("csv"), times);
    let file = dir.join("frames.mcap");
    export("mcap", spec, input, opts, &file);
    let mcap = compare_mcap(label, &frames, &file, times);
    println!(
        "{label}: {} frames; CSV {csv} values, MCAP {mcap} values",
        frames.len()
    );
    let n = frames.len();
    (
        Tally {
            frames: n,
            values: csv,
        },
        Tally {
            frames: n,
            values: mcap,
        },
    )
}

#[test]
fn captures_export_as_decode_decodes() {
    let mut total = (Tally::default(), Tally::default());
    for (spec, name, opts) in CAPTURES {
        let input = format!("examples/captures/{name}.bin");
        let (c, m) = round_trip(name, spec, &[&input], opts, None);
        assert!(c.frames > 0, "{name}: no frame");
        total.0.frames += c.frames;
        total.0.values += c.values;
        total.1.values += m.values;
    }
    // The CAN log: the times of its records are the rows' times and the messages' log times.
    let log = root().join("examples/captures/scout_can.log");
    let (records, _) = protocol_cli::candump::parse(&std::fs::read_to_string(&log).expect("log"));
    let times: Vec<String> = records
        .iter()
        .map(|(_, r)| r.time.clone().expect("a logged time"))
        .collect();
    let (c, m) = round_trip(
        "scout_can",
        "specs/scout.toml",
        &["--candump", "examples/captures/scout_can.log"],
        &[],
        Some(&times),
    );
    assert!(c.frames > 0, "scout_can: no frame");
    total.0.frames += c.frames;
    total.0.values += c.values;
    total.1.values += m.values;
    println!(
        "captures: {} frames; CSV {} values, MCAP {} values compared",
        total.0.frames, total.0.values, total.1.values
    );
}

/// The serial frames of a vector file, back to back.
fn vector_stream(file: &str) -> Vec<u8> {
    let path = root().join("tests/vectors").join(file);
    let v: Value =
        serde_json::from_str(&std::fs::read_to_string(&path).expect("vectors")).expect("JSON");
    let mut bytes = Vec::new();
    for f in v["frames"].as_array().into_iter().flatten() {
        if let Some(h) = f["hex"].as_str().or(f["uart"]["hex"].as_str()) {
            bytes.extend(support::unhex(h));
        }
    }
    bytes
}

#[test]
fn golden_vectors_export_as_decode_decodes() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("exports");
    std::fs::create_dir_all(&dir).expect("dir");
    let mut total = (Tally::default(), Tally::default());
    for (spec, file, opts) in VECTORS {
        let input = dir.join(format!("{spec}.vectors.bin"));
        std::fs::write(&input, vector_stream(file)).expect("write");
        let spec_path = format!("specs/{spec}.toml");
        let label = format!("{spec}-vectors");
        let (c, m) = round_trip(
            &label,
            &spec_path,
            &[input.to_str().expect("utf-8")],
            opts,
            None,
        );
        assert!(c.frames > 0, "{label}: no frame");
        total.0.frames += c.frames;
        total.0.values += c.values;
        total.1.values += m.values;
    }
    println!(
        "golden vectors: {} frames; CSV {} values, MCAP {} values compared",
        total.0.frames, total.0.values, total.1.values
    );
}
