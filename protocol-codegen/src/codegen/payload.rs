//! The one payload code generator: `impl Payload` (wire read and write) for a struct described
//! as a [`PayloadDef`], which `types::payload_def` makes of an IR struct. A spec's structs and a
//! `#[derive(Payload)]` struct reach it through the same validation and the same IR, so both
//! produce the same code for the same layout.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::ir::{BitOrder, ByteOrder, Prim, Rounding, Scalar, Scale};

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
    /// A bit-packed array (the runtime's `packed`), read and written as `size` bytes.
    Packed {
        /// Elements.
        count: usize,
        /// Bits of each element.
        bits: u32,
        /// How the bits fill the bytes.
        order: BitOrder,
        /// Rust type of a raw element.
        prim: Prim,
        /// Raw to physical scaling of each element.
        scale: Option<Scale>,
        /// Bytes on the wire.
        size: usize,
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
    /// Elements of a primitive or enum (`elem`, without count) as `ty` (the runtime's
    /// `Group<T, max>`): to the end of the payload, or as many as the integer field
    /// `size_from` says.
    Array {
        /// The field's type.
        ty: TokenStream,
        /// One element.
        elem: Box<PKind>,
        /// The most elements.
        max: usize,
        /// The field holding the number of elements.
        size_from: Option<Ident>,
        /// Bytes of one element.
        elem_size: usize,
    },
    /// A runtime type whose wire size varies (`NulStr<N>`), read, written and sized by its
    /// own `Payload` impl; fields may follow it.
    Var {
        /// The type.
        ty: TokenStream,
    },
    /// A check value over the fields `first..=last` of the struct (indices into its fields),
    /// verified on read and computed on write by the runtime (`verify_check`, `put_check`);
    /// no field of the Rust struct.
    Check {
        /// The `Checksum` expression.
        checksum: TokenStream,
        /// First field covered.
        first: usize,
        /// Last field covered.
        last: usize,
        /// Byte order of the stored value.
        endian: ByteOrder,
        /// Bytes of the stored value.
        width: usize,
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
    let base = s.prim.spec_name();
    if s.prim.size() == 1 {
        base.to_string()
    } else {
        match s.endian {
            ByteOrder::Little => format!("{base}_le"),
            ByteOrder::Big => format!("{base}_be"),
        }
    }
}

/// `r.u16_le()?`
pub fn read_scalar(s: Scalar) -> TokenStream {
    read_scalar_from(&quote!(r), s)
}

/// `reader.u16_le()?`, `reader` an expression of type `&mut Reader`.
fn read_scalar_from(reader: &TokenStream, s: Scalar) -> TokenStream {
    let m = format_ident!("{}", suffix(s));
    quote!(#reader.#m()?)
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

/// A scaled field's constant in the field's float type: its arithmetic stays in that type
/// (an `f32` field computes in `f32`, no `f64` soft-float on a target with an `f32` FPU).
fn scale_lit(x: f64, sc: &Scale) -> TokenStream {
    match sc.physical {
        Prim::F32 => {
            let lit = proc_macro2::Literal::f32_suffixed(x as f32);
            quote!(#lit)
        }
        _ => float_lit(x),
    }
}

/// The runtime's name of a rounding mode.
fn rounding(rt: &TokenStream, r: Rounding) -> TokenStream {
    match r {
        Rounding::Nearest => quote!(#rt::Rounding::Nearest),
        Rounding::Truncate => quote!(#rt::Rounding::Truncate),
    }
}

/// Reading one element of a field from `reader` (`r`, or `r.pad(n)?` after padding). The
/// field rules are the runtime's (`field`), called with the field's constants.
///
/// Whatever can fail here other than for want of bytes (clamped scales, enums) must also make
/// [`needs_only_bytes`] answer `None`; a kind it does not know it answers `None` for.
fn read_elem(kind: &PKind, reader: &TokenStream, rt: &TokenStream) -> TokenStream {
    match kind {
        PKind::Scalar {
            scalar,
            scale: None,
            ..
        } => read_scalar_from(reader, *scalar),
        PKind::Scalar {
            scalar,
            scale: Some(sc),
            ..
        } => to_physical(read_scalar_from(reader, *scalar), sc, rt),
        PKind::Nested { ty, .. } => quote!(<#ty as #rt::Payload>::read(#reader)?),
        PKind::Enum { ty, scalar, .. } => {
            let raw = read_scalar_from(reader, *scalar);
            quote!(#ty::from_raw(#raw)?)
        }
        PKind::Bytes {
            ty,
            size_from: None,
            ..
        } => quote!(<#ty>::read_rest(r)?),
        PKind::Var { ty } => quote!(<#ty as #rt::Payload>::read(r)?),
        PKind::Bytes {
            ty,
            size_from: Some(n),
            ..
        } => {
            let var = local(n);
            quote!(<#ty>::read_sized(r, #var as u64)?)
        }
        PKind::Pad(_)
        | PKind::Bits { .. }
        | PKind::Group { .. }
        | PKind::Array { .. }
        | PKind::Optional(_)
        | PKind::Packed { .. }
        | PKind::Check { .. } => quote!(()),
    }
}

/// The physical value of the raw integer expression `raw`.
fn to_physical(raw: TokenStream, sc: &Scale, rt: &TokenStream) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let phys = prim_type(sc.physical);
    let value = quote!(#rt::to_physical(#raw as #phys, #f, #o));
    match sc.clamp {
        // A value outside the clamp range would not encode back to the same bytes.
        Some((lo, hi)) => {
            let (lo, hi) = (scale_lit(lo, sc), scale_lit(hi, sc));
            quote!(#rt::check_clamp(#value, #lo, #hi)?)
        }
        None => value,
    }
}

/// The raw integer (of type `raw`) of the physical value `value`: clamped (if the field
/// clamps), quantized and fitted by the runtime; a value the raw type cannot hold is an error.
fn to_raw(value: TokenStream, sc: &Scale, raw: Option<Prim>, rt: &TokenStream) -> TokenStream {
    let (f, o) = (scale_lit(sc.factor, sc), scale_lit(sc.offset, sc));
    let physical = match sc.clamp {
        Some((lo, hi)) => {
            let (lo, hi) = (scale_lit(lo, sc), scale_lit(hi, sc));
            quote!(#rt::clamp(#value, #lo, #hi))
        }
        None => value,
    };
    let mode = rounding(rt, sc.rounding);
    let fit = match raw {
        Some(p) => {
            let t = prim_type(p);
            quote!(#rt::fit::<#t>)
        }
        None => quote!(#rt::fit),
    };
    quote!(#fit(#rt::quantize(#physical, #f, #o, #mode))?)
}

/// The runtime's name of a bit order.
fn bit_order(rt: &TokenStream, order: BitOrder) -> TokenStream {
    match order {
        BitOrder::LsbFirst => quote!(#rt::BitOrder::LsbFirst),
        BitOrder::MsbFirst => quote!(#rt::BitOrder::MsbFirst),
    }
}

/// Reading a bit-packed array: its bytes at once, then each element from them.
fn read_packed(kind: &PKind, rt: &TokenStream) -> TokenStream {
    let PKind::Packed {
        count,
        bits,
        order,
        prim,
        scale,
        size,
    } = kind
    else {
        return quote!(());
    };
    let order = bit_order(rt, *order);
    let raw = quote!(#rt::get_packed(bytes, i, #bits, #order));
    let (t, elem) = match scale {
        None => {
            let t = prim_type(*prim);
            (t.clone(), quote!(#raw as #t))
        }
        Some(sc) => (prim_type(sc.physical), to_physical(raw, sc, rt)),
    };
    quote! {{
        let bytes = r.take(#size)?;
        let mut a: [#t; #count] = [<#t as ::core::default::Default>::default(); #count];
        for (i, e) in a.iter_mut().enumerate() { *e = #elem; }
        a
    }}
}

/// Writing a bit-packed array `value`: each element into its bits of a zeroed run of bytes,
/// then the run.
fn write_packed(kind: &PKind, value: TokenStream, rt: &TokenStream) -> TokenStream {
    let PKind::Packed {
        bits,
        order,
        prim,
        scale,
        size,
        ..
    } = kind
    else {
        return quote!();
    };
    let order = bit_order(rt, *order);
    let raw = match scale {
        None => quote!(*e as u64),
        Some(sc) => {
            let raw = to_raw(quote!(*e), sc, Some(*prim), rt);
            quote!(#raw as u64)
        }
    };
    quote! {{
        let mut bytes = [0u8; #size];
        for (i, e) in #value.iter().enumerate() {
            #rt::set_packed(&mut bytes, i, #bits, #order, #raw)?;
        }
        w.put_bytes(&bytes)?;
    }}
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
                            a.push(#read).map_err(|_| #rt::DecodeError::SizeMismatch)?;
                        }
                        a
                    }}
                }
            }
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

/// `Ok(read)`, the value of a closure that reads: `read` without its final `?` when it has
/// one (`Ok(x?)` is `x`).
fn ok_of(read: TokenStream, rt: &TokenStream) -> TokenStream {
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
fn write_value(
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
fn variable_len(kind: &PKind, value: TokenStream, rt: &TokenStream) -> Option<TokenStream> {
    match kind {
        PKind::Bytes { .. } => Some(quote!(#value.len())),
        PKind::Var { ty } => Some(quote!(<#ty as #rt::Payload>::wire_len(&#value))),
        PKind::Array { elem_size, .. } => Some(quote!(#value.len().saturating_mul(#elem_size))),
        PKind::Optional(inner) => {
            let size = variable_len(inner, quote!(v), rt).unwrap_or_else(|| size_expr(inner, rt));
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
        PKind::Var { ty } => quote!(<#ty as #rt::Payload>::SIZE),
        PKind::Check { width, .. } => quote!(#width),
        PKind::Packed { size, .. } => quote!(#size),
        PKind::Group { .. } | PKind::Array { .. } | PKind::Optional(_) => {
            let s = fixed_size(kind);
            quote!(#s)
        }
    }
}

/// The code of one struct's `write` and `read`, field by field in wire order.
#[derive(Default)]
struct Body {
    /// Statements of `write`.
    writes: Vec<TokenStream>,
    /// Statements of `read` before the value is built.
    reads: Vec<TokenStream>,
    /// `field: expression` of the value `read` builds.
    inits: Vec<TokenStream>,
    /// Statements of `read` after the value is built (trailing padding).
    after: Vec<TokenStream>,
    /// Whether a read expression needs an earlier field (sized bytes, groups), a statement
    /// comes between fields (a bit word) or padding comes before a field that is read in more
    /// than one step (an array): then every field is read into a local first.
    sequenced: bool,
}

impl Body {
    fn of(fields: &[PField], rt: &TokenStream) -> Body {
        let mut b = Body::default();
        for (i, f) in fields.iter().enumerate() {
            b.check_starts(fields, i);
            match &f.kind {
                PKind::Pad(n) => {
                    b.writes.push(quote!(w.zeros(#n)?;));
                    b.reads.push(quote!(r.skip(#n)?;));
                }
                PKind::Bits { word, members } => {
                    b.bits(&format_ident!("word{}", i), *word, members, rt);
                    b.sequenced = true;
                }
                PKind::Check {
                    checksum, endian, ..
                } => {
                    let (start, end) = (
                        format_ident!("check{i}_start"),
                        format_ident!("check{i}_end"),
                    );
                    let order = match endian {
                        ByteOrder::Little => quote!(#rt::ByteOrder::Little),
                        ByteOrder::Big => quote!(#rt::ByteOrder::Big),
                    };
                    b.reads
                        .push(quote!(#rt::verify_check(r, &#start, #end, &#checksum, #order)?;));
                    b.writes
                        .push(quote!(#rt::put_check(w, #start, #end, &#checksum, #order)?;));
                }
                PKind::Bytes {
                    ty,
                    size_from: None,
                    ..
                } if i + 1 < fields.len() => {
                    // Every byte left but the checks after it.
                    let Some(id) = &f.ident else { continue };
                    let keep: usize = fields[i + 1..].iter().map(|f| fixed_size(&f.kind)).sum();
                    b.writes.push(quote!(self.#id.write(w)?;));
                    let var = local(id);
                    b.reads
                        .push(quote!(let #var = <#ty>::read_rest_but(r, #keep)?;));
                    b.inits.push(quote!(#id: #var));
                }
                kind => {
                    let Some(id) = &f.ident else { continue };
                    b.sequenced |= needs_locals(kind);
                    b.writes
                        .push(write_value(kind, quote!(self.#id), &quote!(self), rt));
                    let var = local(id);
                    let read = read_value(kind, rt);
                    b.reads.push(quote!(let #var = #read;));
                    b.inits.push(quote!(#id: #var));
                }
            }
            b.check_ends(fields, i);
        }
        b.sequenced |= !pads_fold(fields);
        if !b.sequenced {
            b.inline_reads(fields, rt);
        }
        b
    }

    /// Where the checks whose covered fields start at field `i` begin: a copy of the reader,
    /// the writer's position.
    fn check_starts(&mut self, fields: &[PField], i: usize) {
        for (k, f) in fields.iter().enumerate() {
            if let PKind::Check { first, .. } = f.kind {
                if first == i {
                    let start = format_ident!("check{k}_start");
                    self.reads.push(quote!(let #start = r.clone();));
                    self.writes.push(quote!(let #start = w.position();));
                    self.sequenced = true;
                }
            }
        }
    }

    /// Where the checks whose covered fields end at field `i` end: the position after it.
    fn check_ends(&mut self, fields: &[PField], i: usize) {
        for (k, f) in fields.iter().enumerate() {
            if let PKind::Check { last, .. } = f.kind {
                if last == i {
                    let end = format_ident!("check{k}_end");
                    self.reads.push(quote!(let #end = r.position();));
                    self.writes.push(quote!(let #end = w.position();));
                }
            }
        }
    }

    /// Nothing but padding between the fields: each field read straight into the value, in
    /// order, the padding before it skipped by the read itself (`r.pad(3)?.f32_le()?`), and
    /// the padding after the last field once the value is built.
    fn inline_reads(&mut self, fields: &[PField], rt: &TokenStream) {
        self.reads.clear();
        self.inits.clear();
        let mut pad = 0usize;
        for f in fields {
            match (&f.kind, &f.ident) {
                (PKind::Pad(n), _) => pad += n,
                (kind, Some(id)) => {
                    let read = match pad {
                        0 => read_value(kind, rt),
                        n => read_elem(kind, &quote!(r.pad(#n)?), rt),
                    };
                    pad = 0;
                    self.inits.push(quote!(#id: #read));
                }
                _ => {}
            }
        }
        if pad > 0 {
            self.after.push(quote!(r.skip(#pad)?;));
        }
    }

    /// A bitfield word: each member set into (and got from) its bits by the runtime.
    fn bits(&mut self, var: &Ident, word: Scalar, members: &[PBit], rt: &TokenStream) {
        let wt = prim_type(word.prim);
        let mut sets = Vec::new();
        for m in members {
            let (id, shift, width) = (&m.ident, m.shift, m.width);
            let raw = match &m.ty {
                BitType::Bool => quote!(u64::from(self.#id)),
                BitType::Uint(_) => quote!(self.#id as u64),
                // Through the word type, as the word holds it (a signed raw value's bits).
                BitType::Enum(ty, _) => {
                    quote!(#rt::enum_raw(self.#id, #ty::to_raw, #ty::from_raw)? as #wt as u64)
                }
            };
            sets.push(quote!(#var = #rt::set_bits(#var, #raw, #shift, #width)?;));
            let field = quote!(#rt::get_bits(#var, #shift, #width));
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
            self.inits.push(quote!(#id: #value));
        }
        self.writes.push(quote!(let mut #var = 0u64; #(#sets)*));
        self.writes.push(write_scalar(word, quote!(#var as #wt)));
        let read = read_scalar(word);
        self.reads.push(quote!(let #var = u64::from(#read);));
    }
}

/// Whether the padding of `fields` can be skipped by the read of the field after it: that
/// field is read in one step (a single value, not an array, group or optional field).
fn pads_fold(fields: &[PField]) -> bool {
    fields
        .windows(2)
        .all(|pair| match (&pair[0].kind, &pair[1].kind) {
            (PKind::Pad(_), PKind::Pad(_)) => true,
            (PKind::Pad(_), next) => {
                matches!(
                    next,
                    PKind::Scalar { count: None, .. }
                        | PKind::Nested { count: None, .. }
                        | PKind::Enum { count: None, .. }
                )
            }
            _ => true,
        })
}

/// Whether reading a field names an earlier field (sized bytes; a group, whose elements' sized
/// bytes may name the repeating struct's fields).
fn needs_locals(kind: &PKind) -> bool {
    match kind {
        PKind::Group { .. } => true,
        PKind::Bytes { size_from, .. } | PKind::Array { size_from, .. } => size_from.is_some(),
        PKind::Optional(inner) => needs_locals(inner),
        _ => false,
    }
}

/// `const MIN_SIZE` and `fn wire_len` of a struct with fields of variable size (nothing for
/// a struct of fixed size); `None` when the struct has a fixed size.
fn emit_variable_size(def: &PayloadDef, rt: &TokenStream) -> Option<TokenStream> {
    let mut fixed = Vec::new();
    let mut lens = Vec::new();
    for f in &def.fields {
        match (variable_len(&f.kind, quote!(x), rt), &f.ident) {
            (Some(_), Some(id)) => lens.extend(variable_len(&f.kind, quote!(self.#id), rt)),
            _ => fixed.push(size_expr(&f.kind, rt)),
        }
    }
    if lens.is_empty() {
        return None;
    }
    let min = match def.min_size {
        Some(n) => quote!(#n),
        None => quote!(0 #(+ #fixed)*),
    };
    Some(quote! {
        const MIN_SIZE: usize = #min;
        #[inline]
        fn wire_len(&self) -> usize {
            const FIXED: usize = 0 #(+ #fixed)*;
            FIXED #(.saturating_add(#lens))*
        }
    })
}

/// `impl Payload for NAME`: SIZE, write and read, fields in wire order. `rt` is the path of the
/// runtime's `__private` module as the impl sees it.
pub fn emit_payload_impl(def: &PayloadDef, rt: &TokenStream) -> TokenStream {
    let name = &def.name;
    let sizes: Vec<TokenStream> = def.fields.iter().map(|f| size_expr(&f.kind, rt)).collect();
    let Body {
        writes,
        reads,
        inits,
        after,
        ..
    } = Body::of(&def.fields, rt);
    // Padding after the last field is skipped once the value is built.
    let value = if after.is_empty() {
        quote!(#rt::Ok(Self { #(#inits),* }))
    } else {
        quote! {
            let value = Self { #(#inits),* };
            #(#after)*
            #rt::Ok(value)
        }
    };
    let size = match def.size {
        Some(n) => quote!(#n),
        None if sizes.is_empty() => quote!(0),
        None => quote!(#(#sizes)+*),
    };
    let variable = emit_variable_size(def, rt);
    // A value of fixed size: its room checked once, not per field.
    let reserve = if variable.is_none() && !writes.is_empty() {
        quote!(let w = &mut w.reserve(<Self as #rt::Payload>::SIZE)?;)
    } else {
        quote!()
    };
    let only_bytes = match variable {
        None => needs_only_bytes(&def.fields, rt),
        Some(_) => None,
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
            fn write(&self, w: &mut #rt::Writer<'_>) -> #rt::EncodeResult {
                #reserve
                #(#writes)*
                #rt::Ok(())
            }
            #[inline]
            fn read(r: &mut #rt::Reader<'_>) -> #rt::DecodeResult<Self> {
                #(#reads)*
                #value
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
            PKind::Packed { scale, .. } if scale.as_ref().is_none_or(|s| s.clamp.is_none()) => {}
            _ => return None,
        }
    }
    Some(nested)
}
