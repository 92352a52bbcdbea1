//! Expansion: the checked IR to Rust tokens. Infallible: everything that could be wrong was
//! reported by validation. Output order is the spec's order, so expansion is deterministic.
//!
//! One module per concern: [`payload`] (the one payload printer, which also prints the derive's),
//! [`types`] (structs and enums), [`frame`] (layout statics and header), [`dispatch`]
//! (commands, messages, packets), [`docs`] (rustdoc text), [`paths`] (runtime paths).

pub mod dispatch;
pub mod docs;
pub mod frame;
mod header;
pub mod integrations;
pub mod packets;
pub mod paths;
pub mod payload;
pub mod registers;
pub mod types;

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

use crate::ir::Protocol;
pub use integrations::Derives;
pub use paths::RuntimePath;

/// Rust keywords that must be written as raw identifiers.
const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "dyn", "else", "enum", "extern", "false",
    "fn", "for", "gen", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "static", "struct", "trait", "true", "type", "unsafe", "use", "where",
    "while", "abstract", "become", "box", "do", "final", "macro", "override", "priv", "try",
    "typeof", "unsized", "virtual", "yield",
];

/// An identifier for a spec name; keywords become raw identifiers (`r#type`), never renamed.
pub fn ident(name: &str) -> Ident {
    if KEYWORDS.contains(&name) {
        Ident::new_raw(name, Span::call_site())
    } else {
        Ident::new(name, Span::call_site())
    }
}

/// `SCREAMING_CASE` identifier for a const named after a spec name.
pub fn const_ident(name: &str) -> Ident {
    Ident::new(&name.to_ascii_uppercase(), Span::call_site())
}

/// How items of the generated module name the runtime's `__private` module: the module imports
/// it once (`use <runtime>::__private as __rt;`), which keeps every path of the expansion short.
/// Nested modules and the derive, which have no such import, use [`RuntimePath::private`].
pub fn rt() -> TokenStream {
    quote!(__rt)
}

/// Expand a protocol into its module.
pub fn expand(p: &Protocol, paths: &RuntimePath) -> TokenStream {
    expand_with(p, paths, Derives::default())
}

/// Expand a protocol into its module, with the derives the user chose
/// ([`integrations`]).
pub fn expand_with(p: &Protocol, paths: &RuntimePath, derives: Derives) -> TokenStream {
    let module = ident(&p.name);
    let doc = docs::doc_attrs(&docs::module_doc(p));
    let constants = types::emit_constants(p);
    let addresses = types::emit_addresses(p);
    let enums = types::emit_enums(p);
    let structs = types::emit_structs(p);
    let frames = frame::emit_frames(p);
    let dispatch = dispatch::emit_dispatch(p);
    let packet_traits = packets::emit_packet_traits(p);
    let registers = registers::emit_registers(p);
    let private = paths.private();
    let items = integrations::apply(
        quote! {
            #constants
            #addresses
            #enums
            #structs
            #frames
            #dispatch
            #packet_traits
            #registers
        },
        p,
        derives,
    );
    quote! {
        #doc
        // Numbers in a spec are taken as written: a robot's 0.5235 rad/s limit is not pi/6.
        #[allow(clippy::approx_constant)]
        pub mod #module {
            use #private as __rt;
            #items
        }
    }
}

/// Expand and format with prettyplease (for review, snapshots and `protocol expand`).
pub fn expand_pretty(p: &Protocol, paths: &RuntimePath) -> String {
    expand_pretty_with(p, paths, Derives::default())
}

/// [`expand_pretty`] with the derives the user chose.
pub fn expand_pretty_with(p: &Protocol, paths: &RuntimePath, derives: Derives) -> String {
    let tokens = expand_with(p, paths, derives);
    match syn::parse2::<syn::File>(tokens.clone()) {
        Ok(file) => prettyplease::unparse(&file),
        Err(_) => tokens.to_string(),
    }
}
