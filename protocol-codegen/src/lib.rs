//! Everything between a protocol spec and its users: loading the TOML ([`spec`]), validating it
//! into a checked IR ([`validate`], [`ir`]), and expanding the IR into Rust ([`codegen`]).
//!
//! The pipeline is `spec::load_spec` → `validate::validate` → `codegen::expand`; [`compile`]
//! runs the first two and is what the macros, the CLI and the tests call. [`derive`](mod@derive) takes a
//! `#[derive(Payload)]` through the same validation and payload printer.

pub mod c;
pub mod codegen;
pub mod derive;
pub mod diag;
pub mod docs_md;
pub mod input;
pub mod ir;
pub mod layout;
pub mod lint;
pub mod rules;
pub mod source;
pub mod spec;
pub mod validate;

use diag::{Diagnostic, Diagnostics};
use source::SpecSource;

/// Load and validate a spec: the checked IR, or every error found, sorted.
pub fn compile(source: &SpecSource) -> Result<ir::Protocol, Vec<Diagnostic>> {
    let mut diags = Diagnostics::new();
    let (spec, repaired_tables) = spec::load_spec_repaired(source, &mut diags);
    let Some(spec) = spec else {
        return Err(diags.into_sorted());
    };
    let shape_errors = diags.spans();
    let mut semantic = Diagnostics::new();
    let protocol = validate::validate(&spec, &mut semantic);
    // A semantic error about an element whose ill-typed or unknown entry was dropped is a
    // consequence of that shape error, not a second mistake: report the shape error alone. So
    // is an error about the whole table the entry was dropped from.
    for d in semantic.into_sorted() {
        let follows = shape_errors
            .iter()
            .any(|s| d.span.start <= s.start && s.end <= d.span.end)
            || repaired_tables.contains(&d.span);
        if !follows {
            diags.push(d);
        }
    }
    match protocol {
        Some(protocol) if diags.is_empty() => Ok(protocol),
        _ => Err(diags.into_sorted()),
    }
}
