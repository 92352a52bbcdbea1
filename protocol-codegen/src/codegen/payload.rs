//! The one payload code generator: `impl Payload` (wire read and write) for a struct described
//! as a [`PayloadDef`]. `protocol!` lowers the spec's structs into it and `#[derive(Payload)]`
//! lowers a hand-written struct into it, so both produce the same code for the same layout.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::paths::RuntimePath;
use crate::ir::{Endian, Prim, Scalar, Scale};

/// A struct as the payload generator sees it.
pub struct PayloadDef {
    /// The struct's name.
    pub name: Ident,
    /// Fields in wire order (generic structs are not supported: payloads are plain data).
    pub fields: Vec<PField>,
    /// The wire size when the caller knows it (spec structs); otherwise it is computed as a
    /// const expression over the fields (derive, whose nested types are opaque).
    pub size: Option<usize>,
}

/// One field (or padding run) in wire order.
pub struct PField {
    /// The field (`None` for padding and for the word of a bitfield).
    pub ident: Option<Ident>,
    /// What is on the wire.
    pub kind: PKind,
}

/// The wire form of a field.
pub enum PKind {
    /// Bytes written as zero and skipped when read.
    Pad(usize),
    /// A primitive (or array of them), optionally scaled to a physical float.
    Scalar {
        /// Wire type.
        scalar: Scalar,
        /// Raw to physical scaling.
        scale: Option<Scale>,
        /// Array length.
        count: Option<usize>,
    },
    /// A type that implements `Payload` itself (or an array of it).
    Nested {
        /// The type.
        ty: TokenStream,
        /// Array length.
        count: Option<usize>,
    },
    /// A generated enum with `to_raw`/`from_raw` over `scalar`.
    Enum {
        /// The enum type.
        ty: TokenStream,
        /// Wire type of the raw value.
        scalar: Scalar,
        /// Array length.
        count: Option<usize>,
    },
    /// Every byte left, as `ty` (the runtime's `Bytes<max>`).
    Bytes {
        /// The field's type.
        ty: TokenStream,
        /// The most bytes.
        max: usize,
    },
    /// An unsigned word whose bits are the struct fields `members`.
    Bits {
        /// The word on the wire.
        word: Scalar,
        /// Members, each a field of the struct.
        members: Vec<PBit>,
    },
}

/// A bit member of a [`PKind::Bits`] word.
pub struct PBit {
    /// Field name.
    pub ident: Ident,
    /// Lowest bit.
    pub shift: u32,
    /// Number of bits.
    pub width: u32,
    /// The field's type.
    pub ty: BitType,
}

/// The Rust type of a bit member.
pub enum BitType {
    /// `bool` (one bit).
    Bool,
    /// An unsigned integer.
    Uint(Prim),
    /// A generated enum; its raw type is given.
    Enum(TokenStream, Prim),
}

/// The Rust type of a primitive.
pub fn prim_type(prim: Prim) -> TokenStream {
    let t = Ident::new(prim.rust_name(), Span::call_site());
    quote!(#t)
}

fn suffix(s: Scalar) -> String {
    let base = s.prim.rust_name();
    if s.prim.size() == 1 {
        base.to_string()
    } else {
        match s.endian {
            Endian::Little => format!("{base}_le"),
            Endian::Big => format!("{base}_be"),
        }
    }
}

/// `r.u16_le()?`
pub fn read_scalar(s: Scalar) -> TokenStream {
    let m = format_ident!("{}", suffix(s));
    quote!(r.#m()?)
}

/// `w.put_u16_le(value)?`
pub fn write_scalar(s: Scalar, value: TokenStream) -> TokenStream {
    let m = format_ident!("put_{}", suffix(s));
    quote!(w.#m(#value)?;)
}

fn float_lit(x: f64) -> TokenStream {
    let lit = proc_macro2::Literal::f64_suffixed(x);
    quote!(#lit)
}

/// Reading one element of a field.
fn read_elem(kind: &PKind, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Scalar {
            scalar,
            scale: None,
            ..
        } => read_scalar(*scalar),
        PKind::Scalar {
            scalar,
            scale: Some(sc),
            ..
        } => {
            let raw = read_scalar(*scalar);
            let (f, o) = (float_lit(sc.factor), float_lit(sc.offset));
            let phys = prim_type(sc.physical);
            quote!(((#raw as f64) * #f + #o) as #phys)
        }
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::read(r)?),
        PKind::Enum { ty, scalar, .. } => {
            let raw = read_scalar(*scalar);
            quote!(#ty::from_raw(#raw)?)
        }
        PKind::Bytes { ty, .. } => quote!(<#ty>::read_rest(r)?),
        PKind::Pad(_) | PKind::Bits { .. } => quote!(()),
    }
}

/// Writing one element `value` (an expression of the field's element type).
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
        } => {
            let (f, o) = (float_lit(sc.factor), float_lit(sc.offset));
            let raw_ty = prim_type(scalar.prim);
            let clamped = match sc.clamp {
                Some((lo, hi)) => {
                    let (lo, hi) = (float_lit(lo), float_lit(hi));
                    quote!(((#value) as f64).clamp(#lo, #hi))
                }
                None => quote!(((#value) as f64)),
            };
            // `as` saturates out-of-range values and maps NaN to 0. No `round`/`trunc`: they are
            // not in `core`.
            let raw = match sc.rounding {
                crate::ir::Rounding::Nearest => quote! {{
                    let q = (#clamped - #o) / #f;
                    (if q >= 0.0 { q + 0.5 } else { q - 0.5 }) as #raw_ty
                }},
                // Toward zero, as a C cast; but a value within float noise of an integer is that
                // integer, so that a decoded value (raw * factor, rounded to f32) encodes back
                // to the same raw value.
                crate::ir::Rounding::Truncate => quote! {{
                    let q = (#clamped - #o) / #f;
                    let nearest = (if q >= 0.0 { q + 0.5 } else { q - 0.5 }) as i64 as f64;
                    let off = if q >= nearest { q - nearest } else { nearest - q };
                    let mag = if q >= 0.0 { q } else { -q };
                    (if off <= 1e-6 * (if mag > 1.0 { mag } else { 1.0 }) { nearest } else { q }) as #raw_ty
                }},
            };
            write_scalar(*scalar, raw)
        }
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::write(&#value, w)?;),
        PKind::Enum { scalar, .. } => write_scalar(*scalar, quote!((#value).to_raw())),
        PKind::Bytes { .. } => quote!(#value.write(w)?;),
        PKind::Pad(_) | PKind::Bits { .. } => quote!(),
    }
}

/// The Rust type of one element of a field.
pub fn elem_type(kind: &PKind) -> TokenStream {
    match kind {
        PKind::Scalar {
            scale: Some(sc), ..
        } => prim_type(sc.physical),
        PKind::Scalar { scalar, .. } => prim_type(scalar.prim),
        PKind::Nested { ty, .. } | PKind::Enum { ty, .. } | PKind::Bytes { ty, .. } => ty.clone(),
        PKind::Pad(_) | PKind::Bits { .. } => quote!(()),
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
        _ => None,
    }
}

/// The wire size of one field, as a constant expression.
fn size_expr(kind: &PKind, rt: &TokenStream) -> TokenStream {
    let n = count_of(kind).unwrap_or(1);
    match kind {
        PKind::Pad(len) => quote!(#len),
        PKind::Scalar { scalar, .. } | PKind::Enum { scalar, .. } => {
            let s = scalar.prim.size() * n;
            quote!(#s)
        }
        PKind::Nested { ty, count: None } => quote!(<#ty as #rt::Payload>::SIZE),
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::SIZE * #n),
        PKind::Bits { word, .. } => {
            let s = word.prim.size();
            quote!(#s)
        }
        PKind::Bytes { max, .. } => quote!(#max),
    }
}

/// `impl Payload for NAME`: SIZE, write and read, fields in wire order.
pub fn emit_payload_impl(def: &PayloadDef, paths: &RuntimePath) -> TokenStream {
    let rt = paths.private();
    let name = &def.name;
    let mut sizes = Vec::new();
    let mut writes = Vec::new();
    let mut reads = Vec::new();
    let mut inits = Vec::new();
    for (i, f) in def.fields.iter().enumerate() {
        sizes.push(size_expr(&f.kind, &rt));
        match &f.kind {
            PKind::Pad(n) => {
                writes.push(quote!(w.zeros(#n)?;));
                reads.push(quote!(r.skip(#n)?;));
            }
            PKind::Bits { word, members } => {
                let wt = prim_type(word.prim);
                let var = format_ident!("word{}", i);
                let mut parts = Vec::new();
                for m in members {
                    let id = &m.ident;
                    let shift = m.shift;
                    let mask = bit_mask(m.width, word.prim);
                    let raw = match &m.ty {
                        BitType::Bool => quote!(#wt::from(self.#id)),
                        BitType::Uint(_) => quote!((self.#id as #wt)),
                        BitType::Enum(_, _) => quote!((self.#id.to_raw() as #wt)),
                    };
                    parts.push(quote!(#var |= (#raw & #mask) << #shift;));
                    let field = quote!(((#var >> #shift) & #mask));
                    let value = match &m.ty {
                        BitType::Bool => quote!(#field != 0),
                        BitType::Uint(p) => {
                            let t = prim_type(*p);
                            quote!(#field as #t)
                        }
                        BitType::Enum(ty, p) => {
                            let t = prim_type(*p);
                            quote!(#ty::from_raw(#field as #t)?)
                        }
                    };
                    inits.push(quote!(#id: #value));
                }
                writes.push(quote! {
                    let mut #var: #wt = 0;
                    #(#parts)*
                });
                writes.push(write_scalar(*word, quote!(#var)));
                let read = read_scalar(*word);
                reads.push(quote!(let #var: #wt = #read;));
            }
            kind => {
                let Some(id) = &f.ident else { continue };
                let var = format_ident!("f_{}", id.to_string().trim_start_matches("r#"));
                match count_of(kind) {
                    None => {
                        writes.push(write_elem(kind, quote!(self.#id), &rt));
                        let read = read_elem(kind, &rt);
                        reads.push(quote!(let #var = #read;));
                    }
                    Some(_) => {
                        let w1 = write_elem(kind, quote!(*e), &rt);
                        writes.push(quote!(for e in self.#id.iter() { #w1 }));
                        let read = read_elem(kind, &rt);
                        let n = count_of(kind).unwrap_or(1);
                        let t = elem_type(kind);
                        reads.push(quote! {
                            let mut #var: [#t; #n] = [<#t as ::core::default::Default>::default(); #n];
                            for e in #var.iter_mut() { *e = #read; }
                        });
                    }
                }
                inits.push(quote!(#id: #var));
            }
        }
    }
    let size = match def.size {
        Some(n) => quote!(#n),
        None if sizes.is_empty() => quote!(0),
        None => quote!(#(#sizes)+*),
    };
    // A struct that ends with variable bytes: its minimum size and its actual size.
    let variable = def.fields.iter().find_map(|f| match (&f.kind, &f.ident) {
        (PKind::Bytes { max, .. }, Some(id)) => Some((*max, id.clone())),
        _ => None,
    });
    let variable = match variable {
        Some((max, id)) => quote! {
            const MIN_SIZE: usize = Self::SIZE - #max;
            #[inline]
            fn wire_len(&self) -> usize {
                Self::MIN_SIZE + self.#id.len()
            }
        },
        None => quote!(),
    };
    quote! {
        impl #rt::Payload for #name {
            const SIZE: usize = #size;
            #variable
            #[inline]
            fn write(&self, w: &mut #rt::Writer<'_>) -> ::core::result::Result<(), #rt::EncodeError> {
                #(#writes)*
                ::core::result::Result::Ok(())
            }
            #[inline]
            fn read(r: &mut #rt::Reader<'_>) -> ::core::result::Result<Self, #rt::DecodeError> {
                #(#reads)*
                ::core::result::Result::Ok(Self { #(#inits),* })
            }
        }
    }
}

fn bit_mask(width: u32, word: Prim) -> TokenStream {
    let m: u64 = if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    let lit = match word {
        Prim::U8 => proc_macro2::Literal::u8_suffixed(m as u8),
        Prim::U16 => proc_macro2::Literal::u16_suffixed(m as u16),
        Prim::U32 => proc_macro2::Literal::u32_suffixed(m as u32),
        _ => proc_macro2::Literal::u64_suffixed(m),
    };
    quote!(#lit)
}
