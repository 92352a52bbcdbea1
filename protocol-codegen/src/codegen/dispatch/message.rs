//! The message enums: one variant per command holding its payload (`Message`, or one enum per
//! direction and a `Message` over them), opened in one place by `visit_payload` (their
//! `MessagePayload` impl).

use proc_macro2::TokenStream;
use quote::{format_ident, quote};

use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::ir::Protocol;

pub(super) fn emit_message_enum(
    p: &Protocol,
    di: usize,
    name: &proc_macro2::Ident,
    doc: &str,
    rt: &TokenStream,
) -> TokenStream {
    // Acknowledgements (a frame format with `ack`): a variant without a command.
    let ack_max = p
        .frames
        .first()
        .and_then(|f| f.ack.map(|(_, hl)| f.max_len() - hl - f.trailer_len));
    // Trailing-zero truncation: a short payload is zero-filled to its struct's size before it
    // is read, in a buffer of that size (the largest payload's for a struct of the user's
    // crate, whose size is not known here), which only a short payload costs.
    let truncating = p.frames.first().filter(|f| f.truncate_zeros);
    let fill = match truncating {
        Some(_) => quote!(),
        None => quote!(use #rt::read_payload as read;),
    };
    let read_fn = |si: usize| match truncating {
        Some(f) => {
            let s = &p.structs[si];
            let size = if s.foreign { f.payload_max } else { s.size };
            quote!(#rt::read_filled::<_, #size>(b))
        }
        None => quote!(read(b)),
    };
    // A direction that carries a struct in place of a command makes the command optional.
    let none = command_none(p);
    let optional_command = none.is_some();
    let doc = doc_attrs(doc);
    let mut variants = Vec::new();
    let mut visit_arms = Vec::new();
    let mut read_arms = Vec::new();
    let mut any_empty = false;
    for c in &p.commands {
        let v = ident(&c.rust_name);
        let command = if optional_command {
            quote!(#rt::Some(C::#v))
        } else {
            quote!(C::#v)
        };
        match c.payloads.get(di).copied().flatten() {
            Some(si) => {
                let s = ident(&p.structs[si].name);
                let d = doc_attrs(&format!(
                    "`{}`, carrying a `{}`. {}",
                    c.name, p.structs[si].name, c.doc
                ));
                variants.push(quote!(#d #v(#s)));
                visit_arms.push(quote!(Self::#v(p) => v.visit(#command, p),));
                let read = read_fn(si);
                read_arms.push(quote!(C::#v => Self::#v(#read?),));
            }
            None => {
                let d = doc_attrs(&format!("`{}`, with an empty payload. {}", c.name, c.doc));
                variants.push(quote!(#d #v));
                visit_arms.push(quote!(Self::#v => v.visit(#command, &()),));
                read_arms.push(quote!(C::#v if b.is_empty() => Self::#v,));
                any_empty = true;
            }
        }
    }
    if let Some(max) = ack_max {
        variants.push(quote! {
            #[doc = " An acknowledgement: no command, the acknowledgement data."]
            Ack(#rt::Bytes<#max>)
        });
        visit_arms.push(quote!(Self::Ack(data) => v.visit(#rt::None, data),));
    }
    let (visit_impl, command_fn) = emit_visit_and_command(
        name,
        rt,
        none,
        quote!(use Command as C; match self { #(#visit_arms)* }),
    );
    // The commands without payload match only an empty one; any other bytes fall through.
    if any_empty {
        read_arms.push(quote!(_ => return #rt::Err(#rt::expected_empty(b)),));
    }
    quote! {
        #doc
        #[derive(Debug, Clone, Copy, PartialEq)]
        #[non_exhaustive]
        pub enum #name {
            #(#variants,)*
        }
        #visit_impl
        impl #name {
            #command_fn
            /// Read the payload of `command` from exactly `b`.
            ///
            /// # Errors
            /// `DecodeError::PayloadLength` if the payload's size is not the command's, or any
            /// error of the payload's fields (an unknown enum value, ...).
            pub fn read_payload(command: Command, b: &[u8]) -> #rt::DecodeResult<Self> {
                #fill
                use Command as C;
                // `?` in each arm and one `Ok`: every error leaves by one path, which names
                // the command.
                let message = #rt::read_command(command.name(), || #rt::Ok(match command {
                    #(#read_arms)*
                }))?;
                #rt::Ok(message)
            }
        }
    }
}

/// `impl MessagePayload` (its `visit_payload`, whose body, `visit`, opens the message once;
/// the runtime's trait measures and writes the payload through it) and the inherent `command`.
fn emit_visit_and_command(
    name: &proc_macro2::Ident,
    rt: &TokenStream,
    none: Option<&str>,
    visit: TokenStream,
) -> (TokenStream, TokenStream) {
    let (command_ty, command_doc) = if let Some(none) = none {
        (
            quote!(#rt::Option<Command>),
            format!(" The command of this message (`None` for {none})."),
        )
    } else {
        (quote!(Command), " The command of this message.".to_string())
    };
    let visit_impl = quote! {
        impl #rt::MessagePayload for #name {
            type Command = #command_ty;
            #[inline(always)]
            fn visit_payload<V: #rt::PayloadVisitor<#command_ty>>(&self, v: V) -> V::Output {
                #visit
            }
        }
    };
    let command = quote! {
        #[doc = #command_doc]
        #[inline(always)]
        pub fn command(&self) -> #command_ty {
            self.visit_payload(#rt::CommandOf)
        }
    };
    (visit_impl, command)
}

/// What a message without a command is, when a spec has such messages (its `command()` is
/// then an `Option`).
pub(super) fn command_none(p: &Protocol) -> Option<&'static str> {
    if p.frames.first().is_some_and(|f| f.ack.is_some()) {
        Some("an acknowledgement")
    } else if p.directions.iter().any(|d| d.message.is_some()) {
        Some("a message that carries its direction's struct in place of a command")
    } else {
        None
    }
}

pub(super) fn emit_direction_message(p: &Protocol, rt: &TokenStream) -> TokenStream {
    let variants = p.directions.iter().map(|d| {
        let v = format_ident!("{}", d.rust_name);
        match d.message {
            Some((si, _)) => {
                let s = ident(&p.structs[si].name);
                let doc = doc_attrs(&format!(
                    "A {}, carrying a `{}` (no command). {}",
                    d.name, p.structs[si].name, d.doc
                ));
                quote!(#doc #v(#s))
            }
            None if d.empty => {
                let doc = doc_attrs(&format!(
                    "A frame of direction `{}`: the command alone, no payload whatever the command. {}",
                    d.name, d.doc
                ));
                quote!(#doc #v(Command))
            }
            None => {
                let doc = doc_attrs(&format!("A {}. {}", d.name, d.doc));
                quote!(#doc #v(#v))
            }
        }
    });
    let arms = p.directions.iter().map(|d| {
        let v = format_ident!("{}", d.rust_name);
        match d.message {
            Some(_) => quote!(Self::#v(m) => v.visit(#rt::None, m),),
            None if d.empty => quote!(Self::#v(c) => v.visit(*c, &()),),
            None => quote!(Self::#v(m) => m.visit_payload(v),),
        }
    });
    let (visit_impl, command_fn) = emit_visit_and_command(
        &format_ident!("Message"),
        rt,
        command_none(p),
        quote!(match self { #(#arms)* }),
    );
    quote! {
        /// A decoded message: its direction, then the command and payload.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum Message {
            #(#variants,)*
        }
        #visit_impl
        impl Message {
            #command_fn
        }
    }
}
