//! The spec front end: loading the TOML ([`spec`]), validating it into the checked IR
//! ([`validate`], [`ir`]), lowering a frame format to the runtime's frame layout ([`layout`])
//! and to its packet rules ([`rules`]), the conversation to its session rules ([`session`]),
//! the diagnostics every stage reports into and their one renderer ([`diag`], [`source`]),
//! what a spec's decoders take ([`resources`]), and the lints ([`lint`]).
//!
//! The pipeline is `spec::load_spec` → `validate::validate`; [`compile`] runs both and is what
//! the macros, the run-time codec, the CLI and the tests call. What reads the IR lives
//! elsewhere: the printers (Rust tokens, C, Markdown) in `protocol-codegen`, the run-time codec
//! in `protocol-dynamic`. This crate prints no code, so it builds without `syn` or `quote`.

pub mod diag;
pub mod ir;
pub mod layout;
pub mod lint;
pub mod resources;
pub mod rules;
pub mod session;
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
        Some(mut protocol) if diags.is_empty() => {
            resources::locate_payloads(&spec, source, &mut protocol);
            Ok(protocol)
        }
        _ => Err(diags.into_sorted()),
    }
}
