//! `protocol expand SPEC`: the Rust code `protocol!` generates, formatted for review.

use std::path::Path;
use std::process::ExitCode;

use miette::Result;
use protocol_codegen::codegen::{RuntimePath, expand_pretty};

use super::load_checked;

/// Prints the expansion.
pub fn run(spec: &Path) -> Result<ExitCode> {
    let p = match load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    print!("{}", expand_pretty(&p, &RuntimePath::default()));
    Ok(ExitCode::SUCCESS)
}
