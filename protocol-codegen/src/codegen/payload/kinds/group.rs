//! A repeated group ([`FieldKind::Group`](crate::ir::FieldKind::Group)): elements of a struct
//! to the end of the payload, as the runtime's `Group<elem, max>`, read and written inline so
//! that an element's sized bytes can use the repeating struct's fields.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::{Kind, Slot, size_sum, slots};
use crate::codegen::{ident, rt as type_rt};
use crate::ir::Protocol;

/// Up to `max` elements of the struct `elem_ty`.
pub(super) struct Group<'a> {
    elem_ty: Ident,
    elem: Vec<Slot<'a>>,
    max: usize,
    elem_size: usize,
}

impl<'a> Group<'a> {
    pub(super) fn new(p: &'a Protocol, elem: usize, max: usize) -> Group<'a> {
        let e = &p.structs[elem];
        Group {
            elem_ty: ident(&e.name),
            elem: slots(p, e),
            max,
            elem_size: e.size,
        }
    }
}

impl Group<'_> {
    /// Whether the elements are read and written by the element's own `Payload` impl: when
    /// they hold bit words or checks (which only the struct's own code reads and writes) and
    /// no field reads an earlier one, which inline code reads from the repeating struct's
    /// locals.
    fn reads_as_itself(&self) -> bool {
        let sized = self.elem.iter().any(|f| f.kind.needs_locals());
        let own_code = self.elem.iter().any(|f| f.kind.own_code());
        own_code && !sized
    }
}

impl Kind for Group<'_> {
    fn elem_type(&self) -> TokenStream {
        let rt = type_rt();
        let (elem_ty, max) = (&self.elem_ty, self.max);
        quote!(#rt::Group<#elem_ty, #max>)
    }

    fn is_eq(&self) -> bool {
        false
    }

    fn fixed_size(&self) -> usize {
        self.max * self.elem_size
    }

    fn variable_len(&self, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
        let mut fixed = Vec::new();
        let mut vars = Vec::new();
        for f in &self.elem {
            match f
                .ident
                .as_ref()
                .and_then(|id| f.kind.variable_len(quote!(e.#id), rt))
            {
                Some(len) => vars.push(len),
                None => fixed.push(&*f.kind),
            }
        }
        let fixed = size_sum(fixed, rt);
        Some(quote!(#value.iter().fold(0usize, |acc, e| {
            const FIXED: usize = #fixed;
            acc.saturating_add(FIXED #(.saturating_add(#vars))*)
        })))
    }

    fn read(&self, _reader: &TokenStream, rt: &TokenStream) -> TokenStream {
        let (ty, elem_ty) = (self.elem_type(), &self.elem_ty);
        if self.reads_as_itself() {
            return quote! {{
                let mut group = <#ty>::new();
                while #rt::more(r) {
                    let e = <#elem_ty as #rt::Payload>::read(r)?;
                    let size = <Self as #rt::Payload>::SIZE;
                    group.push(e).map_err(|_| #rt::group_full(r, size))?;
                }
                group
            }};
        }
        let mut lets = Vec::new();
        let mut inits = Vec::new();
        for f in &self.elem {
            match (f.kind.padding(), &f.ident) {
                (Some(n), _) => lets.push(quote!(r.skip(#n)?;)),
                (None, Some(id)) => {
                    let v = format_ident!("e_{}", id.to_string().trim_start_matches("r#"));
                    let read = f.kind.read(&quote!(r), rt);
                    lets.push(quote!(let #v = #read;));
                    inits.push(quote!(#id: #v));
                }
                _ => {}
            }
        }
        quote! {{
            let mut group = <#ty>::new();
            while #rt::more(r) {
                #(#lets)*
                let size = <Self as #rt::Payload>::SIZE;
                group.push(#elem_ty { #(#inits),* }).map_err(|_| #rt::group_full(r, size))?;
            }
            group
        }}
    }

    fn write(&self, value: TokenStream, owner: &TokenStream, rt: &TokenStream) -> TokenStream {
        if self.reads_as_itself() {
            return quote!(for e in #value.iter() { #rt::Payload::write(e, w)?; });
        }
        let parts = self
            .elem
            .iter()
            .map(|f| match (f.kind.padding(), &f.ident) {
                (Some(n), _) => quote!(w.zeros(#n)?;),
                (None, Some(id)) => f.kind.write(quote!(e.#id), owner, rt),
                _ => quote!(),
            });
        quote!(for e in #value.iter() { #(#parts)* })
    }

    fn needs_locals(&self) -> bool {
        true
    }

    fn value_can_fail(&self) -> bool {
        true
    }
}
