//! `protocol expand SPEC`: the Rust code `protocol!` generates, formatted for review. The Rust
//! printer (`syn`, `quote`, `prettyplease`) is built with the `expand` feature only; a build
//! without it keeps the command and answers with how to get it.

use std::path::Path;
use std::process::ExitCode;

use miette::Result;

/// Prints the expansion.
#[cfg(feature = "expand")]
pub fn run(spec: &Path) -> Result<ExitCode> {
    use protocol_codegen::codegen::{RuntimePath, expand_pretty};

    let p = match super::load_checked(spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    print!("{}", expand_pretty(&p, &RuntimePath::default()));
    Ok(ExitCode::SUCCESS)
}

/// Says that this build has no Rust printer, and how to install one that has.
#[cfg(not(feature = "expand"))]
pub fn run(_spec: &Path) -> Result<ExitCode> {
    Err(miette::miette!(
        help = "install the command with the feature: `cargo install --locked protocol-cli \
                --features expand` (from a clone: `cargo install --locked --path protocol-cli \
                --features expand`)",
        "`protocol expand` is not in this build: it prints with the Rust printer, which the \
         `expand` feature of protocol-cli builds"
    ))
}
