//! The `Command` enum: every command of the spec with its id and name, and its CAN ids.

use proc_macro2::TokenStream;
use quote::quote;

use super::{id_type, id_value};
use crate::codegen::docs::doc_attrs;
use crate::codegen::ident;
use crate::ir::{Frame, Protocol, Transport};

pub(super) fn emit_command_enum(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let id_ty = id_type(p);
    // Ids 0, 1, 2, ... of one key field are the variants' discriminants: `id` is a cast. (Other
    // ids stay a match: sparse discriminants would make every match on a command sparse too.)
    let single = f.dispatch.len() == 1
        && p.commands
            .iter()
            .enumerate()
            .all(|(i, c)| c.id == [i as u64]);
    let keys: Vec<&str> = f
        .dispatch
        .iter()
        .map(|&i| f.values[i].name.as_str())
        .collect();
    let variants = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let ids =
            c.id.iter()
                .map(|x| format!("{x:#04x}"))
                .collect::<Vec<_>>()
                .join(", ");
        let d = doc_attrs(&format!("`{}` (id {ids}). {}", c.name, c.doc));
        if single {
            let id = id_value(p, c);
            quote!(#d #v = #id)
        } else {
            quote!(#d #v)
        }
    });
    let all = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let name = &c.name;
        quote!((Self::#v, #name))
    });
    let n = p.commands.len();
    let to_id = if single {
        quote!(self as CommandId)
    } else {
        let arms = p.commands.iter().map(|c| {
            let v = ident(&c.rust_name);
            let id = id_value(p, c);
            quote!(Self::#v => #id,)
        });
        quote!(match self { #(#arms)* })
    };
    let repr = if single {
        quote!(#[repr(#id_ty)])
    } else {
        quote!()
    };
    // A match, not a lookup in `ALL`: with dense ids it compiles to a range test and no table.
    let from_id = p.commands.iter().map(|c| {
        let v = ident(&c.rust_name);
        let id = id_value(p, c);
        quote!(#id => #rt::Some(Self::#v),)
    });
    let id_doc = format!(
        " A command id: the value of the dispatch key ({}).",
        keys.join(", ")
    );
    let can = emit_can_ids(p, rt);
    quote! {
        #[doc = #id_doc]
        pub type CommandId = #id_ty;
        /// Every command of the spec, with its id (non-exhaustive: adding one is a compatible change).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
        #[non_exhaustive]
        #repr
        pub enum Command {
            #(#variants,)*
        }
        impl Command {
            /// Every command with its name in the spec, in spec order.
            pub const ALL: [(Command, &'static str); #n] = [#(#all),*];
            /// The command's id.
            pub const fn id(self) -> CommandId {
                #to_id
            }
            /// The command with this id, if any.
            pub const fn from_id(id: CommandId) -> #rt::Option<Self> {
                match id {
                    #(#from_id)*
                    _ => #rt::None,
                }
            }
            /// The command's name in the spec.
            pub const fn name(self) -> &'static str {
                // The variants' discriminants are their places in spec order (with dense ids,
                // the ids, which are the same), so the name is always found.
                match Self::ALL.split_at_checked(self as usize) {
                    #rt::Some((_, [(_, name), ..])) => name,
                    _ => "",
                }
            }
            #can
        }
        impl #rt::CommandName for Command {
            #[inline(always)]
            fn command_name(&self) -> &'static str {
                self.name()
            }
        }
    }
}

/// `Command::can_id` and `Command::from_can_id`, when a frame format is CAN.
fn emit_can_ids(p: &Protocol, rt: &TokenStream) -> TokenStream {
    if p.frames
        .iter()
        .skip(1)
        .any(|f| matches!(f.transport, Transport::Can { .. }))
    {
        let to = p.commands.iter().map(|c| {
            let v = ident(&c.rust_name);
            match c.can_id {
                Some(id) => {
                    let id = id as u32;
                    quote!(Self::#v => #rt::Some(#id),)
                }
                None => quote!(Self::#v => #rt::None,),
            }
        });
        let from = p.commands.iter().filter_map(|c| {
            let v = ident(&c.rust_name);
            let id = c.can_id? as u32;
            Some(quote!(#id => #rt::Some(Self::#v),))
        });
        quote! {
            /// The command's CAN id, if it has one.
            pub const fn can_id(self) -> #rt::Option<u32> {
                match self {
                    #(#to)*
                }
            }
            /// The command with this CAN id, if any.
            pub const fn from_can_id(id: u32) -> #rt::Option<Self> {
                match id {
                    #(#from)*
                    _ => #rt::None,
                }
            }
        }
    } else {
        quote!()
    }
}
