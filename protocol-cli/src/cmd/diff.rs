//! `protocol diff OLD NEW`: every change between two versions of a spec, breaking or
//! compatible, with its reason; exit 1 if anything breaks, 2 if a spec is invalid.

use std::path::Path;
use std::process::ExitCode;

use miette::Result;
use protocol_dynamic::compat::{Class, diff};
use serde_json::{Value, json};

use super::load_checked;

/// Exit status when a spec cannot be compared.
const UNCOMPARABLE: u8 = 2;

/// Prints the report.
pub fn run(old: &Path, new: &Path, as_json: bool) -> Result<ExitCode> {
    let (Ok(a), Ok(b)) = (load_checked(old)?, load_checked(new)?) else {
        return Ok(ExitCode::from(UNCOMPARABLE));
    };
    let changes = diff(&a, &b);
    let breaking = changes
        .iter()
        .filter(|c| c.class == Class::Breaking)
        .count();
    if as_json {
        let items: Vec<Value> = changes
            .iter()
            .map(|c| {
                json!({
                    "class": if c.class == Class::Breaking { "breaking" } else { "compatible" },
                    "subject": c.subject,
                    "reason": c.reason,
                })
            })
            .collect();
        println!("{}", json!({ "breaking": breaking > 0, "changes": items }));
    } else {
        for c in &changes {
            println!("{c}");
        }
        let verdict = if breaking > 0 {
            "NOT wire-compatible"
        } else {
            "wire-compatible"
        };
        println!(
            "{} → {}: {} breaking, {} compatible: {verdict}",
            old.display(),
            new.display(),
            breaking,
            changes.len() - breaking
        );
    }
    Ok(if breaking > 0 {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}
