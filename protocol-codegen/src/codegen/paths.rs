//! Every path the expansion names in the runtime, in one place. Generated code reaches the
//! runtime only through `::protocol_kit::__private`, the facade crate users depend on, or through
//! the path a user names instead (`protocol!(crate = ::my::protocol, ...)`,
//! `#[payload(crate = "::my::protocol")]`), so a user's own `use` items never shadow it.

use proc_macro2::TokenStream;
use quote::quote;

/// Where the runtime is, as seen from the generated code.
#[derive(Debug, Clone)]
pub struct RuntimePath(pub TokenStream);

impl Default for RuntimePath {
    fn default() -> Self {
        RuntimePath(quote!(::protocol_kit))
    }
}

impl RuntimePath {
    /// `<runtime>::__private`.
    pub fn private(&self) -> TokenStream {
        let root = &self.0;
        quote!(#root::__private)
    }
}
