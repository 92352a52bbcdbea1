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
    /// The smallest wire size, for structs whose size varies (spec structs).
    pub min_size: Option<usize>,
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
    /// Bytes, as `ty` (the runtime's `Bytes<max>`): every byte left, or as many as the
    /// integer field `size_from` says.
    Bytes {
        /// The field's type.
        ty: TokenStream,
        /// The most bytes.
        max: usize,
        /// The field holding the number of bytes (of this struct, or of the struct that
        /// repeats this one).
        size_from: Option<Ident>,
    },
    /// Elements repeated to the end of the payload, as `ty` (the runtime's `Group<elem, max>`),
    /// read and written inline so that an element's sized bytes can use this struct's fields.
    Group {
        /// The field's type.
        ty: TokenStream,
        /// The element type.
        elem_ty: TokenStream,
        /// The element's fields.
        elem: Vec<PField>,
        /// The most elements.
        max: usize,
        /// The element's largest wire size.
        elem_size: usize,
    },
    /// A value present when bytes remain.
    Optional(Box<PKind>),
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
///
/// Whatever can fail here other than for want of bytes (clamped scales, enums) must also make
/// [`needs_only_bytes`] answer `None`; a kind it does not know it answers `None` for.
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
            match sc.clamp {
                // A value outside the clamp range would not encode back to the same bytes.
                Some((lo, hi)) => {
                    let (lo, hi) = (float_lit(lo), float_lit(hi));
                    quote!({
                        let v = (#raw as f64) * #f + #o;
                        if !#rt::within_clamp(v, #lo, #hi) {
                            return ::core::result::Result::Err(#rt::DecodeError::ValueOutOfRange);
                        }
                        v as #phys
                    })
                }
                None => quote!(((#raw as f64) * #f + #o) as #phys),
            }
        }
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::read(r)?),
        PKind::Enum { ty, scalar, .. } => {
            let raw = read_scalar(*scalar);
            quote!(#ty::from_raw(#raw)?)
        }
        PKind::Bytes {
            ty,
            size_from: None,
            ..
        } => quote!(<#ty>::read_rest(r)?),
        PKind::Bytes {
            ty,
            size_from: Some(n),
            ..
        } => {
            let var = local(n);
            quote!(<#ty>::from_slice(r.take(#var as usize)?).ok_or(#rt::DecodeError::SizeMismatch)?)
        }
        PKind::Pad(_) | PKind::Bits { .. } | PKind::Group { .. } | PKind::Optional(_) => quote!(()),
    }
}

/// The local variable a struct's read code holds field `id` in.
fn local(id: &Ident) -> Ident {
    format_ident!("f_{}", id.to_string().trim_start_matches("r#"))
}

/// An expression reading a whole field (array, optional, group included).
fn read_value(kind: &PKind, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Optional(inner) => {
            let read = read_value(inner, rt);
            quote!(if r.remaining() > 0 { ::core::option::Option::Some(#read) } else { ::core::option::Option::None })
        }
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
                while r.remaining() > 0 {
                    #(#lets)*
                    let available = r.position().saturating_add(r.remaining());
                    group
                        .push(#elem_ty { #(#inits),* })
                        .map_err(|_| #rt::DecodeError::PayloadLength { expected: <Self as #rt::Payload>::SIZE, actual: available })?;
                }
                group
            }}
        }
        k => match count_of(k) {
            None => read_elem(k, rt),
            Some(n) => {
                let read = read_elem(k, rt);
                let t = elem_type(k);
                quote! {{
                    let mut a: [#t; #n] = [<#t as ::core::default::Default>::default(); #n];
                    for e in a.iter_mut() { *e = #read; }
                    a
                }}
            }
        },
    }
}

/// Statements writing a whole field whose value is `value`; `owner` is the expression whose
/// fields sized bytes take their size from (`self`).
fn write_value(
    kind: &PKind,
    value: TokenStream,
    owner: &TokenStream,
    rt: &TokenStream,
) -> TokenStream {
    match kind {
        PKind::Optional(inner) => {
            let w = write_value(inner, quote!((*v)), owner, rt);
            quote!(if let ::core::option::Option::Some(v) = &#value { #w })
        }
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
            if #value.len() != #owner.#n as usize {
                return ::core::result::Result::Err(#rt::EncodeError::ValueOutOfRange);
            }
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
fn variable_len(kind: &PKind, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
    match kind {
        PKind::Bytes { .. } => Some(quote!(#value.len())),
        PKind::Optional(inner) => {
            let size = variable_len(inner, quote!(v), rt).unwrap_or_else(|| size_expr(inner, rt));
            Some(
                quote!(match &#value { ::core::option::Option::Some(v) => #size, ::core::option::Option::None => 0 }),
            )
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
                    None => fixed.push(size_expr(&f.kind, rt)),
                }
            }
            Some(quote!(#value.iter().fold(0usize, |acc, e| {
                const FIXED: usize = 0 #(+ #fixed)*;
                acc.saturating_add(FIXED #(.saturating_add(#vars))*)
            })))
        }
        _ => None,
    }
}

/// The wire size of a fixed-size field.
fn fixed_size(kind: &PKind) -> usize {
    let n = count_of(kind).unwrap_or(1);
    match kind {
        PKind::Pad(len) => *len,
        PKind::Scalar { scalar, .. } | PKind::Enum { scalar, .. } => scalar.prim.size() * n,
        PKind::Bits { word, .. } => word.prim.size(),
        PKind::Bytes { max, .. } => *max,
        PKind::Group { max, elem_size, .. } => max * elem_size,
        PKind::Optional(inner) => fixed_size(inner),
        // Nested payloads are sized by their own impl; only spec structs call this, whose
        // nested structs are fixed and whose size the IR knows.
        PKind::Nested { .. } => 0,
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
        // An `Unknown(raw)` holding a known variant's value would decode as that variant.
        PKind::Enum { ty, scalar, .. } => {
            let w = write_scalar(*scalar, quote!(raw));
            quote! {{
                let v = #value;
                let raw = v.to_raw();
                if #ty::from_raw(raw) != ::core::result::Result::Ok(v) {
                    return ::core::result::Result::Err(#rt::EncodeError::ValueOutOfRange);
                }
                #w
            }}
        }
        PKind::Bytes { .. } => quote!(#value.write(w)?;),
        PKind::Pad(_) | PKind::Bits { .. } | PKind::Group { .. } | PKind::Optional(_) => quote!(),
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
        | PKind::Group { ty, .. } => ty.clone(),
        PKind::Optional(inner) => {
            let t = field_type(inner);
            quote!(::core::option::Option<#t>)
        }
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
        PKind::Group { .. } | PKind::Optional(_) => {
            let s = fixed_size(kind);
            quote!(#s)
        }
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
                        BitType::Enum(ty, _) => quote!({
                            let raw = self.#id.to_raw();
                            if #ty::from_raw(raw) != ::core::result::Result::Ok(self.#id) {
                                return ::core::result::Result::Err(#rt::EncodeError::ValueOutOfRange);
                            }
                            raw as #wt
                        }),
                    };
                    // A member value wider than its bits would be cut: refuse it.
                    if !matches!(m.ty, BitType::Bool) {
                        parts.push(quote! {
                            if (#raw as u64) > (#mask as u64) {
                                return ::core::result::Result::Err(#rt::EncodeError::ValueOutOfRange);
                            }
                        });
                    }
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
                let var = local(id);
                writes.push(write_value(kind, quote!(self.#id), &quote!(self), &rt));
                let read = read_value(kind, &rt);
                reads.push(quote!(let #var = #read;));
                inits.push(quote!(#id: #var));
            }
        }
    }
    let size = match def.size {
        Some(n) => quote!(#n),
        None if sizes.is_empty() => quote!(0),
        None => quote!(#(#sizes)+*),
    };
    // A struct with fields of variable size: its minimum size and its actual size.
    let mut fixed = Vec::new();
    let mut lens = Vec::new();
    for f in &def.fields {
        match (variable_len(&f.kind, quote!(x), &rt), &f.ident) {
            (Some(_), Some(id)) => lens.extend(variable_len(&f.kind, quote!(self.#id), &rt)),
            _ => fixed.push(size_expr(&f.kind, &rt)),
        }
    }
    let variable = if lens.is_empty() {
        quote!()
    } else {
        let min = match def.min_size {
            Some(n) => quote!(#n),
            None => quote!(0 #(+ #fixed)*),
        };
        quote! {
            const MIN_SIZE: usize = #min;
            #[inline]
            fn wire_len(&self) -> usize {
                const FIXED: usize = 0 #(+ #fixed)*;
                FIXED #(.saturating_add(#lens))*
            }
        }
    };
    // A value of fixed size: its room checked once, not per field.
    let reserve = if lens.is_empty() && !writes.is_empty() {
        quote!(let w = &mut w.reserve(<Self as #rt::Payload>::SIZE)?;)
    } else {
        quote!()
    };
    let only_bytes = if lens.is_empty() {
        needs_only_bytes(&def.fields, &rt)
    } else {
        None
    };
    let only_bytes = only_bytes.map(|parts| {
        let parts = if parts.is_empty() {
            vec![quote!(true)]
        } else {
            parts
        };
        quote!(const READ_NEEDS_ONLY_BYTES: bool = #(#parts)&&*;)
    });
    quote! {
        impl #rt::Payload for #name {
            const SIZE: usize = #size;
            #variable
            #only_bytes
            #[inline]
            fn write(&self, w: &mut #rt::Writer<'_>) -> ::core::result::Result<(), #rt::EncodeError> {
                #reserve
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

/// Whether reading `fields` can fail only for want of bytes (`Payload::READ_NEEDS_ONLY_BYTES`):
/// `None` if some field can fail otherwise (an enum, a clamped value, a bit member that is an
/// enum: the failures [`read_elem`] and the bit members' reads emit) or has a variable size;
/// else the conditions on nested types, all of which must hold. Checked against reading field
/// by field on every bundled spec's structs (`tests/tests/payload_length_first.rs`).
fn needs_only_bytes(fields: &[PField], rt: &TokenStream) -> Option<Vec<TokenStream>> {
    let mut nested = Vec::new();
    for f in fields {
        match &f.kind {
            PKind::Pad(_) => {}
            PKind::Scalar { scale, .. } if scale.as_ref().is_none_or(|s| s.clamp.is_none()) => {}
            PKind::Nested { ty, .. } => {
                let condition = quote!(<#ty as #rt::Payload>::READ_NEEDS_ONLY_BYTES);
                // Once per nested type.
                if !nested
                    .iter()
                    .any(|c: &TokenStream| c.to_string() == condition.to_string())
                {
                    nested.push(condition);
                }
            }
            PKind::Bits { members, .. }
                if members.iter().all(|m| !matches!(m.ty, BitType::Enum(..))) => {}
            _ => return None,
        }
    }
    Some(nested)
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
