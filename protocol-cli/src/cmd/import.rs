//! `protocol import mavlink DIALECT.xml [-o SPEC]`: a definition of another language as a
//! spec (the importers live in [`protocol_cli::import`]).

use std::path::Path;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::import;

/// Writes the spec of a MAVLink dialect to `output` or stdout.
pub fn mavlink(dialect: &Path, output: Option<&Path>) -> Result<ExitCode> {
    let text = import::mavlink::import(dialect).map_err(|e| miette!("{e}"))?;
    match output {
        Some(path) => std::fs::write(path, text)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot write `{}`", path.display()))?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}
