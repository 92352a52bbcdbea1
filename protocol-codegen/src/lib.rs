//! Everything between a protocol spec and its users: loading the TOML ([`spec`]), validating it
//! into a checked IR ([`validate`], [`ir`]), and expanding the IR into Rust ([`codegen`]).
//!
//! The pipeline is `spec::load_spec` → `validate::validate` → `codegen::expand`; [`compile`]
//! runs the first two and is what the macros, the CLI and the tests call.

pub mod codegen;
pub mod diag;
pub mod input;
pub mod ir;
pub mod source;
pub mod spec;
pub mod validate;

use diag::{Diagnostic, Diagnostics};
use source::SpecSource;

/// Load and validate a spec: the checked IR, or every error found, sorted.
pub fn compile(source: &SpecSource) -> Result<ir::Protocol, Vec<Diagnostic>> {
    let mut diags = Diagnostics::new();
    let Some(spec) = spec::load_spec(source, &mut diags) else {
        return Err(diags.into_sorted());
    };
    match validate::validate(&spec, &mut diags) {
        Some(protocol) if diags.is_empty() => Ok(protocol),
        _ => Err(diags.into_sorted()),
    }
}
