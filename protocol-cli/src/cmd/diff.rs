//! `protocol diff OLD NEW`: every change between two versions of a spec, once, at the most
//! severe level it reaches (breaking the wire, breaking the generated Rust source, or
//! compatible), with its reason. Exit 0 when both levels are compatible, 1 when anything
//! breaks, 2 when a spec cannot be read or is invalid.

use std::path::Path;
use std::process::ExitCode;

use miette::Result;
use protocol_dynamic::compat::{Class, diff};
use serde_json::{Value, json};

use super::load_checked;

/// Exit status when anything breaks, at either level.
const BREAKING: u8 = 1;
/// Exit status when a spec cannot be compared: unreadable or invalid.
const UNCOMPARABLE: u8 = 2;

/// Prints the report.
pub fn run(old: &Path, new: &Path, as_json: bool) -> Result<ExitCode> {
    let mut loaded = Vec::new();
    for path in [old, new] {
        match load_checked(path) {
            Ok(Ok(p)) => loaded.push(p),
            // Invalid: its errors are printed.
            Ok(Err(_)) => return Ok(ExitCode::from(UNCOMPARABLE)),
            Err(unreadable) => {
                super::print_error(&unreadable);
                return Ok(ExitCode::from(UNCOMPARABLE));
            }
        }
    }
    let [a, b] = <[_; 2]>::try_from(loaded).map_err(|_| miette::miette!("two specs"))?;
    let changes = diff(&a, &b);
    let count = |class| changes.iter().filter(|c| c.class == class).count();
    let (wire, source) = (count(Class::Breaking), count(Class::SourceBreaking));
    if as_json {
        let items: Vec<Value> = changes
            .iter()
            .map(|c| {
                json!({
                    "class": c.class.label(),
                    "subject": c.subject,
                    "reason": c.reason,
                })
            })
            .collect();
        println!(
            "{}",
            json!({
                "wire_compatible": wire == 0,
                "source_compatible": wire == 0 && source == 0,
                "changes": items,
            })
        );
    } else {
        for c in &changes {
            println!("{c}");
        }
        let verdict = match (wire, source) {
            (0, 0) => "wire- and source-compatible",
            (0, _) => "wire-compatible, NOT source-compatible",
            _ => "NOT wire-compatible",
        };
        println!(
            "{} → {}: {wire} breaking, {source} source-breaking, {} compatible: {verdict}",
            old.display(),
            new.display(),
            changes.len() - wire - source
        );
    }
    Ok(if wire + source > 0 {
        ExitCode::from(BREAKING)
    } else {
        ExitCode::SUCCESS
    })
}
