//! `protocol check SPEC... [--json]`: validate specs, print every diagnostic, exit 1 on error.
//! A valid spec's lint warnings ([`protocol_spec::lint`]) are printed too; they do not
//! change the exit status. A valid spec's line is followed by what a decoder of each of its
//! frame formats takes ([`protocol_spec::resources`]).

use std::path::PathBuf;
use std::process::ExitCode;

use miette::Result;
use protocol_cli::spec;
use protocol_spec::resources;
use serde_json::{Value, json};

use super::{INVALID, stderr_color};

/// Checks every spec; all are checked even after one fails.
pub fn run(specs: &[PathBuf], as_json: bool) -> Result<ExitCode> {
    let mut failed = false;
    let mut all = Vec::new();
    for path in specs {
        let loaded = match spec::load(path) {
            Ok(l) => l,
            Err(e) => {
                failed = true;
                if as_json {
                    all.push(json!({
                        "file": e.path, "line": Value::Null, "column": Value::Null,
                        "end_line": Value::Null, "end_column": Value::Null,
                        "severity": "error", "message": e.to_string(), "help": Value::Null,
                    }));
                } else {
                    eprint!("{}", e.render(stderr_color()));
                }
                continue;
            }
        };
        match &loaded.result {
            Ok(p) => {
                let warnings = protocol_spec::lint::lint(&loaded.source);
                if as_json {
                    all.extend(warnings.iter().map(|d| spec::to_json(d, &loaded.source)));
                } else if !warnings.is_empty() {
                    eprint!(
                        "{}",
                        spec::render_warnings(&warnings, &loaded.source, stderr_color())
                    );
                }
                if !as_json {
                    println!(
                        "{}: ok ({} command{}, {} frame format{}, {} struct{})",
                        loaded.source.path,
                        p.commands.len(),
                        plural(p.commands.len()),
                        p.frames.len(),
                        plural(p.frames.len()),
                        p.structs.len(),
                        plural(p.structs.len()),
                    );
                    for f in &p.frames {
                        println!("  frame `{}`: {}", f.name, resources::needs(f).summary());
                    }
                }
            }
            Err(diags) => {
                failed = true;
                if as_json {
                    all.extend(diags.iter().map(|d| spec::to_json(d, &loaded.source)));
                } else {
                    eprint!(
                        "{}",
                        spec::render_errors(diags, &loaded.source, stderr_color())
                    );
                }
            }
        }
    }
    if as_json {
        println!("{}", Value::Array(all));
    }
    Ok(if failed {
        ExitCode::from(INVALID)
    } else {
        ExitCode::SUCCESS
    })
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}
