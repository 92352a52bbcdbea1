//! Checks the output of the QEMU firmware (`examples/firmware-qemu`) against the golden vectors
//! and prints its instruction counts.
//!
//! Every golden frame must have its line: a frame that the run-time codec (`protocol-dynamic`,
//! on the host) decodes must be `ok` on the firmware with the same command and, encoded back,
//! the vector's exact bytes; a frame it refuses must be an `error` with the same runtime error.
//! Every stream must yield exactly its `expected_frames` (offset and bytes). Then the `measure`
//! lines become instructions per frame and per byte: SysTick ticks times the instructions per
//! tick the firmware's own calibration line measured, less the loop that only walks the chunks.
//!
//! Usage: `qemu-check OUTPUT` (the firmware's semihosting output). Exit status 1 on a mismatch.

use std::collections::BTreeMap;
use std::process::ExitCode;

use protocol_dynamic::{Interpreter, hex};
use serde_json::Value;

fn vectors(file: &str) -> Value {
    let path = format!("{}/../tests/vectors/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    serde_json::from_str(&text).expect("vector JSON")
}

fn bytes(v: &Value) -> Vec<u8> {
    let text: String = v["hex"].as_str().expect("hex").split_whitespace().collect();
    protocol_dynamic::parse_hex(&text).expect("vector hex")
}

/// The line the firmware must print for golden frame `name` of `spec`.
fn expected_frame_line(interp: &Interpreter, spec: &str, name: &str, frame: &[u8]) -> String {
    let codec = interp.codec();
    match codec.parse(0, frame) {
        Ok(d) => {
            let command = d
                .command
                .map(|c| interp.protocol().commands[c].name.clone())
                .unwrap_or_default();
            format!("frame {spec} {name} ok {command} {}", hex(frame))
        }
        Err(issue) => format!("frame {spec} {name} error {}", issue.to_runtime()),
    }
}

/// The lines the firmware must print for a stream vector.
fn expected_stream_lines(interp: &Interpreter, spec: &str, stream: &Value) -> Vec<String> {
    let name = stream["name"].as_str().expect("name");
    let codec = interp.codec();
    let mut lines: Vec<String> = stream["expected_frames"]
        .as_array()
        .expect("expected_frames")
        .iter()
        .map(|f| {
            let b = bytes(f);
            let verdict = if codec.decode_frame(0, &b).is_ok() {
                ""
            } else {
                " undecodable"
            };
            format!(
                "stream {spec} {name} frame {} {}{verdict}",
                f["offset"],
                hex(&b)
            )
        })
        .collect();
    let n = lines.len();
    lines.push(format!("stream {spec} {name} stats {n} "));
    lines
}

fn check(output: &str) -> Result<Vec<String>, Vec<String>> {
    let got: Vec<&str> = output.lines().map(str::trim_end).collect();
    let mut errors = Vec::new();
    let mut checked = 0;
    for (spec, file) in [
        ("hflink", "hflink.json"),
        ("referee", "robomaster_referee.json"),
    ] {
        let interp = Interpreter::load(format!(
            "{}/../specs/{spec}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .expect("spec loads");
        let v = vectors(file);
        for f in v["frames"].as_array().expect("frames") {
            let name = f["name"].as_str().expect("name");
            let want = expected_frame_line(&interp, spec, name, &bytes(f));
            if !got.contains(&want.as_str()) {
                let prefix = format!("frame {spec} {name} ");
                let seen = got
                    .iter()
                    .find(|l| l.starts_with(&prefix))
                    .unwrap_or(&"nothing");
                errors.push(format!("expected `{want}`, the firmware printed `{seen}`"));
            }
            checked += 1;
        }
        for s in v["streams"].as_array().expect("streams") {
            let want = expected_stream_lines(&interp, spec, s);
            let name = s["name"].as_str().expect("name");
            let prefix = format!("stream {spec} {name} ");
            let seen: Vec<&str> = got
                .iter()
                .copied()
                .filter(|l| l.starts_with(&prefix))
                .collect();
            let (frames, stats) = want.split_at(want.len() - 1);
            let matches = seen.len() == want.len()
                && seen[..frames.len()] == *frames
                && seen[frames.len()].starts_with(&stats[0]);
            if !matches {
                errors.push(format!(
                    "stream {spec} {name}: expected {want:#?}, got {seen:#?}"
                ));
            }
            checked += 1;
        }
    }
    if !got.contains(&"done") {
        errors.push("the firmware did not finish (no `done` line)".into());
    }
    if errors.is_empty() {
        Ok(vec![format!(
            "{checked} golden frames and streams decoded on the firmware as expected"
        )])
    } else {
        Err(errors)
    }
}

/// The `measure` lines as a Markdown table of instructions.
fn counts(output: &str) -> Result<Vec<String>, String> {
    let mut per_tick = None;
    let mut rows = Vec::new();
    let mut loops = BTreeMap::new();
    for line in output.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["calibrate", insns, ticks] => {
                let (i, t): (f64, f64) = (
                    insns.parse().map_err(|_| line)?,
                    ticks.parse().map_err(|_| line)?,
                );
                per_tick = Some(i / t);
            }
            ["measure", spec, "loop", _, _, ticks] => {
                loops.insert(spec.to_string(), ticks.parse::<f64>().map_err(|_| line)?);
            }
            ["measure", spec, decoder, frames, bytes, ticks] => rows.push((
                spec.to_string(),
                decoder.to_string(),
                frames.parse::<f64>().map_err(|_| line)?,
                bytes.parse::<f64>().map_err(|_| line)?,
                ticks.parse::<f64>().map_err(|_| line)?,
            )),
            _ => {}
        }
    }
    let per_tick = per_tick.ok_or("no calibrate line")?;
    let mut out = vec![
        format!("instructions per SysTick tick (calibrated): {per_tick:.2}"),
        "| stream | decoder | frames | bytes | instructions | per frame | per byte |".into(),
        "|---|---|---:|---:|---:|---:|---:|".into(),
    ];
    let mut per_frame = BTreeMap::new();
    for (spec, decoder, frames, bytes, ticks) in &rows {
        let base = loops.get(spec).copied().unwrap_or(0.0);
        let insns = (ticks - base) * per_tick;
        per_frame.insert((spec.clone(), decoder.clone()), insns / frames);
        out.push(format!(
            "| {spec} | {decoder} | {frames} | {bytes} | {insns:.0} | {:.0} | {:.1} |",
            insns / frames,
            insns / bytes
        ));
    }
    let key = |d: &str| ("hflink".to_string(), d.to_string());
    if let (Some(g), Some(h)) = (
        per_frame.get(&key("generated")),
        per_frame.get(&key("hand")),
    ) {
        out.push(format!(
            "hflink instructions per decoded frame, generated / hand-written: {:.2}",
            g / h
        ));
    }
    Ok(out)
}

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: qemu-check OUTPUT");
        return ExitCode::from(2);
    };
    let output = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(e) => {
            eprintln!("{path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    match check(&output) {
        Ok(lines) => lines.iter().for_each(|l| println!("{l}")),
        Err(errors) => {
            errors.iter().for_each(|e| eprintln!("error: {e}"));
            return ExitCode::FAILURE;
        }
    }
    match counts(&output) {
        Ok(lines) => {
            lines.iter().for_each(|l| println!("{l}"));
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
