//! Every path the expansion names in the runtime, in one place. Generated code reaches the
//! runtime only through `::protocol_runtime::__private` (or the `crate = ...` override), so a
//! user's own `use` items never shadow it.

use proc_macro2::TokenStream;
use quote::quote;

/// Where the runtime is, as seen from the generated code.
#[derive(Debug, Clone)]
pub struct RuntimePath(pub TokenStream);

impl Default for RuntimePath {
    fn default() -> Self {
        RuntimePath(quote!(::protocol_runtime))
    }
}

impl RuntimePath {
    /// `<runtime>::__private`.
    pub fn private(&self) -> TokenStream {
        let root = &self.0;
        quote!(#root::__private)
    }
}
