//! The printers of a checked protocol: Rust tokens ([`codegen`], the `protocol!` expansion),
//! C ([`c`], `protocol gen c`) and Markdown reference docs ([`docs_md`]). [`derive`](mod@derive)
//! takes a `#[derive(Payload)]` through the front end's validation and the same payload
//! printer; [`input`] is the `protocol!` macro's argument to its expansion.
//!
//! The front end (loading, validation, the IR, the layout lowering, diagnostics) is the
//! `protocol-spec` crate; its modules are re-exported here, so `protocol_codegen::ir` and
//! `protocol_spec::ir` are one module. The pipeline is [`compile`] (the front end) →
//! `codegen::expand` (or `c::generate`, `docs_md::render`).

pub use protocol_spec::{compile, diag, ir, layout, lint, source, spec, validate};

pub mod c;
pub mod codegen;
pub mod derive;
pub mod docs_md;
pub mod input;
