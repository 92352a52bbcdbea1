//! `#[derive(Payload)]` for hand-written structs: the struct and its `#[payload(...)]`
//! attributes are lowered into a draft spec of one struct ([`validate::derive`]), checked by the
//! rules that check a spec's structs (so a derive gets a spec's diagnostics, each on the
//! attribute or type it is about), and printed by the payload printer that prints spec structs.
//!
//! Attributes:
//! - on the struct: `#[payload(byte_order = "big")]` (default `"little"`),
//!   `#[payload(crate = "::my::protocol")]` (where the `protocol-kit` crate is, when it is not
//!   `::protocol_kit`; a bare path works too);
//! - on a field: `#[payload(byte_order = "big")]`, `#[payload(pad_before = 3)]`,
//!   `#[payload(pad_after = 1)]`, `#[payload(scale = 0.001, raw = "i16")]` (an `f32`/`f64` field
//!   stored as a scaled integer), `#[payload(raw = "u24")]` alone on an integer field (a `u32`
//!   or `i32` on the wire as the 24-bit `u24`/`i24`), `#[payload(repr = "u8")]` (a type with
//!   `to_raw`/`from_raw`, such as a generated enum).
//!
//! Fields of primitive types (`u8` … `i64`, `f32`, `f64`, `bool`) and arrays of them are
//! encoded directly; any other type must implement `Payload` itself.
//!
//! [`validate::derive`]: crate::validate::derive

use std::ops::Range;

use indexmap::IndexMap;
use proc_macro2::{Span, TokenStream};
use quote::{ToTokens, quote};
use syn::spanned::Spanned as _;
use syn::{Data, DeriveInput, Expr, Fields, Lit, Type};
use toml::Spanned;

use crate::codegen::RuntimePath;
use crate::codegen::payload::{PayloadDef, emit_payload_impl, payload_def};
use crate::diag::{Diagnostic, Diagnostics};
use crate::ir::{ByteOrder, Prim};
use crate::spec::model::{CountDef, FieldDef, ProtocolTable, SpecFile, StructDef};
use crate::validate::derive::{Foreign, validate_derive};

/// Expand `#[derive(Payload)]`.
///
/// # Errors
/// A `syn::Error` pointing at the offending item for anything that is not a struct with named
/// fields or an attribute it cannot read, and then every error the spec rules find, each at
/// the attribute or type it is about.
pub fn derive_payload(input: &DeriveInput) -> syn::Result<TokenStream> {
    let named = check_struct_shape(input)?;
    let mut draft = Draft::new(input.ident.span());
    let (byte_order, paths) = parse_struct_attrs(input, &mut draft)?;
    let name = input.ident.to_string();
    let mut fields = Vec::new();
    for f in &named.named {
        draft.field(f, &name, &mut fields)?;
    }
    let spec = draft.spec(&input.ident, byte_order, fields);
    let mut diags = Diagnostics::new();
    let protocol = validate_derive(&spec, &draft.foreign, &mut diags);
    if let Some(e) = draft.errors(diags.into_sorted()) {
        return Err(e);
    }
    let Some(s) = protocol.as_ref().and_then(|p| Some((p, p.structs.last()?))) else {
        return Err(syn::Error::new(
            input.ident.span(),
            "#[derive(Payload)] failed",
        ));
    };
    let def = PayloadDef {
        size: None,
        min_size: None,
        ..payload_def(s.0, s.1)
    };
    Ok(emit_payload_impl(&def, &paths.private()))
}

/// The draft being built: the span of each spanned value (a value's span in the draft is
/// `i..i + 1`, `i` its index here; index 0 is the struct's name, where an error about the whole
/// struct points) and the user's types its fields name.
struct Draft {
    spans: Vec<Span>,
    foreign: Vec<Foreign>,
}

impl Draft {
    fn new(name: Span) -> Self {
        Draft {
            spans: vec![name],
            foreign: Vec::new(),
        }
    }

    /// `value`, spanned at `span` in the draft.
    fn at<T>(&mut self, span: Span, value: T) -> Spanned<T> {
        let i = self.spans.len();
        self.spans.push(span);
        Spanned::new(i..i + 1, value)
    }

    /// The source span of a draft span.
    fn span(&self, range: &Range<usize>) -> Span {
        self.spans
            .get(range.start)
            .or(self.spans.first())
            .copied()
            .unwrap_or_else(Span::call_site)
    }

    /// The errors as one compile error (each at its own span), if any.
    fn errors(&self, diags: Vec<Diagnostic>) -> Option<syn::Error> {
        diags
            .into_iter()
            .map(|d| {
                let message = match &d.help {
                    Some(help) => format!("{}\n= help: {help}", d.message),
                    None => d.message.clone(),
                };
                syn::Error::new(self.span(&d.span), message)
            })
            .reduce(|mut all, e| {
                all.combine(e);
                all
            })
    }

    /// A spec of the one struct `name`.
    fn spec(
        &mut self,
        name: &syn::Ident,
        byte_order: Option<Spanned<String>>,
        fields: Vec<Spanned<FieldDef>>,
    ) -> SpecFile {
        let at = name.span();
        let protocol = ProtocolTable {
            name: self.at(at, "derive".to_string()),
            version: None,
            doc: None,
            byte_order: None,
        };
        let def = StructDef {
            doc: None,
            byte_order,
            fields: self.at(at, fields),
        };
        let mut structs = IndexMap::new();
        structs.insert(self.at(at, name.to_string()), self.at(at, def));
        SpecFile {
            protocol: self.at(at, protocol),
            constants: IndexMap::new(),
            addresses: IndexMap::new(),
            checksums: IndexMap::new(),
            frames: IndexMap::new(),
            directions: IndexMap::new(),
            commands: IndexMap::new(),
            structs,
            enums: IndexMap::new(),
            session: None,
            registers: None,
        }
    }

    /// One field of the struct `owner` as draft fields (with its padding entries).
    fn field(
        &mut self,
        f: &syn::Field,
        owner: &str,
        out: &mut Vec<Spanned<FieldDef>>,
    ) -> syn::Result<()> {
        let a = parse_field_attrs(f)?;
        let Some(id) = &f.ident else {
            return Ok(());
        };
        if let Some((span, n)) = a.pad_before {
            let pad = FieldDef {
                pad: Some(self.at(span, n)),
                ..FieldDef::default()
            };
            out.push(self.at(span, pad));
        }
        let (elem, count) = array_elem(&f.ty);
        let elem_text = match elem.to_token_stream().to_string() {
            t if t == "Self" => owner.to_string(),
            t => t,
        };
        let order = a.endian.as_ref();
        let ty = match (a.repr, &a.raw) {
            (Some(repr), _) => {
                self.foreign_type(elem, &elem_text, Some(repr))?;
                elem_text.clone()
            }
            (None, Some(raw)) => with_order(&raw.value(), order),
            (None, None) if Prim::from_rust_name(&elem_text).is_some() => {
                with_order(&elem_text, order)
            }
            (None, None) => {
                if elem_text != owner {
                    self.foreign_type(elem, &elem_text, None)?;
                }
                elem_text.clone()
            }
        };
        let ty_span = a.raw.as_ref().map_or(elem.span(), syn::LitStr::span);
        let count = match count {
            Some(len) => Some(self.count(len)?),
            None => None,
        };
        let name = id.to_string().trim_start_matches("r#").to_string();
        let def = FieldDef {
            name: Some(self.at(id.span(), name)),
            ty: Some(self.at(ty_span, ty)),
            count,
            scale: a.scale.map(|(span, x)| self.at(span, x)),
            rust: Some(self.at(elem.span(), elem_text)),
            ..FieldDef::default()
        };
        out.push(self.at(f.span(), def));
        if let Some((span, n)) = a.pad_after {
            let pad = FieldDef {
                pad: Some(self.at(span, n)),
                ..FieldDef::default()
            };
            out.push(self.at(span, pad));
        }
        Ok(())
    }

    /// An array's length, which must be an integer literal so that the wire size is known at
    /// expansion.
    fn count(&mut self, len: &Expr) -> syn::Result<Spanned<CountDef>> {
        match len {
            Expr::Lit(syn::ExprLit {
                lit: Lit::Int(i), ..
            }) => Ok(self.at(len.span(), CountDef::Literal(i.base10_parse()?))),
            _ => Err(syn::Error::new(
                len.span(),
                "array length must be an integer literal",
            )),
        }
    }

    /// Record a user's type that a field names: one kind of use per type.
    fn foreign_type(&mut self, ty: &Type, path: &str, repr: Option<Prim>) -> syn::Result<()> {
        match self.foreign.iter().find(|x| x.path == path) {
            Some(x) if x.repr == repr => Ok(()),
            Some(_) => Err(syn::Error::new(
                ty.span(),
                format!("`{path}` is used with two different `repr`s (or with and without one)"),
            )),
            None => {
                self.foreign.push(Foreign {
                    path: path.to_string(),
                    repr,
                });
                Ok(())
            }
        }
    }
}

/// A wire type with the field's own byte order, if it states one (the struct's otherwise).
fn with_order(ty: &str, order: Option<&ByteOrder>) -> String {
    match order {
        Some(_) if ty == "bool" => ty.to_string(),
        Some(ByteOrder::Little) => format!("{ty}le"),
        Some(ByteOrder::Big) => format!("{ty}be"),
        None => ty.to_string(),
    }
}

/// A field's `#[payload(...)]` attributes, each with the span of its value.
#[derive(Default)]
struct FieldAttrs {
    endian: Option<ByteOrder>,
    pad_before: Option<(Span, i64)>,
    pad_after: Option<(Span, i64)>,
    scale: Option<(Span, f64)>,
    raw: Option<syn::LitStr>,
    repr: Option<Prim>,
}

fn parse_endian(lit: &syn::LitStr) -> syn::Result<ByteOrder> {
    match lit.value().as_str() {
        "little" => Ok(ByteOrder::Little),
        "big" => Ok(ByteOrder::Big),
        _ => Err(syn::Error::new(
            lit.span(),
            "expected \"little\" or \"big\"",
        )),
    }
}

/// `crate = "::my::protocol"` (as serde's `crate = "..."`) or `crate = ::my::protocol`.
fn parse_crate_path(value: syn::parse::ParseStream<'_>) -> syn::Result<RuntimePath> {
    let path: syn::Path = if value.peek(syn::LitStr) {
        value.parse::<syn::LitStr>()?.parse()?
    } else {
        value.parse()?
    };
    Ok(RuntimePath(quote!(#path)))
}

fn parse_prim_lit(lit: &syn::LitStr) -> syn::Result<Prim> {
    Prim::from_spec_name(&lit.value())
        .filter(|p| p.is_signed() || p.is_unsigned())
        .ok_or_else(|| {
            syn::Error::new(
                lit.span(),
                "expected an integer type such as \"u8\" or \"i16\"",
            )
        })
}

/// The derive takes a struct with named fields and no generic parameters: the wire layout is
/// the fields in order, and a generic field has no fixed wire type.
fn check_struct_shape(input: &DeriveInput) -> syn::Result<&syn::FieldsNamed> {
    let Data::Struct(data) = &input.data else {
        return Err(syn::Error::new(
            input.ident.span(),
            "#[derive(Payload)] supports structs only",
        ));
    };
    if !input.generics.params.is_empty() {
        return Err(syn::Error::new(
            input.generics.span(),
            "#[derive(Payload)] does not support generic structs",
        ));
    }
    let Fields::Named(named) = &data.fields else {
        return Err(syn::Error::new(
            input.ident.span(),
            "#[derive(Payload)] needs named fields",
        ));
    };
    Ok(named)
}

/// The struct's `#[payload(...)]`: its byte order (checked by the spec rules) and where the
/// runtime is.
fn parse_struct_attrs(
    input: &DeriveInput,
    draft: &mut Draft,
) -> syn::Result<(Option<Spanned<String>>, RuntimePath)> {
    let mut byte_order = None;
    let mut paths = RuntimePath::default();
    for attr in input.attrs.iter().filter(|a| a.path().is_ident("payload")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("byte_order") {
                let lit: syn::LitStr = meta.value()?.parse()?;
                byte_order = Some(draft.at(lit.span(), lit.value()));
                Ok(())
            } else if meta.path.is_ident("crate") {
                paths = parse_crate_path(meta.value()?)?;
                Ok(())
            } else {
                Err(meta.error("unknown payload attribute; expected `byte_order` or `crate`"))
            }
        })?;
    }
    Ok((byte_order, paths))
}

/// A field's `#[payload(...)]` attributes.
fn parse_field_attrs(f: &syn::Field) -> syn::Result<FieldAttrs> {
    let mut a = FieldAttrs::default();
    for attr in f.attrs.iter().filter(|a| a.path().is_ident("payload")) {
        attr.parse_nested_meta(|meta| {
            if meta.path.is_ident("byte_order") {
                let lit: syn::LitStr = meta.value()?.parse()?;
                a.endian = Some(parse_endian(&lit)?);
            } else if meta.path.is_ident("pad_before") {
                let lit: syn::LitInt = meta.value()?.parse()?;
                a.pad_before = Some((lit.span(), lit.base10_parse()?));
            } else if meta.path.is_ident("pad_after") {
                let lit: syn::LitInt = meta.value()?.parse()?;
                a.pad_after = Some((lit.span(), lit.base10_parse()?));
            } else if meta.path.is_ident("scale") {
                let e: Expr = meta.value()?.parse()?;
                a.scale = Some((e.span(), parse_number(&e)?));
            } else if meta.path.is_ident("raw") {
                a.raw = Some(meta.value()?.parse()?);
            } else if meta.path.is_ident("repr") {
                a.repr = Some(parse_prim_lit(&meta.value()?.parse()?)?);
            } else {
                return Err(meta.error("unknown payload attribute; expected `byte_order`, `pad_before`, `pad_after`, `scale`, `raw` or `repr`"));
            }
            Ok(())
        })?;
    }
    Ok(a)
}

/// A number literal, integer or float, as an `f64` (a scale factor).
fn parse_number(e: &Expr) -> syn::Result<f64> {
    let negative = matches!(e, Expr::Unary(u) if matches!(u.op, syn::UnOp::Neg(_)));
    let lit = match e {
        Expr::Unary(u) if negative => &*u.expr,
        other => other,
    };
    let x: f64 = match lit {
        Expr::Lit(l) => match &l.lit {
            Lit::Float(x) => x.base10_parse()?,
            Lit::Int(x) => x.base10_parse::<i64>()? as f64,
            _ => return Err(syn::Error::new(e.span(), "expected a number")),
        },
        _ => return Err(syn::Error::new(e.span(), "expected a number")),
    };
    Ok(if negative { -x } else { x })
}

/// A field's element type and, for an array, its length expression.
fn array_elem(ty: &Type) -> (&Type, Option<&Expr>) {
    match ty {
        Type::Array(arr) => (&arr.elem, Some(&arr.len)),
        _ => (ty, None),
    }
}
