//! Synthetic specs for the scaling measurements.
//!
//! - `synth spec N`: prints a spec of N commands (`benches/footprint.sh` builds a firmware from
//!   it);
//! - `synth expand [N...]`: loads, validates and expands specs of N commands in process (what
//!   the `protocol!` macro does) and prints, per N, the median time of `compile` and of
//!   `codegen::expand` over 5 runs, and the size of the expansion;
//! - `synth expand-file SPEC...`: the same for spec files (`specs/mavlink-common.toml`, the
//!   whole MAVLink common dialect, against `specs/mavlink.toml`).
//!
//! Build it in the dev profile to time expansion as the macro runs it: cargo builds
//! proc-macros without optimizations unless a profile says otherwise.

use std::process::ExitCode;
use std::time::{Duration, Instant};

use protocol_benches::synth;
use protocol_codegen::codegen::{RuntimePath, expand, expand_pretty};
use protocol_codegen::source::SpecSource;

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let numbers = |from: usize| -> Result<Vec<usize>, String> {
        args[from..]
            .iter()
            .map(|a| a.parse().map_err(|_| format!("not a number: {a}")))
            .collect()
    };
    let result = match args.first().map(String::as_str) {
        Some("spec") => numbers(1).and_then(|n| match n.as_slice() {
            [n] if *n <= 256 => {
                print!("{}", synth::spec(*n));
                Ok(())
            }
            _ => Err("usage: synth spec N (N <= 256)".into()),
        }),
        Some("expand") => numbers(1).map(|mut n| {
            if n.is_empty() {
                n = vec![16, 64, 256];
            }
            let specs = n.iter().map(|&n| (n.to_string(), synth::spec(n.min(256))));
            expand_table("commands", specs.collect());
        }),
        Some("expand-file") if args.len() > 1 => args[1..]
            .iter()
            .map(|path| {
                let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
                Ok((path.clone(), text))
            })
            .collect::<Result<Vec<_>, String>>()
            .map(|specs| expand_table("spec", specs)),
        _ => Err("usage: synth spec N | synth expand [N...] | synth expand-file SPEC...".into()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("synth: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Times loading and expanding each `(label, spec text)`, one table row each.
fn expand_table(what: &str, specs: Vec<(String, String)>) {
    println!(
        "| {what} | spec bytes | compile (ms) | expand (ms) | total (ms) | expansion bytes | formatted lines |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for (n, text) in specs {
        let source = SpecSource::new("synth.toml", text.clone());
        let paths = RuntimePath::default();
        let (mut compile_t, mut expand_t, mut total_t) = (Vec::new(), Vec::new(), Vec::new());
        let mut bytes = 0;
        for _ in 0..5 {
            let t0 = Instant::now();
            let Ok(protocol) = protocol_codegen::compile(&source) else {
                eprintln!("synth: the spec {n} does not validate");
                return;
            };
            let t1 = Instant::now();
            let tokens = expand(&protocol, &paths);
            let t2 = Instant::now();
            bytes = tokens.to_string().len();
            compile_t.push(t1 - t0);
            expand_t.push(t2 - t1);
            total_t.push(t2 - t0);
        }
        let lines = protocol_codegen::compile(&source)
            .map(|p| expand_pretty(&p, &paths).lines().count())
            .unwrap_or(0);
        println!(
            "| {n} | {} | {:.1} | {:.1} | {:.1} | {bytes} | {lines} |",
            text.len(),
            ms(median(compile_t)),
            ms(median(expand_t)),
            ms(median(total_t)),
        );
    }
}
