//! The printers of a checked protocol: Rust tokens ([`codegen`], the `protocol!` expansion),
//! C ([`c`], `protocol gen c`) and Markdown reference docs ([`docs_md`]). [`derive`](mod@derive)
//! takes a `#[derive(Payload)]` through the front end's validation and the same payload
//! printer; [`input`] is the `protocol!` macro's argument to its expansion.
//!
//! The front end (loading, validation, the IR, the layout lowering, diagnostics) is the
//! `protocol-spec` crate; its modules are re-exported here, so `protocol_codegen::ir` and
//! `protocol_spec::ir` are one module. The pipeline is [`compile`] (the front end) →
//! `codegen::expand` (or `c::generate`, `docs_md::render`).
//!
//! [`wireshark`] prints a Wireshark Lua dissector (`protocol gen wireshark`).
//!
//! Each printer is a cargo feature, all on by default: `rust` (`codegen`, `derive`,
//! `input`; the one that builds `syn`, `quote` and `prettyplease`), `c`, `markdown` and
//! `wireshark`. The `protocol!` macro takes `rust` alone; the `protocol` command takes the
//! other three.

pub use protocol_spec::{
    compile, diag, ir, layout, lint, resources, rules, session, source, spec, validate,
};

#[cfg(feature = "c")]
pub mod c;
#[cfg(feature = "rust")]
pub mod codegen;
#[cfg(feature = "rust")]
pub mod derive;
#[cfg(feature = "markdown")]
pub mod docs_md;
#[cfg(feature = "rust")]
pub mod input;
#[cfg(feature = "wireshark")]
pub mod wireshark;

/// The doc text of the Rust printer's rustdoc ([`docs`](codegen::docs)), which the Markdown
/// printer writes too: built without the `rust` feature, `codegen` holds that module alone.
#[cfg(all(feature = "markdown", not(feature = "rust")))]
pub mod codegen {
    pub mod docs;
}
