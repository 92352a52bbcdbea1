//! The commands of `protocol`, one module each, and what they share: loading a spec and
//! reporting its errors.

pub mod check;
pub mod decode;
pub mod diff;
pub mod doc;
pub mod encode;
pub mod expand;
pub mod generate;
pub mod report;

use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result};
use protocol_cli::spec;
use protocol_codegen::ir::Protocol;

/// Exit status when an input (spec, frame object) is wrong.
pub const INVALID: u8 = 1;

/// Whether to colour what goes to stderr: a terminal, and `NO_COLOR` unset.
pub fn stderr_color() -> bool {
    std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none()
}

/// Loads and checks a spec; on errors, prints them and returns the exit status to end with.
pub fn load_checked(path: &Path) -> Result<std::result::Result<Protocol, ExitCode>> {
    let loaded = spec::load(path).into_diagnostic()?;
    match loaded.result {
        Ok(p) => Ok(Ok(p)),
        Err(diags) => {
            eprint!("{}", spec::render(&diags, &loaded.source, stderr_color()));
            eprintln!(
                "{}: {} error{}",
                loaded.source.path,
                diags.len(),
                if diags.len() == 1 { "" } else { "s" }
            );
            Ok(Err(ExitCode::from(INVALID)))
        }
    }
}
