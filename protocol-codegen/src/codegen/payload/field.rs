//! One field: the expressions that read, write and measure it, and its Rust type.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::def::{PField, PKind};
use super::scalar::{local, prim_type, read_elem, read_packed, to_raw, write_packed, write_scalar};

/// An expression reading a whole field (array, optional, group included).
pub(super) fn read_value(kind: &PKind, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Optional(inner) => {
            let read = read_value(inner, rt);
            quote!(if #rt::more(r) { #rt::Some(#read) } else { #rt::None })
        }
        PKind::Packed { .. } => read_packed(kind, rt),
        PKind::Array {
            ty,
            elem,
            max,
            size_from,
            ..
        } => {
            let read = read_elem(elem, &quote!(r), rt);
            match size_from {
                None => quote! {{
                    let mut a = <#ty>::new();
                    while #rt::more(r) {
                        let e = #read;
                        let size = <Self as #rt::Payload>::SIZE;
                        a.push(e).map_err(|_| #rt::group_full(r, size))?;
                    }
                    a
                }},
                Some(n) => {
                    let var = local(n);
                    quote! {{
                        let n = #rt::array_len(#var as u64, #max)?;
                        let mut a = <#ty>::new();
                        for _ in 0..n {
                            a.push(#read).map_err(|_| #rt::DecodeError::SizeMismatch { place: #rt::Place::NONE })?;
                        }
                        a
                    }}
                }
            }
        }
        PKind::Group {
            ty, elem_ty, elem, ..
        } if reads_as_itself(elem) => quote!({
            let mut group = <#ty>::new();
            while #rt::more(r) {
                let e = <#elem_ty as #rt::Payload>::read(r)?;
                let size = <Self as #rt::Payload>::SIZE;
                group.push(e).map_err(|_| #rt::group_full(r, size))?;
            }
            group
        }),
        PKind::Group {
            ty, elem_ty, elem, ..
        } => {
            let mut lets = Vec::new();
            let mut inits = Vec::new();
            for f in elem {
                match (&f.kind, &f.ident) {
                    (PKind::Pad(n), _) => lets.push(quote!(r.skip(#n)?;)),
                    (k, Some(id)) => {
                        let v = format_ident!("e_{}", id.to_string().trim_start_matches("r#"));
                        let read = read_value(k, rt);
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
        k => match count_of(k) {
            None => read_elem(k, &quote!(r), rt),
            Some(_) => {
                let read = ok_of(read_elem(k, &quote!(r), rt), rt);
                quote!(r.array(|r| #read)?)
            }
        },
    }
}

/// Whether a repeated struct's elements are read and written by the element's own `Payload`
/// impl: when they hold bit members or checks (which only the struct's own code reads and
/// writes) and no field takes its size from another, which inline code reads from the
/// repeating struct's locals.
fn reads_as_itself(elem: &[PField]) -> bool {
    let sized = elem.iter().any(|f| {
        matches!(
            &f.kind,
            PKind::Bytes {
                size_from: Some(_),
                ..
            } | PKind::Array {
                size_from: Some(_),
                ..
            }
        )
    });
    let own_code = elem
        .iter()
        .any(|f| matches!(f.kind, PKind::Bits { .. } | PKind::Check { .. }));
    own_code && !sized
}

/// `Ok(read)`, the value of a closure that reads: `read` without its final `?` when it has
/// one (`Ok(x?)` is `x`).
pub(super) fn ok_of(read: TokenStream, rt: &TokenStream) -> TokenStream {
    let mut tokens: Vec<proc_macro2::TokenTree> = read.clone().into_iter().collect();
    match tokens.last() {
        Some(proc_macro2::TokenTree::Punct(p)) if p.as_char() == '?' => {
            tokens.pop();
            tokens.into_iter().collect()
        }
        _ => quote!(#rt::Ok(#read)),
    }
}

/// Statements writing a whole field whose value is `value`; `owner` is the expression whose
/// fields sized bytes take their size from (`self`).
pub(super) fn write_value(
    kind: &PKind,
    value: TokenStream,
    owner: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    match kind {
        PKind::Optional(inner) => {
            let w = write_value(inner, quote!((*v)), owner, rt);
            quote!(if let #rt::Some(v) = &#value { #w })
        }
        PKind::Packed { .. } => write_packed(kind, value, rt),
        PKind::Array {
            elem, size_from, ..
        } => {
            let w1 = write_elem(elem, quote!(*e), rt);
            let stated = size_from
                .as_ref()
                .map(|n| quote!(#rt::check_stated_len(#value.len(), #owner.#n as u64)?;));
            quote!(#stated for e in #value.iter() { #w1 })
        }
        PKind::Group { elem, .. } if reads_as_itself(elem) => quote! {
            for e in #value.iter() { #rt::Payload::write(e, w)?; }
        },
        PKind::Group { elem, .. } => {
            let parts = elem.iter().map(|f| match (&f.kind, &f.ident) {
                (PKind::Pad(n), _) => quote!(w.zeros(#n)?;),
                (k, Some(id)) => write_value(k, quote!(e.#id), owner, rt),
                _ => quote!(),
            });
            quote!(for e in #value.iter() { #(#parts)* })
        }
        PKind::Bytes {
            size_from: Some(n), ..
        } => quote! {
            #rt::check_stated_len(#value.len(), #owner.#n as u64)?;
            #value.write(w)?;
        },
        k => match count_of(k) {
            None => write_elem(k, value, rt),
            Some(_) => {
                let w1 = write_elem(k, quote!(*e), rt);
                quote!(for e in #value.iter() { #w1 })
            }
        },
    }
}

/// The wire size of a field's value, for fields whose size varies.
pub(super) fn variable_len(
    kind: &PKind,
    value: TokenStream,
    rt: &TokenStream,
) -> Option<TokenStream> {
    match kind {
        PKind::Bytes { .. } => Some(quote!(#value.len())),
        PKind::Var { ty } => Some(quote!(<#ty as #rt::Payload>::wire_len(&#value))),
        PKind::Array { elem_size, .. } => Some(quote!(#value.len().saturating_mul(#elem_size))),
        PKind::Optional(inner) => {
            let size =
                variable_len(inner, quote!(v), rt).unwrap_or_else(|| size_sum([&**inner], rt));
            Some(quote!(match &#value { #rt::Some(v) => #size, #rt::None => 0 }))
        }
        PKind::Group { elem, .. } => {
            let mut fixed = Vec::new();
            let mut vars = Vec::new();
            for f in elem {
                match f
                    .ident
                    .as_ref()
                    .and_then(|id| variable_len(&f.kind, quote!(e.#id), rt))
                {
                    Some(len) => vars.push(len),
                    None => fixed.push(&f.kind),
                }
            }
            let fixed = size_sum(fixed, rt);
            Some(quote!(#value.iter().fold(0usize, |acc, e| {
                const FIXED: usize = #fixed;
                acc.saturating_add(FIXED #(.saturating_add(#vars))*)
            })))
        }
        _ => None,
    }
}

/// The wire size of a fixed-size field.
pub(super) fn fixed_size(kind: &PKind) -> usize {
    let n = count_of(kind).unwrap_or(1);
    match kind {
        PKind::Pad(len) => *len,
        PKind::Scalar { scalar, .. } | PKind::Enum { scalar, .. } => scalar.prim.size() * n,
        PKind::Bits { word, .. } => word.prim.size(),
        PKind::Packed { size, .. } => *size,
        PKind::Bytes { max, .. } => *max,
        PKind::Group { max, elem_size, .. } | PKind::Array { max, elem_size, .. } => {
            max * elem_size
        }
        PKind::Optional(inner) => fixed_size(inner),
        PKind::Check { width, .. } => *width,
        // Nested payloads and variable runtime types are sized by their own impl; only spec structs call this, whose
        // nested structs are fixed and whose size the IR knows.
        PKind::Nested { .. } | PKind::Var { .. } => 0,
    }
}

/// Writing one element `value` (an expression of the field's element type). A scaled value
/// is clamped (if its field clamps), quantized and fitted to its raw type by the runtime: a
/// value the raw type cannot hold is an error.
fn write_elem(kind: &PKind, value: TokenStream, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Scalar {
            scalar,
            scale: None,
            ..
        } => write_scalar(*scalar, value),
        PKind::Scalar {
            scalar,
            scale: Some(sc),
            ..
        } => write_scalar(*scalar, to_raw(value, sc, None, rt)),
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::write(&#value, w)?;),
        PKind::Enum { ty, scalar, .. } => write_scalar(
            *scalar,
            quote!(#rt::enum_raw(#value, #ty::to_raw, #ty::from_raw)?),
        ),
        PKind::Bytes { .. } => quote!(#value.write(w)?;),
        PKind::Var { ty } => quote!(<#ty as #rt::Payload>::write(&#value, w)?;),
        PKind::Pad(_)
        | PKind::Bits { .. }
        | PKind::Group { .. }
        | PKind::Array { .. }
        | PKind::Optional(_)
        | PKind::Packed { .. }
        | PKind::Check { .. } => quote!(),
    }
}

/// The Rust type of one element of a field.
pub fn elem_type(kind: &PKind) -> TokenStream {
    match kind {
        PKind::Scalar {
            scale: Some(sc), ..
        } => prim_type(sc.physical),
        PKind::Scalar { scalar, .. } => prim_type(scalar.prim),
        PKind::Nested { ty, .. }
        | PKind::Enum { ty, .. }
        | PKind::Bytes { ty, .. }
        | PKind::Group { ty, .. }
        | PKind::Array { ty, .. }
        | PKind::Var { ty } => ty.clone(),
        PKind::Optional(inner) => {
            let t = field_type(inner);
            quote!(::core::option::Option<#t>)
        }
        PKind::Packed {
            scale: Some(sc), ..
        } => prim_type(sc.physical),
        PKind::Packed { prim, .. } => prim_type(*prim),
        PKind::Pad(_) | PKind::Bits { .. } | PKind::Check { .. } => quote!(()),
    }
}

/// The Rust type of a whole field (array or element).
pub fn field_type(kind: &PKind) -> TokenStream {
    let t = elem_type(kind);
    match count_of(kind) {
        Some(n) => quote!([#t; #n]),
        None => t,
    }
}

fn count_of(kind: &PKind) -> Option<usize> {
    match kind {
        PKind::Scalar { count, .. } | PKind::Nested { count, .. } | PKind::Enum { count, .. } => {
            *count
        }
        PKind::Packed { count, .. } => Some(*count),
        _ => None,
    }
}

/// The wire size of one field: the bytes known at expansion, and a term over a nested type's
/// `SIZE` (opaque to the derive), if any.
fn size_parts(kind: &PKind, rt: &TokenStream) -> (usize, Option<TokenStream>) {
    let n = count_of(kind).unwrap_or(1);
    match kind {
        PKind::Nested { ty, count: None } | PKind::Var { ty } => {
            (0, Some(quote!(<#ty as #rt::Payload>::SIZE)))
        }
        PKind::Nested { ty, .. } => (0, Some(quote!(<#ty as #rt::Payload>::SIZE * #n))),
        PKind::Pad(len) => (*len, None),
        PKind::Scalar { scalar, .. } | PKind::Enum { scalar, .. } => (scalar.prim.size() * n, None),
        PKind::Bits { word, .. } => (word.prim.size(), None),
        PKind::Bytes { max, .. } => (*max, None),
        PKind::Check { width, .. } => (*width, None),
        PKind::Packed { size, .. } => (*size, None),
        PKind::Group { .. } | PKind::Array { .. } | PKind::Optional(_) => (fixed_size(kind), None),
    }
}

/// The wire size of `kinds` together, as a constant expression: the bytes known at expansion
/// summed into one literal, then the nested types' sizes.
pub(super) fn size_sum<'a>(
    kinds: impl IntoIterator<Item = &'a PKind>,
    rt: &TokenStream,
) -> TokenStream {
    let mut bytes = 0usize;
    let mut terms = Vec::new();
    for kind in kinds {
        let (b, term) = size_parts(kind, rt);
        bytes += b;
        terms.extend(term);
    }
    if bytes == 0 && !terms.is_empty() {
        quote!(#(#terms)+*)
    } else {
        quote!(#bytes #(+ #terms)*)
    }
}
