//! The `registers` module of a spec with `[registers]`: a `const` per register (the runtime's
//! [`Register`](protocol_runtime::registers::Register): name, address, size and a typed
//! `decode` that reads the register as a struct field of its type is read), the whole map as
//! `MAP`, and per command that selects registers the window of register bytes a frame holds
//! (`read_answer(&request, &answer)`, `write_data(&request)`, and for a request that asks each
//! listed device a run of its own `bulk_read_answer(&request, id, &answer)`). Where a register
//! lies in a window is the runtime's rule; this module prints the values it runs on.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::docs::bytes;
use super::docs::doc_attrs;
use super::payload::{prim_type, read_scalar, suffix, to_physical};
use super::{const_ident, ident};
use crate::ir::{Access, PerDevice, Protocol, Register, RegisterMap, Select, ValueType};

/// The `registers` module, or nothing for a spec without `[registers]`.
pub fn emit_registers(p: &Protocol) -> TokenStream {
    let Some(map) = &p.registers else {
        return quote!();
    };
    let rt = quote!(__rt);
    let consts = map.registers.iter().map(|r| register(&rt, r));
    let entries = map.registers.iter().map(|r| {
        let (name, address, size) = (&r.name, r.address, r.size);
        quote!((#name, #address, #size))
    });
    let n = map.registers.len();
    let windows = map.selects.iter().map(|s| windows(p, s));
    let doc = doc_attrs(&module_doc(map));
    quote! {
        #doc
        pub mod registers {
            use super::__rt;

            #(#consts)*

            /// Every register: its name, address and size in bytes, in address order.
            pub const MAP: [(&str, u32, usize); #n] = [#(#entries),*];

            #(#windows)*
        }
    }
}

fn module_doc(map: &RegisterMap) -> String {
    let mut doc = String::from(
        "The device's register map: a `const` per register, whose `read` takes the register\n\
         from a window of register bytes (a READ's answer, a WRITE's data).",
    );
    if !map.doc.is_empty() {
        doc.push_str("\n\n");
        doc.push_str(&map.doc);
    }
    doc
}

/// A register's `const`, its value type and its `decode`.
fn register(rt: &TokenStream, r: &Register) -> TokenStream {
    let ValueType::Scalar { scalar, scale } = &r.ty else {
        return quote!();
    };
    let (ty, read) = match scale {
        None => {
            let method = format_ident!("{}", suffix(*scalar));
            (prim_type(scalar.prim), quote!(r.#method()))
        }
        Some(sc) => {
            let value = to_physical(read_scalar(*scalar), scalar.prim, sc, rt);
            (prim_type(sc.physical), quote!(#rt::Ok(#value)))
        }
    };
    let name = const_ident(&r.name);
    let (text, address) = (&r.name, r.address);
    let size = u8::try_from(r.size).unwrap_or(u8::MAX);
    let doc = doc_attrs(&register_doc(r, scalar.prim.spec_name()));
    quote! {
        #doc
        pub const #name: #rt::registers::Register<#ty> = #rt::registers::Register::new(
            #text,
            #address,
            #size,
            |b| #rt::registers::value(b, |r| #read),
        );
    }
}

fn register_doc(r: &Register, ty: &str) -> String {
    let access = match r.access {
        Access::Read => "read only",
        Access::Write => "write only",
        Access::ReadWrite => "read and write",
    };
    let unit = if r.unit.is_empty() {
        String::new()
    } else {
        format!(", in {}", r.unit)
    };
    let mut doc = format!(
        "`{}`: address {}, {} (`{ty}`{unit}), {access}.",
        r.name,
        r.address,
        bytes(r.size)
    );
    if !r.doc.is_empty() {
        doc.push_str("\n\n");
        doc.push_str(&r.doc);
    }
    doc
}

/// `request.FIELD` as a `target` of `bits` bits (`u32`, `u64`): by `From` for a narrower
/// unsigned field, as it is for one of that type, else by `as` (validation checked that every
/// register's address fits the field).
fn widen(rs: &crate::ir::Struct, field: &str, target: &str, bits: usize) -> TokenStream {
    widen_of(&quote!(request), rs, field, target, bits)
}

/// `OF.FIELD` of struct `rs` as a `target` of `bits` bits, as [`widen`] reads the request's.
fn widen_of(
    of: &TokenStream,
    rs: &crate::ir::Struct,
    field: &str,
    target: &str,
    bits: usize,
) -> TokenStream {
    let name = ident(field);
    let t = format_ident!("{target}");
    let prim = rs
        .fields
        .iter()
        .find(|f| f.name == field)
        .and_then(|f| match &f.kind {
            crate::ir::FieldKind::Value {
                ty: ValueType::Scalar { scalar, .. },
                ..
            } => Some(scalar.prim),
            _ => None,
        });
    match prim {
        Some(p) if p.is_unsigned() && p.size() * 8 == bits => quote!(#of.#name),
        Some(p) if p.is_unsigned() && p.size() * 8 < bits => quote!(#t::from(#of.#name)),
        _ => quote!(#of.#name as #t),
    }
}

/// The windows of register bytes a command's frames hold.
fn windows(p: &Protocol, s: &Select) -> TokenStream {
    let (Some(c), Some(rs)) = (p.commands.get(s.command), p.structs.get(s.request)) else {
        return quote!();
    };
    let rt = quote!(__rt);
    let snake = c.name.to_ascii_lowercase();
    let request = format_ident!("{}", rs.name);
    let start = widen(rs, &s.address, "u32", 32);
    let mut out = TokenStream::new();
    if let Some(data) = &s.data {
        let f = format_ident!("{snake}_data");
        let data = ident(data);
        let doc = format!(
            "The registers a `{}` writes: its `{}`, from its `{}`.",
            c.name,
            s.data.as_deref().unwrap_or_default(),
            s.address
        );
        let doc = doc_attrs(&doc);
        out.extend(quote! {
            #doc
            pub fn #f(request: &super::#request) -> #rt::registers::Window<'_> {
                #rt::registers::Window::new(#start, request.#data.as_slice())
            }
        });
    }
    if let Some(each) = &s.each {
        out.extend(per_device_answer(p, s, each));
    } else if let Some((si, field)) = &s.answer {
        let Some(answer) = p.structs.get(*si) else {
            return out;
        };
        let f = format_ident!("{snake}_answer");
        let ty = format_ident!("{}", answer.name);
        let bytes = ident(field);
        let window = match &s.length {
            Some(l) => {
                let asked = widen(rs, l, "u64", 64);
                quote!(#rt::registers::Window::asked(#start, #asked, answer.#bytes.as_slice()))
            }
            None => quote!(#rt::registers::Window::new(#start, answer.#bytes.as_slice())),
        };
        let doc = format!(
            "The registers the answer to a `{}` carries: its `{field}`, from the request's `{}`{}.",
            c.name,
            s.address,
            s.length
                .as_ref()
                .map(|l| format!(", as many bytes as its `{l}` asked"))
                .unwrap_or_default()
        );
        let doc = doc_attrs(&doc);
        out.extend(quote! {
            #doc
            pub fn #f<'a>(request: &super::#request, answer: &'a super::#ty) -> #rt::registers::Window<'a> {
                #window
            }
        });
    }
    out
}

/// The window the answer of one listed device carries, for a request that asks each device a
/// run of its own (a `BULK_READ`): the run of the first element whose id is the answer's
/// sender's, `None` when the request does not list it.
fn per_device_answer(p: &Protocol, s: &Select, each: &PerDevice) -> TokenStream {
    let (Some(c), Some(rs), Some(es), Some((si, field))) = (
        p.commands.get(s.command),
        p.structs.get(s.request),
        p.structs.get(each.element),
        s.answer.as_ref(),
    ) else {
        return quote!();
    };
    let Some(answer) = p.structs.get(*si) else {
        return quote!();
    };
    let rt = quote!(__rt);
    let f = format_ident!("{}_answer", c.name.to_ascii_lowercase());
    let (request, ty) = (
        format_ident!("{}", rs.name),
        format_ident!("{}", answer.name),
    );
    let (group, id, bytes) = (ident(&each.group), ident(&each.id), ident(field));
    let e = quote!(e);
    let start = widen_of(&e, es, &s.address, "u32", 32);
    let window = match &s.length {
        Some(l) => {
            let asked = widen_of(&e, es, l, "u64", 64);
            quote!(#rt::registers::Window::asked(#start, #asked, answer.#bytes.as_slice()))
        }
        None => quote!(#rt::registers::Window::new(#start, answer.#bytes.as_slice())),
    };
    let doc = format!(
        "The registers the answer of device `id` to a `{}` carries: its `{field}`, from the `{}` \
         of the request's first `{}` element whose `{}` is `id`{}; `None` when the request \
         does not list `id`.",
        c.name,
        s.address,
        each.group,
        each.id,
        s.length
            .as_ref()
            .map(|l| format!(", as many bytes as its `{l}` asked"))
            .unwrap_or_default()
    );
    let doc = doc_attrs(&doc);
    quote! {
        #doc
        pub fn #f<'a>(
            request: &super::#request,
            id: u8,
            answer: &'a super::#ty,
        ) -> #rt::Option<#rt::registers::Window<'a>> {
            let e = request.#group.as_slice().iter().find(|e| e.#id == id)?;
            #rt::Some(#window)
        }
    }
}
