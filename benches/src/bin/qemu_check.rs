//! Checks the output of the QEMU firmware (`examples/firmware-qemu`: the Rust firmware and the
//! C one in its `c/` directory) against the golden vectors and prints their instruction counts.
//!
//! Every golden frame must have its line: a frame that the run-time codec (`protocol-dynamic`,
//! on the host) decodes must be `ok` on the firmware with the same command and, encoded back,
//! the vector's exact bytes; a frame it refuses must be an `error` with the same runtime error
//! (the Rust firmware prints the error's text, the C firmware the name of its `ERR_` code).
//! Every stream must yield exactly its `expected_frames` (offset and bytes). Then the `measure`
//! lines become instructions per frame and per byte: SysTick ticks times the instructions per
//! tick the firmware's own calibration line measured, less the loop that only walks the chunks
//! (measured by the same firmware, per stream).
//!
//! Usage: `qemu-check OUTPUT [C_OUTPUT]` (the firmwares' semihosting output); exit status 1 on a
//! mismatch. `qemu-check --c-vectors FILE` writes the golden vectors as a C header for the C
//! firmware, so that both firmwares decode the same bytes.

use std::collections::BTreeMap;
use std::process::ExitCode;

use protocol_dynamic::{Interpreter, hex};
use serde_json::Value;

/// The spec and vector file of each stream the firmwares decode.
const SPECS: [(&str, &str); 2] = [
    ("hflink", "hflink.json"),
    ("referee", "robomaster_referee.json"),
];

/// Which firmware printed an output: they differ only in how a refused frame is named.
#[derive(Clone, Copy, PartialEq)]
enum Firmware {
    Rust,
    C,
}

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
fn expected_frame_line(
    fw: Firmware,
    interp: &Interpreter,
    spec: &str,
    name: &str,
    frame: &[u8],
) -> String {
    let codec = interp.codec();
    match codec.parse(0, frame) {
        Ok(d) => {
            let command = d
                .command
                .map(|c| interp.protocol().commands[c].name.clone())
                .unwrap_or_default();
            format!("frame {spec} {name} ok {command} {}", hex(frame))
        }
        Err(issue) if fw == Firmware::C => {
            format!(
                "frame {spec} {name} error {}",
                protocol_codegen::c::error_name(&issue.to_runtime())
            )
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

fn check(fw: Firmware, output: &str) -> Result<Vec<String>, Vec<String>> {
    let got: Vec<&str> = output.lines().map(str::trim_end).collect();
    let mut errors = Vec::new();
    let mut checked = 0;
    for (spec, file) in SPECS {
        let interp = Interpreter::load(format!(
            "{}/../specs/{spec}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .expect("spec loads");
        let v = vectors(file);
        for f in v["frames"].as_array().expect("frames") {
            let name = f["name"].as_str().expect("name");
            let want = expected_frame_line(fw, &interp, spec, name, &bytes(f));
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

/// One `measure` line of a firmware, its loop's ticks subtracted: (spec, decoder, frames,
/// bytes, instructions).
type Row = (String, String, f64, f64, f64);

/// The `measure` lines of one output as instructions, and the instructions per tick.
fn measurements(output: &str) -> Result<(f64, Vec<Row>), String> {
    let mut per_tick = None;
    let mut lines = Vec::new();
    let mut loops = BTreeMap::new();
    for line in output.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        let num = |s: &str| s.parse::<f64>().map_err(|_| line.to_string());
        match w.as_slice() {
            ["calibrate", insns, ticks] => per_tick = Some(num(insns)? / num(ticks)?),
            ["measure", spec, "loop", _, _, ticks] => {
                loops.insert(spec.to_string(), num(ticks)?);
            }
            ["measure", spec, decoder, frames, bytes, ticks] => lines.push((
                spec.to_string(),
                decoder.to_string(),
                num(frames)?,
                num(bytes)?,
                num(ticks)?,
            )),
            _ => {}
        }
    }
    let per_tick = per_tick.ok_or("no calibrate line")?;
    let rows = lines
        .into_iter()
        .map(|(spec, decoder, frames, bytes, ticks)| {
            let base = loops
                .get(&spec)
                .copied()
                .ok_or(format!("no loop measured for {spec}"))?;
            Ok((spec, decoder, frames, bytes, (ticks - base) * per_tick))
        })
        .collect::<Result<_, String>>()?;
    Ok((per_tick, rows))
}

/// The `measure` lines of the outputs as one Markdown table of instructions, with the ratios of
/// instructions per decoded frame.
fn counts(outputs: &[(&str, &str)]) -> Result<Vec<String>, String> {
    let mut out = Vec::new();
    let mut rows = Vec::new();
    for (label, output) in outputs {
        let (per_tick, r) = measurements(output).map_err(|e| format!("{label}: {e}"))?;
        out.push(format!(
            "{label}: instructions per SysTick tick (calibrated): {per_tick:.2}"
        ));
        rows.extend(r);
    }
    out.push("| stream | decoder | frames | bytes | instructions | per frame | per byte |".into());
    out.push("|---|---|---:|---:|---:|---:|---:|".into());
    let mut per_frame = BTreeMap::new();
    for (spec, decoder, frames, bytes, insns) in &rows {
        per_frame.insert((spec.as_str(), decoder.as_str()), insns / frames);
        out.push(format!(
            "| {spec} | {decoder} | {frames} | {bytes} | {insns:.0} | {:.0} | {:.1} |",
            insns / frames,
            insns / bytes
        ));
    }
    for (spec, a, b) in [
        ("hflink", "generated", "hand"),
        ("hflink", "C", "hand"),
        ("hflink", "C", "generated"),
        ("referee", "C", "generated"),
    ] {
        if let (Some(x), Some(y)) = (per_frame.get(&(spec, a)), per_frame.get(&(spec, b))) {
            out.push(format!(
                "{spec} instructions per decoded frame, {a} / {b}: {:.2}",
                x / y
            ));
        }
    }
    Ok(out)
}

/// The golden frames and streams as C arrays (`vector` tables named `SPEC_frames` and
/// `SPEC_streams`), for the C firmware.
fn c_vectors() -> String {
    let mut out = String::from(
        "/* Written by `qemu-check --c-vectors` from tests/vectors/. */\n\
         #include <stddef.h>\n#include <stdint.h>\n\n\
         typedef struct vector {\n    const char *name;\n    const uint8_t *bytes;\n    size_t len;\n} vector;\n",
    );
    for (spec, file) in SPECS {
        let v = vectors(file);
        for key in ["frames", "streams"] {
            let items = v[key].as_array().expect("an array");
            for (i, item) in items.iter().enumerate() {
                let b = bytes(item);
                let list: Vec<String> = b.iter().map(|x| format!("0x{x:02x}")).collect();
                // C99 has no empty initialiser: an empty vector gets one byte it does not use.
                let list = if list.is_empty() {
                    "0".to_string()
                } else {
                    list.join(", ")
                };
                out.push_str(&format!(
                    "\nstatic const uint8_t {spec}_{key}_{i}[] = {{{list}}};\n"
                ));
            }
            out.push_str(&format!("\nstatic const vector {spec}_{key}[] = {{\n"));
            for (i, item) in items.iter().enumerate() {
                let name = item["name"].as_str().expect("a name");
                let len = bytes(item).len();
                out.push_str(&format!("    {{\"{name}\", {spec}_{key}_{i}, {len}u}},\n"));
            }
            out.push_str("};\n");
        }
    }
    out
}

fn read(path: &str) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))
}

fn run(args: &[String]) -> Result<Vec<String>, Vec<String>> {
    let one = |e: String| vec![e];
    let outputs: Vec<(Firmware, &str, String)> = match args {
        [flag, file] if flag == "--c-vectors" => {
            std::fs::write(file, c_vectors()).map_err(|e| one(format!("{file}: {e}")))?;
            return Ok(Vec::new());
        }
        [rust] => vec![(Firmware::Rust, "Rust", read(rust).map_err(one)?)],
        [rust, c] => vec![
            (Firmware::Rust, "Rust", read(rust).map_err(one)?),
            (Firmware::C, "C", read(c).map_err(one)?),
        ],
        _ => {
            return Err(one(
                "usage: qemu-check OUTPUT [C_OUTPUT] | qemu-check --c-vectors FILE".into(),
            ));
        }
    };
    let mut lines = Vec::new();
    for (fw, label, output) in &outputs {
        let checked = check(*fw, output).map_err(|errors| {
            errors
                .into_iter()
                .map(|e| format!("{label} firmware: {e}"))
                .collect::<Vec<_>>()
        })?;
        lines.extend(
            checked
                .into_iter()
                .map(|l| format!("{label} firmware: {l}")),
        );
    }
    let texts: Vec<(&str, &str)> = outputs.iter().map(|(_, l, o)| (*l, o.as_str())).collect();
    lines.extend(counts(&texts).map_err(one)?);
    Ok(lines)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(lines) => {
            lines.iter().for_each(|l| println!("{l}"));
            ExitCode::SUCCESS
        }
        Err(errors) => {
            errors.iter().for_each(|e| eprintln!("error: {e}"));
            ExitCode::FAILURE
        }
    }
}
