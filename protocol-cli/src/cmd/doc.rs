//! `protocol doc SPEC [-o FILE]`: the Markdown reference of a spec.

use std::path::Path;
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr};

use super::load_checked;

/// Renders the reference to `output` or stdout.
pub fn run(spec: &Path, output: Option<&Path>) -> Result<ExitCode> {
    let p = match load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let text = protocol_codegen::docs_md::render(&p);
    match output {
        Some(path) => std::fs::write(path, text)
            .into_diagnostic()
            .wrap_err_with(|| format!("cannot write `{}`", path.display()))?,
        None => print!("{text}"),
    }
    Ok(ExitCode::SUCCESS)
}
