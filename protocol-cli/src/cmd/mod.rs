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

use miette::Result;
use protocol_cli::spec;
use protocol_codegen::ir::Protocol;

/// Exit status when an input (spec, frame object) is wrong.
pub const INVALID: u8 = 1;

/// Whether to colour what goes to stderr: a terminal, and `NO_COLOR` unset.
pub fn stderr_color() -> bool {
    std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none()
}

/// Loads and checks a spec; on errors, prints them (the report the macro's compile error
/// carries) and returns the exit status to end with.
///
/// # Errors
/// The spec cannot be read ([`spec::ReadError`], which `main` prints as every command does).
pub fn load_checked(path: &Path) -> Result<std::result::Result<Protocol, ExitCode>> {
    let loaded = spec::load(path)?;
    match loaded.result {
        Ok(p) => Ok(Ok(p)),
        Err(diags) => {
            eprint!(
                "{}",
                spec::render_errors(&diags, &loaded.source, stderr_color())
            );
            Ok(Err(ExitCode::from(INVALID)))
        }
    }
}

/// Prints an error that ends a command: a file that cannot be read as every command words it
/// ([`spec::ReadError::render`]), anything else as miette renders it.
pub fn print_error(e: &miette::Report) {
    match e.downcast_ref::<spec::ReadError>() {
        Some(unreadable) => eprint!("{}", unreadable.render(stderr_color())),
        None => eprintln!("{e:?}"),
    }
}
