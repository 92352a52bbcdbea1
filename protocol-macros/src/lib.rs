//! The `protocol!` and `#[derive(Payload)]` macros. A thin shim: all logic is in the front end
//! (`protocol-spec`) and the Rust printer (`protocol-codegen` with its `rust` feature alone; the
//! C and Markdown printers are not built). Use them through the `protocol-kit` crate, which
//! re-exports them with the runtime the generated code names (`::protocol_kit`).

use proc_macro::TokenStream;

/// Generate a protocol module from a TOML spec.
///
/// `protocol!("specs/hflink.toml")` reads the spec relative to the calling crate's
/// `Cargo.toml` and expands to `pub mod <name> { ... }`: payload structs, enums, the `Command`
/// and `Message` enums, `Header`, `Packet` (decode/encode), the `LAYOUT` the runtime's stream
/// decoder uses, and size consts. Errors in the spec are compile errors that quote the spec's
/// line and column. Also accepts `inline = "..."` (the spec text instead of a path) and
/// `crate = ::path::to::protocol`, where the generated code finds the `protocol-kit` crate when a
/// crate re-exports it rather than depending on it under its own name.
/// `derive(serde, defmt)` (either or both) derives those crates' traits on the generated types,
/// through the `protocol-kit` crate's re-exports (its features `serde` and `defmt`).
#[proc_macro]
pub fn protocol(input: TokenStream) -> TokenStream {
    protocol_codegen::input::protocol_macro(input.into()).into()
}

/// Derive `Payload` (wire encoding and decoding) for a hand-written struct. See
/// `protocol_codegen::derive` for the attributes; `#[payload(crate = "::path")]`
/// names the `protocol-kit` crate when it is not `::protocol_kit`.
#[proc_macro_derive(Payload, attributes(payload))]
pub fn derive_payload(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as syn::DeriveInput);
    match protocol_codegen::derive::derive_payload(&input) {
        Ok(tokens) => tokens.into(),
        Err(e) => e.to_compile_error().into(),
    }
}
