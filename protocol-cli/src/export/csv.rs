//! CSV export: one table per command, one row per frame, one column per value.
//!
//! Column names are the paths of the values in the frame's JSON object: `header.sender`,
//! `payload.x`; array elements and group entries take their index in brackets
//! (`payload.voltages[3]`, `payload.sats[0].id`). Values are written as the JSON output has
//! them: enum variants by name, numbers in their shortest round-trip form, `true`/`false`, an
//! empty cell for an absent optional value. A table's columns are those of all its frames, in
//! order of first appearance (a frame with fewer array elements leaves cells empty). The
//! command (the file's name) and the frame's hex are not columns; a `time` column comes first
//! when the capture has receive times (seconds since the Unix epoch).

use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::{Record, by_key};

/// The values of a JSON object as (column, cell) pairs, depth first, in the object's order.
///
/// ```
/// use protocol_cli::export::csv::flatten;
/// let v = serde_json::json!({"header": {"seq": 3}, "payload": {"v": [1, 2], "mode": "AUTO"}});
/// let cells: Vec<(String, String)> = flatten(&v);
/// assert_eq!(cells, [
///     ("header.seq".to_string(), "3".to_string()),
///     ("payload.v[0]".into(), "1".into()),
///     ("payload.v[1]".into(), "2".into()),
///     ("payload.mode".into(), "AUTO".into()),
/// ]);
/// ```
pub fn flatten(value: &Value) -> Vec<(String, String)> {
    let mut out = Vec::new();
    walk(value, String::new(), &mut out);
    out
}

fn walk(value: &Value, path: String, out: &mut Vec<(String, String)>) {
    match value {
        Value::Object(map) => {
            for (k, v) in map {
                let sub = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                walk(v, sub, out);
            }
        }
        Value::Array(items) => {
            for (i, v) in items.iter().enumerate() {
                walk(v, format!("{path}[{i}]"), out);
            }
        }
        Value::Null => out.push((path, String::new())),
        Value::String(s) => out.push((path, s.clone())),
        Value::Bool(b) => out.push((path, b.to_string())),
        Value::Number(n) => out.push((path, n.to_string())),
    }
}

/// The keys of a frame object that are not columns.
const NOT_COLUMNS: [&str; 2] = ["command", "hex"];

/// The table of some frames of one command: the header row, then one row per frame.
pub fn table(records: &[&Record]) -> Vec<Vec<String>> {
    let timed = records.iter().any(|r| r.time_ns.is_some());
    let rows: Vec<Vec<(String, String)>> = records
        .iter()
        .map(|r| {
            let mut cells = Vec::new();
            if timed {
                let time = r.time_ns.map_or_else(String::new, |ns| {
                    format!("{}.{:09}", ns / 1_000_000_000, ns % 1_000_000_000)
                });
                cells.push(("time".to_string(), time));
            }
            if let Value::Object(map) = &r.value {
                for (k, v) in map
                    .iter()
                    .filter(|(k, _)| !NOT_COLUMNS.contains(&k.as_str()))
                {
                    walk(v, k.clone(), &mut cells);
                }
            }
            cells
        })
        .collect();
    let mut columns: Vec<&str> = Vec::new();
    for (name, _) in rows.iter().flatten() {
        if !columns.contains(&name.as_str()) {
            columns.push(name);
        }
    }
    let mut out = vec![columns.iter().map(|c| c.to_string()).collect::<Vec<_>>()];
    for row in &rows {
        let cells: HashMap<&str, &str> =
            row.iter().map(|(n, v)| (n.as_str(), v.as_str())).collect();
        out.push(
            columns
                .iter()
                .map(|c| cells.get(c).map_or_else(String::new, |v| v.to_string()))
                .collect(),
        );
    }
    out
}

/// Writes one `KEY.csv` per command (or frame format without commands) into `dir`; returns
/// the files written with their number of frames.
///
/// # Errors
/// When `dir` cannot be created or a file cannot be written.
pub fn write_dir(records: &[Record], dir: &Path) -> io::Result<Vec<(PathBuf, usize)>> {
    std::fs::create_dir_all(dir)?;
    let mut written = Vec::new();
    for (key, group) in by_key(records) {
        let path = dir.join(format!("{key}.csv"));
        let mut w = ::csv::Writer::from_path(&path)?;
        for row in table(&group) {
            w.write_record(&row)?;
        }
        w.flush()?;
        written.push((path, group.len()));
    }
    Ok(written)
}
