//! The commands of `protocol`, one module each, and what they share: loading a spec and
//! reporting its errors.

pub mod check;
pub mod decode;
pub mod diff;
pub mod doc;
pub mod encode;
pub mod expand;
pub mod export;
pub mod export_data;
pub mod generate;
pub mod import;
pub mod report;
pub mod twin;
pub mod wireshark;

use std::io::IsTerminal;
use std::path::Path;
use std::process::ExitCode;

use miette::{Result, miette};
use protocol_cli::spec;
use protocol_spec::ir::Protocol;

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

/// The direction `--direction NAME` gives the codec: only for a spec whose directions no header
/// field tells (`given = true`), where decoding (`required`) needs one; an error names the
/// choices.
///
/// # Errors
/// A name the spec does not have, a name for a spec whose header tells its directions, or no
/// name where one is required.
pub fn pick_direction(p: &Protocol, name: Option<&str>, required: bool) -> Result<Option<usize>> {
    let names: Vec<String> = p
        .directions
        .iter()
        .map(|d| format!("`{}`", d.name))
        .collect();
    let choices = names.join(" or ");
    match name {
        Some(n) if !p.directions_given() => Err(if p.directions.is_empty() {
            miette!("`--direction {n}`: spec `{}` has no directions", p.name)
        } else {
            miette!(
                "`--direction {n}`: spec `{}` tells its directions by a header field, so the decoder finds each frame's direction itself; remove `--direction`",
                p.name
            )
        }),
        Some(n) => p
            .directions
            .iter()
            .position(|d| d.name == n)
            .map(Some)
            .ok_or_else(|| {
                miette!(
                    "`--direction {n}`: spec `{}` has no such direction (it has {})",
                    p.name,
                    names.join(", ")
                )
            }),
        None if required && p.directions_given() => Err(miette!(
            "spec `{}` does not tell its directions by a header field: say which frames these are with `--direction NAME`, NAME {choices}",
            p.name
        )),
        None => Ok(None),
    }
}
