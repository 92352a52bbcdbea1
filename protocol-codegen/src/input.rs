//! The `protocol!` macro's entry: its arguments (a spec path, or an inline spec; an optional
//! `crate = path` naming the `protocol-kit` crate when it is not `::protocol_kit`; an optional
//! `derive(serde, defmt)` choosing those derives on the generated types), reading the spec file relative to the calling crate, and turning
//! diagnostics into compile errors placed on the macro's argument.

use std::path::PathBuf;

use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::parse::{Parse, ParseStream};
use syn::{LitStr, Token};

use crate::codegen::{Derives, RuntimePath, expand_with};
use crate::diag::{Color, Diagnostic, render_read_error, render_report};
use crate::source::SpecSource;

/// Environment variable that overrides the directory spec paths are relative to (trybuild
/// runs the cases in a crate of its own, so its cases point this at the project).
pub const MANIFEST_DIR_OVERRIDE: &str = "PROTOCOL_SPEC_DIR";

/// Parsed macro arguments.
pub struct MacroInput {
    /// `"specs/x.toml"` or `inline = "..."`.
    pub spec: SpecArg,
    /// Where generated code finds the `protocol-kit` crate (`::protocol_kit` unless `crate = path`).
    pub paths: RuntimePath,
    /// The derives on generated types: `derive(serde, defmt)`.
    pub derives: Derives,
}

/// Where the spec comes from.
pub enum SpecArg {
    /// A path relative to the calling crate's manifest directory.
    Path(LitStr),
    /// The spec text itself.
    Inline(LitStr),
}

impl Parse for MacroInput {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let mut spec = None;
        let mut paths = RuntimePath::default();
        let mut derives = Derives::default();
        while !input.is_empty() {
            if input.peek(LitStr) {
                spec = Some(SpecArg::Path(input.parse()?));
            } else if input.peek2(syn::token::Paren) {
                derives = parse_derives(input)?;
            } else {
                let key: syn::Ident = input.call(syn::ext::IdentExt::parse_any)?;
                input.parse::<Token![=]>()?;
                match key.to_string().as_str() {
                    "path" => spec = Some(SpecArg::Path(input.parse()?)),
                    "inline" => spec = Some(SpecArg::Inline(input.parse()?)),
                    "crate" => {
                        // `crate = ::my::protocol`, or as a string as in the derive.
                        let p: syn::Path = if input.peek(LitStr) {
                            input.parse::<LitStr>()?.parse()?
                        } else {
                            input.parse()?
                        };
                        paths = RuntimePath(quote!(#p));
                    }
                    _ => {
                        return Err(syn::Error::new(
                            key.span(),
                            "expected `path = \"...\"`, `inline = \"...\"`, `crate = path` or `derive(serde, defmt)`",
                        ));
                    }
                }
            }
            if !input.is_empty() {
                input.parse::<Token![,]>()?;
            }
        }
        let spec = spec.ok_or_else(|| {
            input.error("expected the spec's path: protocol!(\"specs/name.toml\")")
        })?;
        Ok(MacroInput {
            spec,
            paths,
            derives,
        })
    }
}

/// `derive(serde, defmt)`: the derives on generated types, each named once.
fn parse_derives(input: ParseStream<'_>) -> syn::Result<Derives> {
    let key: syn::Ident = input.parse()?;
    if key != "derive" {
        return Err(syn::Error::new(
            key.span(),
            "expected `derive(serde, defmt)`",
        ));
    }
    let content;
    syn::parenthesized!(content in input);
    let names = content.parse_terminated(syn::Ident::parse, Token![,])?;
    let mut derives = Derives::default();
    for name in names {
        let slot = match name.to_string().as_str() {
            "serde" => &mut derives.serde,
            "defmt" => &mut derives.defmt,
            _ => {
                return Err(syn::Error::new(
                    name.span(),
                    "expected `serde` or `defmt` (each needs the `protocol` feature of that name)",
                ));
            }
        };
        if *slot {
            return Err(syn::Error::new(name.span(), "named twice"));
        }
        *slot = true;
    }
    Ok(derives)
}

/// The spec's errors as one compile error on the macro's argument: the report every
/// `protocol` command prints for the same spec, without colour.
fn errors_to_tokens(diags: &[Diagnostic], source: &SpecSource, span: Span) -> TokenStream {
    syn::Error::new(span, render_report(diags, source, Color::Plain)).to_compile_error()
}

/// The help of a spec path the macro cannot read.
pub const READ_HELP: &str =
    "the path is relative to the directory of the calling crate's Cargo.toml";

/// Expand `protocol!(...)`. Never panics: every failure is a compile error.
pub fn protocol_macro(tokens: TokenStream) -> TokenStream {
    let input: MacroInput = match syn::parse2(tokens) {
        Ok(i) => i,
        Err(e) => return e.to_compile_error(),
    };
    let (source, span, track) = match &input.spec {
        SpecArg::Inline(lit) => (
            SpecSource::new("<inline spec>", lit.value()),
            lit.span(),
            None,
        ),
        SpecArg::Path(lit) => {
            let rel = lit.value();
            let base = std::env::var_os(MANIFEST_DIR_OVERRIDE)
                .or_else(|| std::env::var_os("CARGO_MANIFEST_DIR"))
                .map(PathBuf::from)
                .unwrap_or_default();
            let full = base.join(&rel);
            match std::fs::read_to_string(&full) {
                Ok(text) => (SpecSource::new(rel.clone(), text), lit.span(), Some(full)),
                Err(e) => {
                    let msg = render_read_error("spec", &rel, &e, Some(READ_HELP), Color::Plain);
                    // rustc writes the `error: ` itself.
                    let msg = msg.strip_prefix("error: ").unwrap_or(&msg).trim_end();
                    return syn::Error::new(lit.span(), msg).to_compile_error();
                }
            }
        }
    };
    match crate::compile(&source) {
        Err(diags) => errors_to_tokens(&diags, &source, span),
        Ok(protocol) => {
            let code = expand_with(&protocol, &input.paths, input.derives);
            let track = track.map(|p| {
                let p = p.to_string_lossy().into_owned();
                quote!(
                    const _: &[u8] = include_bytes!(#p);
                )
            });
            quote!(#code #track)
        }
    }
}
