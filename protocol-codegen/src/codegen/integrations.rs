//! The derives a user chooses in the macro call (`protocol!("spec.toml", derive(serde,
//! defmt))`) on the generated types: `serde`'s `Serialize` and `Deserialize`, and `defmt`'s
//! `Format`.
//!
//! The choice is the user's crate's, made in its macro call, not a `cfg(feature = ...)` in the
//! expansion (which would test the features of the user's crate, not ours). The traits are
//! named through the runtime path (`<runtime>::__private::serde`, `...::defmt`), which
//! re-exports the crates under the facade's `serde` and `defmt` features, with `serde(crate =
//! ...)` and `defmt(crate = ...)` pointing the derives there: the user's crate needs no
//! `serde` or `defmt` dependency of its own.
//!
//! The JSON shape is that of the run-time codec (`protocol decode --format json`): structs and
//! headers derive `serde` (arrays longer than 32 elements through the runtime's `array`
//! helper); spec enums, `Command`, the message enums and the packets have impls that call the
//! runtime's helpers (`serde_support`), so that an enum is its variant's name in the spec (a
//! number when unknown), a message is its payload and a packet is the map of `command`,
//! `header` and `payload` (after `direction` when the decoder is given it; a link's
//! `AnyPacket` is its format's packet after `format`). This module runs after the other
//! printers, on their items: it adds
//! attributes to the structs and enums it finds and appends the impls, so that the printers
//! stay as they are when no derive is chosen.

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use super::dispatch::direction_test;
use super::payload::prim_type;
use super::{ident, rt};
use crate::ir::{Frame, PacketKind, Protocol};

/// The derives chosen in the macro call.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Derives {
    /// `serde::Serialize` and `serde::Deserialize`.
    pub serde: bool,
    /// `defmt::Format`.
    pub defmt: bool,
}

impl Derives {
    /// Whether any derive is chosen.
    pub fn any(self) -> bool {
        self.serde || self.defmt
    }
}

/// The module's items with the chosen derives: attributes on its structs and enums, and the
/// impls that are not derived appended.
pub fn apply(items: TokenStream, p: &Protocol, d: Derives) -> TokenStream {
    if !d.any() {
        return items;
    }
    let Ok(mut file) = syn::parse2::<syn::File>(items.clone()) else {
        return items;
    };
    let rt = rt();
    // Serde derives on the payload structs and the headers; defmt also on the packets (whose
    // serde impls are written out below). Other structs (the `Layout` markers) get neither.
    let mut data: Vec<&str> = p.structs.iter().map(|s| s.name.as_str()).collect();
    data.extend(p.frames.iter().map(|f| f.names.header.as_str()));
    let packets: Vec<&str> = p
        .frames
        .iter()
        .filter(|f| f.packet != PacketKind::None)
        .map(|f| f.names.packet.as_str())
        .collect();
    let serde_crate = path_text(quote!(#rt::serde));
    let header = p.frames.first().map_or("", |f| f.names.header.as_str());
    let directed = directed_values(p);
    for item in &mut file.items {
        match item {
            syn::Item::Struct(s) => {
                let name = s.ident.to_string();
                let is_data = data.contains(&name.as_str());
                if d.defmt && (is_data || packets.contains(&name.as_str())) {
                    s.attrs.extend(defmt_attrs(&rt));
                }
                if d.serde && is_data {
                    s.attrs.push(syn::parse_quote!(
                        #[derive(#rt::serde::Serialize, #rt::serde::Deserialize)]
                    ));
                    s.attrs
                        .push(syn::parse_quote!(#[serde(crate = #serde_crate)]));
                    // A header's flag trailer (`Option<[u8; N]>`): bytes, as the codec's hex.
                    let trailer = p
                        .frames
                        .iter()
                        .filter(|f| f.names.header == name)
                        .find_map(|f| f.flag_trailer.as_ref())
                        .map(|t| t.name.as_str());
                    for field in &mut s.fields {
                        let is_trailer = field
                            .ident
                            .as_ref()
                            .is_some_and(|i| Some(i.to_string().as_str()) == trailer);
                        // A value of one direction's frames: absent from the others' headers,
                        // as the codec's JSON has it.
                        if name == header
                            && field
                                .ident
                                .as_ref()
                                .is_some_and(|i| directed.contains(&i.to_string()))
                        {
                            field.attrs.push(syn::parse_quote!(
                                #[serde(default, skip_serializing_if = "Option::is_none")]
                            ));
                        }
                        let helper = if is_trailer {
                            Some(quote!(trailer))
                        } else {
                            serde_with(&field.ty)
                        };
                        if let Some(helper) = helper {
                            let with = path_text(quote!(#rt::serde_support::#helper));
                            field.attrs.push(syn::parse_quote!(#[serde(with = #with)]));
                        }
                    }
                }
            }
            syn::Item::Enum(e) if d.defmt => e.attrs.extend(defmt_attrs(&rt)),
            _ => {}
        }
    }
    let mut out = quote!(#file);
    if d.serde {
        out.extend(quote!(#rt::require_serde!();));
        out.extend(serde_impls(p, &rt));
    }
    if d.defmt {
        out.extend(quote!(#rt::require_defmt!();));
    }
    out
}

/// A path as the string serde's attributes take (`"a::b"`).
fn path_text(path: TokenStream) -> String {
    path.to_string().replace(' ', "")
}

fn defmt_attrs(rt: &TokenStream) -> [syn::Attribute; 2] {
    [
        syn::parse_quote!(#[derive(#rt::defmt::Format)]),
        syn::parse_quote!(#[defmt(crate = #rt::defmt)]),
    ]
}

/// The runtime's serde helper of a field's type, if its type needs one: floats (non-finite
/// ones as the codec's strings: `float`, `float::floats`, `float::optional`) and arrays longer
/// than serde's own impls take (32 elements: `array`).
fn serde_with(ty: &syn::Type) -> Option<TokenStream> {
    match ty {
        _ if is_float(ty) => Some(quote!(float)),
        syn::Type::Array(a) if is_float(&a.elem) => Some(quote!(float::floats)),
        syn::Type::Array(a) => {
            let long = match &a.len {
                syn::Expr::Lit(syn::ExprLit {
                    lit: syn::Lit::Int(n),
                    ..
                }) => n.base10_parse::<usize>().is_ok_and(|n| n > 32),
                _ => true,
            };
            long.then(|| quote!(array))
        }
        syn::Type::Path(p) => {
            let last = p.path.segments.last()?;
            let syn::PathArguments::AngleBracketed(args) = &last.arguments else {
                return None;
            };
            match args.args.first() {
                Some(syn::GenericArgument::Type(inner))
                    if last.ident == "Option" && is_float(inner) =>
                {
                    Some(quote!(float::optional))
                }
                _ => None,
            }
        }
        _ => None,
    }
}

fn is_float(ty: &syn::Type) -> bool {
    matches!(ty, syn::Type::Path(p) if p.path.is_ident("f32") || p.path.is_ident("f64"))
}

/// The serde impls that are not derived: spec enums, `Command`, messages and packets.
fn serde_impls(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let mut out: TokenStream = p.enums.iter().map(|e| enum_impls(e, rt)).collect();
    let Some(first) = p.frames.first() else {
        return out;
    };
    if !first.dispatch.is_empty() {
        out.extend(command_impls(rt));
        let acks = first.ack.is_some();
        if p.directions.is_empty() {
            out.extend(message_impls(p, 0, &format_ident!("Message"), acks, rt));
        } else {
            // A direction that carries a struct in place of a command has no message enum.
            for (di, dir) in p
                .directions
                .iter()
                .enumerate()
                .filter(|(_, d)| d.message.is_none() && !d.empty)
            {
                let name = format_ident!("{}", dir.rust_name);
                out.extend(message_impls(p, di, &name, acks, rt));
            }
            out.extend(direction_message_impl(p, rt));
        }
    }
    for f in &p.frames {
        out.extend(packet_impls(p, f, rt));
    }
    out.extend(any_packet_impls(p, rt));
    out
}

/// A link's `AnyPacket`: its format's packet, with the format's name first (`format`, as the
/// run-time codec's frame objects have it).
fn any_packet_impls(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let formats: Vec<&Frame> = p.link.iter().map(|&i| &p.frames[i]).collect();
    if formats.is_empty() {
        return quote!();
    }
    let names: Vec<&str> = formats.iter().map(|f| f.name.as_str()).collect();
    let variants: Vec<_> = formats
        .iter()
        .map(|f| format_ident!("{}", f.names.pascal))
        .collect();
    // The last format takes every other index: `FORMATS` gives none beyond it.
    let reads = formats.iter().enumerate().map(|(i, f)| {
        let v = format_ident!("{}", f.names.pascal);
        let read = quote!(#rt::Ok(Self::#v(#rt::serde_support::packet_from_map(map)?)));
        if i + 1 == formats.len() {
            quote!(_ => #read,)
        } else {
            quote!(#i => #read,)
        }
    });
    quote! {
        impl #rt::serde_support::SerdeAnyPacket for AnyPacket {
            const FORMATS: &'static [&'static str] = &[#(#names),*];
            fn visit_format<'de, A: #rt::serde::de::MapAccess<'de>>(format: usize, map: A) -> #rt::Result<Self, A::Error> {
                match format {
                    #(#reads)*
                }
            }
        }
        impl #rt::serde::Serialize for AnyPacket {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                match self {
                    #(Self::#variants(p) => #rt::serde_support::serialize_packet_in(p, #rt::Some(#names), s),)*
                }
            }
        }
        impl<'de> #rt::serde::Deserialize<'de> for AnyPacket {
            fn deserialize<D: #rt::serde::Deserializer<'de>>(d: D) -> #rt::Result<Self, D::Error> {
                #rt::serde_support::deserialize_any_packet(d)
            }
        }
    }
}

/// A spec enum: its variant's name in the spec, or its number when it has none.
fn enum_impls(e: &crate::ir::Enum, rt: &TokenStream) -> TokenStream {
    let name = ident(&e.name);
    let raw = prim_type(e.prim);
    let names = e.variants.iter().map(|v| {
        let vn = ident(&v.rust_name);
        let text = &v.name;
        quote!((#text, Self::#vn))
    });
    quote! {
        impl #name {
            /// Every variant with its name in the spec.
            const SPEC_NAMES: &'static [(&'static str, Self)] = &[#(#names),*];
        }
        impl #rt::serde::Serialize for #name {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                #rt::serde_support::serialize_enum(s, Self::SPEC_NAMES, self, self.to_raw())
            }
        }
        impl<'de> #rt::serde::Deserialize<'de> for #name {
            fn deserialize<D: #rt::serde::Deserializer<'de>>(d: D) -> #rt::Result<Self, D::Error> {
                #rt::serde_support::deserialize_enum(d, Self::SPEC_NAMES, |raw: #raw| Self::from_raw(raw).ok())
            }
        }
    }
}

/// `Command`: its name in the spec.
fn command_impls(rt: &TokenStream) -> TokenStream {
    quote! {
        impl Command {
            /// The command of a name in the spec.
            fn from_spec_name(name: &str) -> #rt::Option<Self> {
                Self::ALL.into_iter().find(|(_, n)| *n == name).map(|(command, _)| command)
            }
        }
        impl #rt::serde::Serialize for Command {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                #rt::serde_support::serialize_name(s, self.name())
            }
        }
        impl<'de> #rt::serde::Deserialize<'de> for Command {
            fn deserialize<D: #rt::serde::Deserializer<'de>>(d: D) -> #rt::Result<Self, D::Error> {
                #rt::serde_support::deserialize_name(d, Self::from_spec_name)
            }
        }
    }
}

/// A message enum: it serializes as its payload (the empty map for a command without one);
/// `deserialize_payload` reads the payload of a command.
fn message_impls(
    p: &Protocol,
    di: usize,
    name: &proc_macro2::Ident,
    acks: bool,
    rt: &TokenStream,
) -> TokenStream {
    let mut ser = Vec::new();
    let mut de = Vec::new();
    for c in &p.commands {
        let v = ident(&c.rust_name);
        let pat = if acks {
            quote!(#rt::Some(Command::#v))
        } else {
            quote!(Command::#v)
        };
        if c.payloads.get(di).copied().flatten().is_some() {
            ser.push(quote!(Self::#v(payload) => #rt::serde::Serialize::serialize(payload, s),));
            de.push(quote!(#pat => Self::#v(#rt::serde::Deserialize::deserialize(d)?),));
        } else {
            ser.push(quote!(Self::#v => #rt::serde::Serialize::serialize(&#rt::serde_support::Empty, s),));
            de.push(quote!(#pat => {
                <#rt::serde_support::Empty as #rt::serde::Deserialize>::deserialize(d)?;
                Self::#v
            }));
        }
    }
    let command_ty = if acks {
        ser.push(quote!(Self::Ack(data) => #rt::serde::Serialize::serialize(data, s),));
        de.push(quote!(#rt::None => Self::Ack(#rt::serde::Deserialize::deserialize(d)?),));
        quote!(#rt::Option<Command>)
    } else {
        quote!(Command)
    };
    quote! {
        impl #rt::serde::Serialize for #name {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                match self {
                    #(#ser)*
                }
            }
        }
        impl #name {
            /// Reads the payload of `command`.
            fn deserialize_payload<'de, D: #rt::serde::Deserializer<'de>>(
                command: #command_ty,
                d: D,
            ) -> #rt::Result<Self, D::Error> {
                #rt::Ok(match command {
                    #(#de)*
                })
            }
        }
    }
}

/// The `Message` over the directions: it serializes as its direction's message.
fn direction_message_impl(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let arms = p.directions.iter().map(|d| {
        let v = format_ident!("{}", d.rust_name);
        if d.empty {
            // The command is the packet's: the payload is the empty map.
            quote!(Self::#v(_) => #rt::serde::Serialize::serialize(&#rt::serde_support::Empty, s),)
        } else {
            quote!(Self::#v(m) => #rt::serde::Serialize::serialize(m, s),)
        }
    });
    quote! {
        impl #rt::serde::Serialize for Message {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                match self {
                    #(#arms)*
                }
            }
        }
    }
}

/// The packet of a frame format: `SerdePacket`, and `Serialize` and `Deserialize` through it.
fn packet_impls(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let packet = format_ident!("{}", f.names.packet);
    let header = format_ident!("{}", f.names.header);
    let acks = p.frames.first().is_some_and(|first| first.ack.is_some());
    let body = match f.packet {
        PacketKind::None => return quote!(),
        PacketKind::Message(si) => {
            let payload = ident(&p.structs[si].name);
            quote! {
                type Message = #payload;
                type Command = ();
                fn parts(&self) -> (#rt::Option<&'static str>, &#header, &#payload) {
                    (#rt::None, &self.header, &self.payload)
                }
                fn command_named(_: &str) -> #rt::Option<()> {
                    #rt::None
                }
                fn payload<'de, D: #rt::serde::Deserializer<'de>>(
                    _: #rt::Option<()>,
                    _: &#header,
                    d: D,
                ) -> #rt::Result<#payload, D::Error> {
                    #rt::serde::Deserialize::deserialize(d)
                }
                fn from_parts(header: #header, payload: #payload) -> Self {
                    Self { header, payload }
                }
            }
        }
        PacketKind::Command if p.directions_given() => given_packet_body(p, &header, rt),
        PacketKind::Command | PacketKind::Commands | PacketKind::Can => {
            let (name, command) = if acks {
                (
                    quote!(self.message.command().map(Command::name)),
                    quote!(command),
                )
            } else {
                (
                    quote!(#rt::Some(self.message.command().name())),
                    quote!(command.ok_or_else(|| #rt::serde_support::payload_error::<D::Error>("a payload without its command"))?),
                )
            };
            let message = packet_message(p, f, rt);
            quote! {
                type Message = Message;
                type Command = Command;
                fn parts(&self) -> (#rt::Option<&'static str>, &#header, &Message) {
                    (#name, &self.header, &self.message)
                }
                fn command_named(name: &str) -> #rt::Option<Command> {
                    Command::from_spec_name(name)
                }
                fn payload<'de, D: #rt::serde::Deserializer<'de>>(
                    command: #rt::Option<Command>,
                    header: &#header,
                    d: D,
                ) -> #rt::Result<Message, D::Error> {
                    let command = #command;
                    #message
                }
                fn from_parts(header: #header, message: Message) -> Self {
                    Self { header, message }
                }
            }
        }
    };
    quote! {
        impl #rt::serde_support::SerdePacket for #packet {
            type Header = #header;
            #body
        }
        impl #rt::serde::Serialize for #packet {
            fn serialize<S: #rt::serde::Serializer>(&self, s: S) -> #rt::Result<S::Ok, S::Error> {
                #rt::serde_support::serialize_packet(self, s)
            }
        }
        impl<'de> #rt::serde::Deserialize<'de> for #packet {
            fn deserialize<D: #rt::serde::Deserializer<'de>>(d: D) -> #rt::Result<Self, D::Error> {
                #rt::serde_support::deserialize_packet(d)
            }
        }
    }
}

/// The `SerdePacket` items of the packet of a spec whose directions the decoder is given: the
/// direction is a key of the packet's map (`direction`, as the run-time codec writes it), which
/// says how to read the payload.
fn given_packet_body(p: &Protocol, header: &proc_macro2::Ident, rt: &TokenStream) -> TokenStream {
    let name = if p.directions.iter().any(|d| d.message.is_some()) {
        quote!(self.message.command().map(Command::name))
    } else {
        quote!(#rt::Some(self.message.command().name()))
    };
    let names: Vec<&str> = p.directions.iter().map(|d| d.name.as_str()).collect();
    let variants: Vec<_> = p
        .directions
        .iter()
        .map(|d| format_ident!("{}", d.rust_name))
        .collect();
    let indices: Vec<usize> = (0..p.directions.len()).collect();
    let reads = p.directions.iter().map(|d| {
        let v = format_ident!("{}", d.rust_name);
        match d.message {
            Some(_) => quote!(Message::#v(#rt::serde::Deserialize::deserialize(d)?)),
            None => quote! {{
                let command = command.ok_or_else(|| #rt::serde_support::payload_error::<D::Error>("a payload without its command"))?;
                Message::#v(#v::deserialize_payload(command, d)?)
            }},
        }
    });
    quote! {
        type Message = Message;
        type Command = Command;
        const GIVEN_DIRECTIONS: &'static [&'static str] = &[#(#names),*];
        fn parts(&self) -> (#rt::Option<&'static str>, &#header, &Message) {
            (#name, &self.header, &self.message)
        }
        fn direction(&self) -> #rt::Option<&'static str> {
            #rt::Some(match &self.message {
                #(Message::#variants(_) => #names,)*
            })
        }
        fn command_named(name: &str) -> #rt::Option<Command> {
            Command::from_spec_name(name)
        }
        fn payload<'de, D: #rt::serde::Deserializer<'de>>(
            command: #rt::Option<Command>,
            header: &#header,
            d: D,
        ) -> #rt::Result<Message, D::Error> {
            Self::payload_in(command, header, #rt::None, d)
        }
        fn payload_in<'de, D: #rt::serde::Deserializer<'de>>(
            command: #rt::Option<Command>,
            _: &#header,
            direction: #rt::Option<usize>,
            d: D,
        ) -> #rt::Result<Message, D::Error> {
            #rt::Ok(match direction {
                #(#rt::Some(#indices) => #reads,)*
                _ => return #rt::Err(#rt::serde_support::payload_error("a payload without its direction: the decoder is given it")),
            })
        }
        fn from_parts(header: #header, message: Message) -> Self {
            Self { header, message }
        }
    }
}

/// The message of a packet's payload: by the header's direction when the spec has directions.
fn packet_message(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    if p.directions.is_empty() {
        return quote!(let _ = header; Message::deserialize_payload(command, d));
    }
    let reads: Vec<_> = p
        .directions
        .iter()
        .map(|d| {
            let v = format_ident!("{}", d.rust_name);
            if d.empty {
                quote! {{
                    <#rt::serde_support::Empty as #rt::serde::Deserialize>::deserialize(d)?;
                    Message::#v(command)
                }}
            } else {
                quote!(Message::#v(#v::deserialize_payload(command, d)?))
            }
        })
        .collect();
    let tests: Vec<_> = p
        .directions
        .iter()
        .map(|d| direction_test(p, f, &d.rule.in_frame(f)))
        .collect();
    quote! {
        #(if #tests { #rt::Ok(#reads) } else)*
        { #rt::Err(#rt::serde_support::payload_error("the header matches no direction")) }
    }
}

/// The header values of the first frame format that only some directions' frames have (an
/// `Option` of its header).
fn directed_values(p: &Protocol) -> Vec<String> {
    let Some(first) = p.frames.first() else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for f in p.directions.iter().filter_map(|d| d.frame.as_ref()) {
        for (_, v) in super::frame::user_values(f) {
            if !first.values.iter().any(|x| x.name == v.name) && !out.contains(&v.name) {
                out.push(v.name.clone());
            }
        }
    }
    out
}
