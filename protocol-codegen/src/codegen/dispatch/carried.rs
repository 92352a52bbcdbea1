//! Packets carried inside a payload (`carries`): for each struct with a carrying `bytes`
//! field, a method per message enum that reads the bytes as the message of the command the
//! key field names (`<field>_request`, or `<field>_message` without directions), and one
//! that writes a message into them, setting the key and the size field
//! (`set_<field>_request`). The struct keeps the bytes, so its size stays finite without a
//! heap, and a carried packet that carries another is read one level at a time.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::codegen::ident;
use crate::ir::{Carried, FieldKind, Protocol, Struct, ValueType};

/// The accessors of every struct that carries a packet.
pub(super) fn emit_carried(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let enums = message_enums(p);
    p.structs
        .iter()
        .filter(|s| !s.carries.is_empty())
        .map(|s| {
            let name = ident(&s.name);
            let methods = s
                .carries
                .iter()
                .flat_map(|c| enums.iter().map(move |(e, suffix)| (c, e, suffix)))
                .map(|(c, e, suffix)| emit_accessors(s, c, e, suffix, rt));
            quote!(impl #name { #(#methods)* })
        })
        .collect()
}

/// The message enums a carried packet can be read as, with the suffix of their accessors:
/// one per direction that has one (an empty direction carries no payload, so no packet), or
/// `Message`.
fn message_enums(p: &Protocol) -> Vec<(Ident, String)> {
    if p.directions.is_empty() {
        return vec![(format_ident!("Message"), "message".to_string())];
    }
    p.directions
        .iter()
        .filter(|d| d.message.is_none() && !d.empty)
        .map(|d| (format_ident!("{}", d.rust_name), d.name.clone()))
        .collect()
}

/// The bits of an unsigned integer field of `s` (its wire width).
fn field_bits(s: &Struct, name: &str) -> u32 {
    s.fields
        .iter()
        .find(|f| f.name == name)
        .and_then(|f| match &f.kind {
            FieldKind::Value {
                ty: ValueType::Scalar { scalar, .. },
                ..
            } => Some(scalar.prim.bits()),
            _ => None,
        })
        .unwrap_or(64)
}

/// The reading and the writing accessor of carried packet `c` of `s` as enum `e`.
fn emit_accessors(
    s: &Struct,
    c: &Carried,
    e: &Ident,
    suffix: &str,
    rt: &TokenStream,
) -> TokenStream {
    let field = &s.fields[c.field];
    let key = &s.fields[c.key];
    let (f, k) = (ident(&field.name), ident(&key.name));
    let place = format!("{}.{}", s.name, field.name);
    let read = format_ident!("{}_{}", field.name, suffix);
    let set = format_ident!("set_{}_{}", field.name, suffix);
    let key_bits = field_bits(s, &key.name);
    let size = match &field.kind {
        FieldKind::Bytes {
            size_from: Some(n), ..
        } => {
            let (id, bits) = (ident(n), field_bits(s, n));
            quote!(self.#id = #rt::carried_key(self.#f.len() as u64, #bits)?;)
        }
        _ => quote!(),
    };
    let read_doc = format!(
        " `{}` read as the {suffix} of the command whose id `{}` holds: the packet this one carries.",
        field.name, key.name
    );
    let set_doc = format!(
        " Writes `message` into `{}` and its command's id into `{}` (the size too): the packet this one carries.",
        field.name, key.name
    );
    quote! {
        #[doc = #read_doc]
        ///
        /// # Errors
        /// `UnknownCommand` when the key names no command, and the errors of reading the
        /// command's payload from the bytes (`PayloadLength`; a field's error names that
        /// field, or this one).
        pub fn #read(&self) -> #rt::DecodeResult<#e> {
            #rt::read_field(#place, || {
                let command = #rt::carried_command(self.#k, Command::from_id)?;
                #e::read_payload(command, self.#f.as_slice())
            })
        }
        #[doc = #set_doc]
        ///
        /// # Errors
        /// `ValueOutOfRange`, naming this field, when the command's id does not fit the key
        /// field or the payload does not fit the bytes; the errors of writing the payload.
        pub fn #set(&mut self, message: &#e) -> #rt::EncodeResult {
            #rt::write_field(#place, || {
                self.#k = #rt::carried_key(message.command().id(), #key_bits)?;
                self.#f = #rt::seal_carried(message)?;
                #size
                #rt::Ok(())
            })
        }
    }
}
