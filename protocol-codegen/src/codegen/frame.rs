//! Frame formats as runtime data: size consts, where each header value sits (`wire`), the
//! `FrameLayout` static the runtime engine decodes and seals with, the CRC tables, the `Header`
//! struct and the `Decoder` type. What the layout holds is decided by the lowering
//! ([`crate::layout::lower_layout`]); this module prints it. The wire rules themselves live in
//! the runtime, not here.

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use super::docs::{doc_attrs, frame_doc};
use super::header::emit_header;
use super::rt;
use crate::ir::{
    Algorithm, ByteOrder, Check, CheckNaming, CrcTable, Direction, Frame, HeaderValue, PacketKind,
    Pos, Prim, Protocol, Role, Transport,
};
use crate::layout::{self, LayoutPlan, RuleKinds, lower_layout};
use crate::resources;
use protocol_runtime::layout::{LengthRule, WordField};

fn pos(rt: &TokenStream, p: Pos) -> TokenStream {
    match p {
        Pos::Start(n) => quote!(#rt::Pos::Start(#n)),
        Pos::End(n) => quote!(#rt::Pos::End(#n)),
    }
}

fn order(rt: &TokenStream, e: ByteOrder) -> TokenStream {
    match e {
        ByteOrder::Little => quote!(#rt::ByteOrder::Little),
        ByteOrder::Big => quote!(#rt::ByteOrder::Big),
    }
}

/// A `WordField` literal for a header value.
pub fn word_field(rt: &TokenStream, v: &HeaderValue) -> TokenStream {
    word_field_lit(rt, layout::word_field(v))
}

/// A `WordField` literal.
pub(crate) fn word_field_lit(rt: &TokenStream, f: WordField) -> TokenStream {
    let WordField {
        at,
        size,
        order: ord,
        shift,
        width,
    } = f;
    let whole = match (at, ord) {
        (Pos::Start(n), ByteOrder::Little) => quote!(#rt::WordField::le(#n, #size)),
        (Pos::Start(n), ByteOrder::Big) => quote!(#rt::WordField::be(#n, #size)),
        (at, ord) => {
            let (at, ord) = (pos(rt, at), order(rt, ord));
            quote!(#rt::WordField::whole(#at, #size, #ord))
        }
    };
    if shift == 0 && u32::from(width) == u32::from(size) * 8 {
        whole
    } else {
        quote!(#whole.bits(#shift, #width))
    }
}

/// The `wire` const of header value `value` of frame `f`, as validation named it.
pub fn wire_const(f: &Frame, value: usize) -> Ident {
    format_ident!("{}", f.names.wire[value])
}

/// The `Checksum` constant of a check, as the IR's algorithm says; a CRC's table goes into
/// `statics`, under the name the IR gives it.
fn checksum_expr(rt: &TokenStream, c: &Check, statics: &mut Vec<TokenStream>) -> TokenStream {
    let checksum = algorithm_expr(rt, &c.name, &c.algorithm, &c.naming, statics);
    let Some(extra) = &c.extra else {
        return checksum;
    };
    let name = Ident::new(
        c.naming.extra_static.as_deref().unwrap_or("CHECK_EXTRA"),
        Span::call_site(),
    );
    let key = word_field_lit(rt, extra.key);
    let pair = |&(k, b): &(u32, u8)| quote!((#k, #b));
    let bytes = extra.searched_pairs().iter().map(pair);
    let direct = match extra.direct {
        0 => quote!(&[]),
        n => {
            let pairs = extra.direct_pairs().iter().map(pair);
            quote!(&#rt::direct_table::<#n>(&[#(#pairs),*]))
        }
    };
    let doc = format!(
        " The `{}` check with the byte each command folds in after the covered bytes.",
        c.name
    );
    statics.push(quote! {
        #[doc = #doc]
        static #name: #rt::Extra<'static> = #rt::Extra {
            crc: #checksum,
            key: #key,
            direct: #direct,
            bytes: &[#(#bytes),*],
        };
    });
    quote!(#rt::Checksum::Extra(&#name))
}

/// The `Checksum` constant of the algorithm of check `name`; a CRC's table goes into
/// `statics`, under the name `naming` gives it.
pub fn algorithm_expr(
    rt: &TokenStream,
    name: &str,
    algorithm: &Algorithm,
    naming: &CheckNaming,
    statics: &mut Vec<TokenStream>,
) -> TokenStream {
    macro_rules! crc {
        ($spec:expr, $w:ident, $ctor:ident, $prim:expr) => {{
            let spec = $spec;
            let params = &spec.params;
            let alg = match &naming.crc_constant {
                Some(name) => {
                    let n = Ident::new(name, Span::call_site());
                    quote!(#rt::crc::#n)
                }
                None => {
                    let lit = |v: u64| super::types::int_lit($prim, v);
                    let (poly, init, xorout, check, residue) = (
                        lit(u64::from(params.poly)),
                        lit(u64::from(params.init)),
                        lit(u64::from(params.xorout)),
                        lit(u64::from(params.check)),
                        lit(u64::from(params.residue)),
                    );
                    let (width, refin, refout) = (params.width, params.refin, params.refout);
                    quote!(#rt::crc::Algorithm { width: #width, poly: #poly, init: #init, refin: #refin, refout: #refout, xorout: #xorout, check: #check, residue: #residue })
                }
            };
            let w = quote!($w);
            let (ty, init, variant) = match spec.table {
                CrcTable::NoTable => (
                    quote!(#rt::crc::Crc<#w, #rt::crc::NoTable>),
                    quote!(#rt::crc::Crc::<#w, #rt::crc::NoTable>::new(&#alg)),
                    quote!(NoTable),
                ),
                CrcTable::Table1 => (
                    quote!(#rt::crc::Crc<#w, #rt::crc::Table<1>>),
                    quote!(#rt::crc::Crc::<#w, #rt::crc::Table<1>>::new(&#alg)),
                    quote!(Table1),
                ),
                CrcTable::Table16 => (
                    quote!(#rt::Slicing16<#w>),
                    quote!(#rt::Slicing16::<#w>::new(&#alg)),
                    quote!(Table16),
                ),
                CrcTable::ByTarget => (
                    quote!(#rt::TargetCrc<#w>),
                    quote!(#rt::TargetCrc::<#w>::new(&#alg)),
                    quote!(by_target),
                ),
            };
            let static_name = Ident::new(
                naming.table_static.as_deref().unwrap_or("CRC_TABLE"),
                Span::call_site(),
            );
            let doc = format!(" Lookup table of the `{}` check ({}).", name, naming.display);
            statics.push(quote! {
                #[doc = #doc]
                static #static_name: #ty = #init;
            });
            quote!(#rt::Checksum::$ctor(#rt::CrcImpl::#variant(&#static_name)))
        }};
    }
    match algorithm {
        Algorithm::Sum8 => quote!(#rt::Checksum::Sum8),
        Algorithm::SumMod255 => quote!(#rt::Checksum::SumMod255),
        Algorithm::Xor8 => quote!(#rt::Checksum::Xor8),
        Algorithm::Sum {
            width,
            init,
            xorout,
        } => {
            quote!(#rt::Checksum::Sum { width: #width, init: #init, xorout: #xorout })
        }
        Algorithm::Xor { init } => quote!(#rt::Checksum::Xor { init: #init }),
        Algorithm::Fletcher16 => quote!(#rt::Checksum::Fletcher16),
        Algorithm::Fletcher16Mod256 => quote!(#rt::Checksum::Fletcher16Mod256),
        Algorithm::Crc8(spec) => crc!(spec, u8, Crc8, Prim::U8),
        Algorithm::Crc16(spec) => crc!(spec, u16, Crc16, Prim::U16),
        Algorithm::Crc32(spec) => crc!(spec, u32, Crc32, Prim::U32),
        Algorithm::Crc64(spec) => crc!(spec, u64, Crc64, Prim::U64),
    }
}

/// The `LAYOUT` static of a frame format, as [`lower_layout`] plans it, with the CRC tables
/// its checks borrow.
fn emit_layout(rt: &TokenStream, f: &Frame, name: &Ident, doc: &str) -> TokenStream {
    let doc = doc_attrs(doc);
    let plan: LayoutPlan<'_> = lower_layout(f);
    let field = |value: usize| wire_const(f, value);
    let length = match (plan.length, plan.length_value) {
        (LengthRule::Field { adjust, .. }, Some(v)) => {
            let field = field(v);
            quote!(#rt::LengthRule::Field { field: wire::#field, adjust: #adjust })
        }
        (LengthRule::FieldOrBare { adjust, bare, .. }, Some(v)) => {
            let field = field(v);
            quote!(#rt::LengthRule::FieldOrBare { field: wire::#field, adjust: #adjust, bare: #bare })
        }
        (
            LengthRule::Conditional {
                adjust,
                extension,
                trailer,
                ..
            },
            Some(v),
        ) => {
            let field = field(v);
            let extension = match (extension, &f.length_extension) {
                (Some(e), Some(fe)) => {
                    let (marker, wide, len) = (e.marker, wire_const(f, fe.value), e.len);
                    quote!(#rt::Some(#rt::LengthExtension { marker: #marker, wide: wire::#wide, len: #len }))
                }
                _ => quote!(#rt::None),
            };
            let trailer = match (trailer, &f.flag_trailer) {
                (Some(t), Some(ft)) => {
                    let (flag, len) = (wire_const(f, ft.flag), t.len);
                    quote!(#rt::Some(#rt::FlagTrailer { flag: wire::#flag, len: #len }))
                }
                _ => quote!(#rt::None),
            };
            quote!(#rt::LengthRule::Conditional { field: wire::#field, adjust: #adjust, extension: #extension, trailer: #trailer })
        }
        (LengthRule::Fixed(n), _) => quote!(#rt::LengthRule::Fixed(#n)),
        // Unreachable: the plan names the header value of every length field.
        (_, None) => quote!(#rt::LengthRule::Fixed(0usize)),
    };
    let constants = plan.constants.iter().map(|(v, c)| {
        let (field, value) = (field(*v), c.value);
        quote!(#rt::Constant { field: wire::#field, value: #value })
    });
    let mut statics = Vec::new();
    let checks: Vec<TokenStream> = f
        .checks
        .iter()
        .map(|ch| {
            let cs = checksum_expr(rt, ch, &mut statics);
            let (from, to, at, ord) = (
                pos(rt, ch.from),
                pos(rt, ch.to),
                pos(rt, ch.at),
                order(rt, ch.endian),
            );
            quote!(#rt::Check { checksum: #cs, from: #from, to: #to, at: #at, order: #ord })
        })
        .collect();
    let header_checks = plan.header_checks.iter().map(|&i| &checks[i]);
    let frame_checks = plan.frame_checks.iter().map(|&i| &checks[i]);
    let markers = plan.markers.iter().map(|m| {
        let (at, bytes) = (pos(rt, m.at), m.bytes);
        quote!(#rt::Marker { at: #at, bytes: &[#(#bytes),*] })
    });
    let escape = match plan.escape {
        Some(e) => {
            let (flag, esc) = (e.flag, e.escape);
            let pairs = e.pairs.iter().map(|[r, s]| quote!([#r, #s]));
            quote!(#rt::Some(#rt::Escape { flag: #flag, escape: #esc, pairs: &[#(#pairs),*] }))
        }
        None => quote!(#rt::None),
    };
    let (sync, sync_set, header_len, min_len, max_len) = (
        plan.sync,
        plan.sync_set,
        plan.header_len,
        plan.min_len,
        plan.max_len,
    );
    quote! {
        #(#statics)*
        #doc
        pub static #name: #rt::FrameLayout<'static> = #rt::FrameLayout {
            sync: &[#(#sync),*],
            sync_set: &[#(#sync_set),*],
            header_len: #header_len,
            min_len: #min_len,
            max_len: #max_len,
            length: #length,
            constants: &[#(#constants),*],
            header_checks: &[#(#header_checks),*],
            frame_checks: &[#(#frame_checks),*],
            markers: &[#(#markers),*],
            escape: #escape,
        };
    }
}

/// Every frame format: consts, layout, decoder; then the `wire` fields of all, and the header
/// structs.
pub fn emit_frames(p: &Protocol) -> TokenStream {
    let mut out = TokenStream::new();
    for (i, f) in p.frames.iter().enumerate() {
        out.extend(emit_frame_consts(f));
        // The module's page shows the first frame's table; the others' layouts carry their own.
        let doc = if i == 0 {
            format!(
                "The `{}` frame format (its table is on the module's page).",
                f.name
            )
        } else {
            frame_doc(f)
        };
        let layout = format_ident!("{}", f.names.layout_static);
        out.extend(emit_layout(&rt(), f, &layout, &doc));
        // A CAN frame arrives whole: it has a packet type, not a stream decoder.
        if f.transport == Transport::Serial {
            out.extend(emit_decoder(f, &layout));
        }
    }
    for (d, f) in own_layouts(p) {
        out.extend(emit_frame_consts(f));
        let doc = format!(
            "The `{}` frame format as {}s lay it out, with the fields of that direction.",
            f.name, d.name
        );
        let layout = format_ident!("{}", f.names.layout_static);
        out.extend(emit_layout(&rt(), f, &layout, &doc));
        let buffer = format_ident!("{}", f.names.sizes.decoder_buffer_len);
        let (rt, max_len) = (rt(), f.max_len());
        let buffer_doc = format!(
            " Bytes of the buffer of a `PacketDecoder` of {}s ([`{}Layout`]).",
            d.name, d.rust_name
        );
        out.extend(quote! {
            #[doc = #buffer_doc]
            pub const #buffer: usize = #rt::decoder_buffer_len(#max_len);
        });
    }
    out.extend(emit_wire(p));
    let own: Vec<_> = own_layouts(p).collect();
    for (i, f) in p.frames.iter().enumerate() {
        if i == 0 {
            out.extend(emit_header(f, &own));
        } else if f.transport != Transport::Serial
            || f.message.is_some()
            || f.packet == PacketKind::Commands
        {
            out.extend(emit_header(f, &[]));
        }
    }
    out
}

/// The directions that lay the first frame format out with fields of their own, each with
/// that layout.
pub(crate) fn own_layouts(p: &Protocol) -> impl Iterator<Item = (&Direction, &Frame)> {
    p.directions
        .iter()
        .filter_map(|d| Some((d, d.frame.as_ref()?)))
}

/// The size consts of a frame format.
fn emit_frame_consts(f: &Frame) -> TokenStream {
    let n = &f.names.sizes;
    let consts = [
        (
            &n.max_frame_len,
            f.max_len(),
            "Largest `{}` frame, in bytes.",
        ),
        (
            &n.min_frame_len,
            f.min_len(),
            "Smallest `{}` frame, in bytes.",
        ),
        (
            &n.max_payload_len,
            f.payload_max,
            "Largest payload of a `{}` frame, in bytes.",
        ),
        (
            &n.min_payload_len,
            f.payload_min,
            "Smallest payload of a `{}` frame, in bytes.",
        ),
        (
            &n.header_len,
            f.header_len,
            "Bytes of a `{}` frame before its payload.",
        ),
        (
            &n.trailer_len,
            f.trailer_len,
            "Bytes of a `{}` frame after its payload.",
        ),
    ];
    consts
        .into_iter()
        .map(|(name, value, doc)| {
            let name = format_ident!("{name}");
            let doc = format!(" {}", doc.replace("{}", &f.name));
            quote!(#[doc = #doc] pub const #name: usize = #value;)
        })
        .collect()
}

/// A `compile_error!` for each pointer width (32, 16 bits) whose targets cannot hold the
/// decoder's buffer of frame format `f`, behind a `cfg` of that width, naming the spec line of
/// the payload. Decided here, where the spec is known, rather than by a `const` assertion on
/// the target: there the buffer's size would already overflow (a `[u8; N]` too large for the
/// target, a constant out of range), and rustc's own error would point at generated code
/// rather than at the spec. The span is the macro call's, the spec path in the user's code.
fn emit_buffer_refusals(f: &Frame) -> TokenStream {
    let needs = resources::needs(f);
    [32u32, 16]
        .into_iter()
        .filter(|&bits| !resources::fits_pointer_width(needs.small_buffer, bits))
        .map(|bits| {
            let width = bits.to_string();
            let message = format!(
                "frame `{}` needs a decoder buffer of {} bytes on a target with {bits}-bit \
                 pointers, where no object exceeds {} bytes (largest frame {} bytes); its \
                 payload is declared at {}: lower the payload's `max` to what the link sends",
                f.name,
                needs.small_buffer,
                (1u64 << (bits - 1)) - 1,
                needs.max_frame,
                f.payload_origin,
            );
            quote! {
                #[cfg(target_pointer_width = #width)]
                ::core::compile_error!(#message);
            }
        })
        .collect()
}

/// The layout type, buffer size, decoder type and constructor of a serial frame format.
fn emit_decoder(f: &Frame, layout: &Ident) -> TokenStream {
    let rt = rt();
    let fname = &f.name;
    let max_len = f.max_len();
    let buffer_name = format_ident!("{}", f.names.sizes.decoder_buffer_len);
    let layout_type = format_ident!("{}", f.names.layout);
    let decoder = format_ident!("{}", f.names.decoder);
    let decoder_fn = format_ident!("{}", f.names.decoder_fn);
    let buffer_doc = format!(
        " Bytes of the buffer of a [`{decoder}`]: a pending frame, the chunks of input staged \
         behind it, and room for a checksum window; at least 2 KiB on hosts \
         (`decoder_buffer_len` of the runtime)."
    );
    let layout_type_doc = format!(
        " [`{layout}`] as a type: the engine reads the layout as a compile-time constant and \
         compiles to code for `{fname}` frames alone."
    );
    let decoder_doc = format!(
        " A streaming decoder of `{fname}` frames: a fixed buffer of `{buffer_name}` bytes, no \
         heap. RAM: {}",
        super::docs::decoder_ram(f)
    );
    let new_doc = format!(" A new decoder of `{fname}` frames.");
    let refusals = emit_buffer_refusals(f);
    let kinds = emit_rule_kinds(RuleKinds::of_link([f]));
    quote! {
        #refusals
        #[doc = #layout_type_doc]
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash)]
        pub struct #layout_type;
        impl #rt::LayoutRef for #layout_type {
            #kinds
            #[inline(always)]
            fn layout(&self) -> &#rt::FrameLayout<'_> {
                &#layout
            }
        }
        #[doc = #buffer_doc]
        pub const #buffer_name: usize = #rt::decoder_buffer_len(#max_len);
        #[doc = #decoder_doc]
        pub type #decoder = #rt::StreamDecoder<#layout_type, #buffer_name>;
        #[doc = #new_doc]
        pub const fn #decoder_fn() -> #decoder {
            #rt::StreamDecoder::new(#layout_type)
        }
    }
}

/// The rule kinds of a `LayoutRef` implementation, as the lowering found them: the engine
/// links no path of a kind that is `false`.
pub(crate) fn emit_rule_kinds(kinds: RuleKinds) -> TokenStream {
    let RuleKinds {
        escaped,
        header_decided,
        several_formats,
        crc_checked,
    } = kinds;
    quote! {
        const ESCAPED: bool = #escaped;
        const HEADER_DECIDED: bool = #header_decided;
        const SEVERAL_FORMATS: bool = #several_formats;
        const CRC_CHECKED: bool = #crc_checked;
    }
}

/// The `wire` module: where each header value of every frame format sits.
fn emit_wire(p: &Protocol) -> TokenStream {
    let rt = &rt();
    let own = own_layouts(p).map(|(d, f)| (f, format!(" {}", d.name)));
    let frames = p.frames.iter().map(|f| (f, String::new())).chain(own);
    let items = frames.flat_map(|(f, what)| {
        f.values.iter().enumerate().map(move |(i, v)| {
            let name = wire_const(f, i);
            let lit = word_field(rt, v);
            let doc = format!(" Where `{}` sits in a `{}`{what} frame.", v.name, f.name);
            quote!(#[doc = #doc] pub const #name: #rt::WordField = #lit;)
        })
    });
    let items: Vec<TokenStream> = items.collect();
    quote! {
        /// Where each header value sits in a frame (for reading raw frames).
        pub mod wire {
            use super::__rt;
            #(#items)*
        }
    }
}

/// The user-set header values of a frame, with their indices in [`Frame::values`].
pub fn user_values(f: &Frame) -> impl Iterator<Item = (usize, &HeaderValue)> {
    f.values
        .iter()
        .enumerate()
        .filter(|(_, v)| matches!(v.role, Role::User { .. }))
}
