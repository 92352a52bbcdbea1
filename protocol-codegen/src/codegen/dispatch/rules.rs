//! The `RULES` static of a frame format with a packet type: its packet rules, as
//! [`lower_rules`] plans them, printed as the runtime's `PacketRules` value that the format's
//! packet decodes and encodes through. The rules live in the runtime; this module prints them.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::codegen::frame::{wire_const, word_field_lit};
use crate::ir::{Frame, Protocol};
use crate::rules::{Field, RulesPlan, lower_rules};
use protocol_runtime::rules::DirectionTest;

/// The format's `RULES` static's name.
pub(super) fn rules_static(f: &Frame) -> Ident {
    format_ident!("{}", f.names.rules_static)
}

/// A field of the rules: its `wire` const, narrowed or widened where the rules read other bits.
pub(super) fn field(f: &Frame, k: &Field, rt: &TokenStream) -> TokenStream {
    if k.is_value_field(f) {
        let c = wire_const(f, k.value);
        quote!(wire::#c)
    } else {
        word_field_lit(rt, k.field)
    }
}

/// The `RULES` static of format `f`.
pub(super) fn emit_rules(p: &Protocol, f: &Frame, rt: &TokenStream) -> TokenStream {
    let plan: RulesPlan<'_> = lower_rules(p, f);
    let name = rules_static(f);
    let layout = format_ident!("{}", f.names.layout_static);
    let header_len = format_ident!("{}", f.names.sizes.header_len);
    let trailer_len = format_ident!("{}", f.names.sizes.trailer_len);
    let max_payload = format_ident!("{}", f.names.sizes.max_payload_len);
    let key = plan.key.iter().map(|k| field(f, k, rt));
    let ack = match plan.ack {
        Some((flag, a)) => {
            let flag = field(
                f,
                &Field {
                    value: flag,
                    field: a.flag,
                },
                rt,
            );
            let (equals, header_len, bare) = (a.equals, a.header_len, a.bare);
            quote!(#rt::Some(#rt::AckRule { flag: #flag, equals: #equals, header_len: #header_len, bare: #bare }))
        }
        None => quote!(#rt::None),
    };
    let directions = plan.directions.iter().map(|(value, t)| match *t {
        DirectionTest::InRange {
            field: w,
            first,
            last,
        } => {
            let w = field(
                f,
                &Field {
                    value: *value,
                    field: w,
                },
                rt,
            );
            quote!(#rt::DirectionTest::in_range(#w, #first, #last))
        }
        DirectionTest::Equals { field: w, value: v } => {
            let w = field(
                f,
                &Field {
                    value: *value,
                    field: w,
                },
                rt,
            );
            quote!(#rt::DirectionTest::equals(#w, #v))
        }
    });
    let stuffing = match plan.stuffing {
        Some(s) => {
            let (after, insert) = (s.after, s.insert);
            quote!(#rt::Some(#rt::Stuffing { after: &[#(#after),*], insert: #insert }))
        }
        None => quote!(#rt::None),
    };
    let truncate_zeros = plan.truncate_zeros;
    let doc = format!(
        " The packet rules of the `{}` frame format: what lies between a frame [`{}`] checked \
         and its packet.",
        f.name, f.names.layout_static
    );
    quote! {
        #[doc = #doc]
        pub static #name: #rt::PacketRules<'static> = #rt::PacketRules {
            layout: &#layout,
            header_len: #header_len,
            trailer_len: #trailer_len,
            max_payload: #max_payload,
            key: &[#(#key),*],
            ack: #ack,
            directions: &[#(#directions),*],
            stuffing: #stuffing,
            truncate_zeros: #truncate_zeros,
        };
    }
}
