//! Rules for bits: bitfield members (widths, names and member types), the reserved bits above
//! them, and bit-packed arrays.

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, unknown_type};
use super::super::{Ctx, text};
use super::fields::{lower_count, lower_scale};
use super::{Enums, mask};
use crate::ir::{
    BitMember, BitOrder, ByteOrder, Constant, FieldKind, Prim, Rounding, Scalar, Scale,
};
use crate::spec::model::{BitDef, FieldDef, PackedDef, SStr};

/// Where bit members stand: a header word, a payload word or a payload bit stream. Scaling,
/// units and signed members are payload values (a header member is a length, a constant or a
/// key the frame rules read as unsigned).
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum MemberSite {
    /// A header field's word.
    Header,
    /// A payload field's word, of this many bits.
    Word,
    /// A payload bit stream: each member 1 to 64 bits, with no limit on their sum.
    Stream,
}

/// Rule: bit members have snake_case names, unique, at least one bit each and at most
/// `limit`; a member's type is `bool` (one bit), an integer wide enough (signed only in a
/// payload: two's complement of the member's width), or an enum whose values fit the member;
/// in a payload a number member may be scaled. `extra` rejects keys the context forbids. The
/// members' `shift` is the running sum of the widths before them, and their sum is at most
/// `limit` in a word.
pub(crate) fn lower_bits(
    ctx: &mut Ctx<'_>,
    bits: &[Spanned<BitDef>],
    limit: u32,
    site: MemberSite,
    enums: &Enums,
    extra: &dyn Fn(&BitDef) -> Option<&'static str>,
) -> Vec<BitMember> {
    let mut shift = 0u32;
    let mut members: Vec<BitMember> = Vec::new();
    for b in bits {
        let m = b.get_ref();
        if let Some(msg) = extra(m) {
            ctx.error(b.span(), msg, "remove the key");
        }
        check_snake_name(ctx, &m.name, "bit member");
        let width = *m.bits.get_ref();
        if width <= 0 || width > i64::from(limit) {
            ctx.error(
                m.bits.span(),
                format!("bit member `{}` has {width} bits", m.name.get_ref()),
                format!("a member has 1 to {limit} bits"),
            );
            continue;
        }
        let width = width as u32;
        if members.iter().any(|x| &x.name == m.name.get_ref()) {
            ctx.error(
                m.name.span(),
                format!("bit member `{}` appears twice", m.name.get_ref()),
                "rename one of them",
            );
        }
        let (prim, enum_index) = member_type(ctx, m, width, site, enums);
        let scale = match site {
            MemberSite::Header => {
                reject_header_scale(ctx, m);
                None
            }
            MemberSite::Word | MemberSite::Stream => {
                lower_member_scale(ctx, b, width, prim, enum_index)
            }
        };
        members.push(BitMember {
            name: m.name.get_ref().clone(),
            doc: text(&m.doc),
            shift,
            width,
            prim,
            enum_index,
            scale,
            unit: text(&m.unit),
        });
        shift = shift.saturating_add(width);
    }
    if site != MemberSite::Stream && shift > limit {
        let span = bits.last().map(Spanned::span).unwrap_or_default();
        ctx.error(
            span,
            format!("the bit members add up to {shift} bits, but the word has {limit}"),
            "shrink the members or use a wider word type",
        );
    }
    members
}

/// Rule: a bit member's type is `bool` for one bit, an unsigned integer at least as wide, a
/// signed one (in a payload only) at least as wide, or an enum whose values fit. Gives the
/// member's Rust type and enum.
fn member_type(
    ctx: &mut Ctx<'_>,
    m: &BitDef,
    width: u32,
    site: MemberSite,
    enums: &Enums,
) -> (Prim, Option<usize>) {
    let Some(t) = &m.ty else {
        return (
            if width == 1 {
                Prim::Bool
            } else {
                smallest_uint(width)
            },
            None,
        );
    };
    let wide = |p: Prim| (p.size() * 8) as u32 >= width;
    match parse_prim(t.get_ref(), ByteOrder::Little) {
        Some(s) if s.prim == Prim::Bool && width == 1 => (Prim::Bool, None),
        Some(s) if s.prim.is_unsigned() && wide(s.prim) => (s.prim, None),
        Some(s) if s.prim.is_signed() && !s.prim.is_narrow() && site != MemberSite::Header => {
            if wide(s.prim) {
                return (s.prim, None);
            }
            ctx.error(
                t.span(),
                format!(
                    "type `{}` cannot hold the {width} bits of `{}`",
                    t.get_ref(),
                    m.name.get_ref()
                ),
                format!(
                    "use `{}`, or a wider signed integer",
                    smallest_int(width).rust_name()
                ),
            );
            (smallest_int(width), None)
        }
        Some(s) if s.prim.is_signed() && site == MemberSite::Header => {
            ctx.error(
                t.span(),
                format!("header bit member `{}` is signed (`{}`)", m.name.get_ref(), t.get_ref()),
                "use an unsigned integer: a header member is a length, a constant or a value read as it is",
            );
            (smallest_uint(width), None)
        }
        Some(_) => {
            let help = match site {
                MemberSite::Header => {
                    "use `bool` for one bit, or an unsigned integer at least as wide"
                }
                _ => {
                    "use `bool` for one bit, or an integer (`u8` ... `u64`, `i8` ... `i64` for two's complement) at least as wide"
                }
            };
            ctx.error(
                t.span(),
                format!(
                    "type `{}` cannot hold the {width} bits of `{}`",
                    t.get_ref(),
                    m.name.get_ref()
                ),
                help,
            );
            (smallest_uint(width), None)
        }
        None => match enums.by_name.get(t.get_ref()) {
            Some(&i) => {
                let e = &enums.enums[i];
                if let Some(v) = e.variants.iter().find(|v| v.value > mask(width)) {
                    ctx.error(
                        t.span(),
                        format!(
                            "enum `{}` has value {} (`{}`), which does not fit in {width} bits",
                            e.name, v.value, v.name
                        ),
                        "widen the member or narrow the enum",
                    );
                }
                (smallest_uint(width), Some(i))
            }
            None => {
                let mut known: Vec<String> = ["bool", "u8", "u16", "u32", "u64"]
                    .into_iter()
                    .map(String::from)
                    .collect();
                if site != MemberSite::Header {
                    known.extend(["i8", "i16", "i32", "i64"].map(String::from));
                }
                known.extend(enums.enums.iter().map(|e| e.name.clone()));
                unknown_type(ctx, t, &known, "a bit member's type");
                (smallest_uint(width), None)
            }
        },
    }
}

/// Rule: `scale`, `offset` and `unit` apply to the bit members of payload fields.
fn reject_header_scale(ctx: &mut Ctx<'_>, m: &BitDef) {
    for (key, span) in [
        ("scale", m.scale.as_ref().map(Spanned::span)),
        ("offset", m.offset.as_ref().map(Spanned::span)),
        ("unit", m.unit.as_ref().map(Spanned::span)),
    ] {
        if let Some(span) = span {
            ctx.error(
                span,
                format!(
                    "`{key}` applies to the bit members of payload fields, not of header fields"
                ),
                format!("remove `{key}`"),
            );
        }
    }
}

/// Rule: `scale` and `offset` on a bit member apply to a number (not `bool`, not an enum);
/// the factor is finite and not 0; the physical value is an `f32` for members of up to 16
/// bits, else an `f64`, and encoding rounds to the nearest raw value, which must fit the
/// member's bits (an error otherwise, never saturated).
fn lower_member_scale(
    ctx: &mut Ctx<'_>,
    b: &Spanned<BitDef>,
    width: u32,
    prim: Prim,
    enum_index: Option<usize>,
) -> Option<Scale> {
    let m = b.get_ref();
    let span = m.scale.as_ref().or(m.offset.as_ref()).map(Spanned::span)?;
    if prim == Prim::Bool || enum_index.is_some() {
        ctx.error(
            span,
            format!(
                "`scale` applies to number members, not to `{}` (a flag or an enum)",
                m.name.get_ref()
            ),
            "remove `scale`/`offset`, or give the member an integer `type`",
        );
        return None;
    }
    let factor = m.scale.as_ref().map_or(1.0, |s| *s.get_ref());
    if factor == 0.0 || !factor.is_finite() {
        ctx.error(
            span,
            "a scale factor must be a finite number other than 0",
            "write e.g. `scale = 0.0001` for 0.1 mm on the wire and metres in Rust",
        );
        return None;
    }
    Some(Scale {
        factor,
        offset: m.offset.as_ref().map_or(0.0, |o| *o.get_ref()),
        physical: if width <= 16 { Prim::F32 } else { Prim::F64 },
        rounding: Rounding::Nearest,
        clamp: None,
    })
}

/// The smallest signed type that holds `width` bits of two's complement.
fn smallest_int(width: u32) -> Prim {
    match width {
        0..=8 => Prim::I8,
        9..=16 => Prim::I16,
        17..=32 => Prim::I32,
        _ => Prim::I64,
    }
}

/// The smallest unsigned type that holds `width` bits.
pub(super) fn smallest_uint(width: u32) -> Prim {
    match width {
        0..=8 => Prim::U8,
        9..=16 => Prim::U16,
        17..=32 => Prim::U32,
        _ => Prim::U64,
    }
}

/// Rule: the bits of a payload bitfield word above its members are never silently zeroed:
/// `reserved = "keep"` (the default) holds them in one more member, `<field>_reserved`, the
/// smallest unsigned type that fits them, so that decoding then encoding gives the same
/// bytes; `reserved = "zero"` declares them reserved-zero (written as zero, ignored when
/// read). `reserved` is `"keep"` or `"zero"`, and the kept member's name is not a member's
/// already. Gives the member that keeps them, if any.
pub(super) fn lower_reserved_bits(
    ctx: &mut Ctx<'_>,
    d: &FieldDef,
    name: &SStr,
    word: Prim,
    members: &[BitMember],
) -> Option<BitMember> {
    let keep = match d.reserved.as_ref().map(|r| (r, r.get_ref().as_str())) {
        None | Some((_, "keep")) => true,
        Some((_, "zero")) => false,
        Some((r, other)) => {
            ctx.error(
                r.span(),
                format!("unknown `reserved` policy `{other}`"),
                "write `reserved = \"keep\"` (the bits above the members are kept in `<field>_reserved`) or `reserved = \"zero\"` (they are written as zero and ignored when read)",
            );
            false
        }
    };
    let word_bits = (word.size() * 8) as u32;
    let shift: u32 = members.iter().map(|m| m.width).sum();
    if !keep || shift >= word_bits {
        return None;
    }
    let member = format!("{}_reserved", name.get_ref());
    if members.iter().any(|m| m.name == member) {
        ctx.error(
            name.span(),
            format!(
                "bit member `{member}` would also hold the bits of `{}` above its members",
                name.get_ref()
            ),
            "rename the member, or write `reserved = \"zero\"` if those bits are always zero",
        );
        return None;
    }
    let width = word_bits - shift;
    Some(BitMember {
        doc: format!(
            "Bits {shift}..{word_bits} of `{}`, which the spec declares no member for: kept so that decoding then encoding gives the same bytes.",
            name.get_ref()
        ),
        name: member,
        shift,
        width,
        prim: smallest_uint(width),
        enum_index: None,
        scale: None,
        unit: String::new(),
    })
}

/// Rule: a bit-packed array has a `count`, elements of 1 to 32 bits, a stated bit order
/// (`"lsb-first"` or `"msb-first"`), no `type` (its elements are the smallest unsigned type
/// that holds them), and may be scaled as an integer field is.
pub(super) fn lower_packed(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    packed: &Spanned<PackedDef>,
    constants: &[Constant],
) -> Option<FieldKind> {
    let d = f.get_ref();
    let p = packed.get_ref();
    if let Some(ty) = &d.ty {
        ctx.error(
            ty.span(),
            "a packed array takes no `type`: its elements are the smallest unsigned type that holds `bits`",
            "remove `type`",
        );
    }
    if d.bits.is_some() || d.repeat.is_some() || d.max.is_some() || d.size.is_some() {
        ctx.error(
            f.span(),
            "a packed array takes `name`, `packed`, `count`, scaling keys, `unit` and `doc`",
            "remove the other keys",
        );
    }
    let bits = *p.bits.get_ref();
    if !(1..=32).contains(&bits) {
        ctx.error(
            p.bits.span(),
            format!("packed elements of {bits} bits"),
            "an element has 1 to 32 bits",
        );
        return None;
    }
    let bits = bits as u32;
    let order = match p.order.get_ref().as_str() {
        "lsb-first" => BitOrder::LsbFirst,
        "msb-first" => BitOrder::MsbFirst,
        other => {
            ctx.error(
                p.order.span(),
                format!("unknown bit order `{other}`"),
                "write `order = \"lsb-first\"` (bit 0 of byte 0 first, as CRSF and SBUS) or `order = \"msb-first\"` (bit 7 of byte 0 first)",
            );
            return None;
        }
    };
    let Some(count) = lower_count(ctx, d, constants) else {
        if d.count.is_none() {
            ctx.error(
                packed.span(),
                "a packed array needs a `count`",
                "add `count = N`, the number of elements",
            );
        }
        return None;
    };
    let prim = smallest_uint(bits);
    let raw = Scalar {
        prim,
        endian: ByteOrder::Little,
    };
    let scale = lower_scale(ctx, f, prim.spec_name(), raw);
    Some(FieldKind::Packed {
        count,
        bits,
        order,
        prim,
        scale,
    })
}

/// Rule: a bit stream (`type = "bitstream"`) has `bits`, at least one member, each of 1 to 64
/// bits (signed, scaled or enum members as in a word); it takes no `count`, `repeat`, `max`,
/// `size`, `reserved` or scaling keys of its own (its members carry them). Gives its size in
/// bytes and its kind.
pub(super) fn lower_stream(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    ty: &SStr,
    enums: &Enums,
) -> Option<(usize, FieldKind)> {
    let d = f.get_ref();
    let own = [
        ("count", d.count.as_ref().map(Spanned::span)),
        ("repeat", d.repeat.as_ref().map(Spanned::span)),
        ("max", d.max.as_ref().map(Spanned::span)),
        ("size", d.size.as_ref().map(Spanned::span)),
        ("reserved", d.reserved.as_ref().map(Spanned::span)),
        ("scale", d.scale.as_ref().map(Spanned::span)),
        ("offset", d.offset.as_ref().map(Spanned::span)),
        ("unit", d.unit.as_ref().map(Spanned::span)),
    ];
    for (key, span) in own {
        if let Some(span) = span {
            ctx.error(
                span,
                format!("`{key}` does not apply to a bit stream"),
                format!("remove `{key}`: a bit stream's members carry their own scaling and units, and its bits after the last member are zero"),
            );
        }
    }
    let Some(bits) = &d.bits else {
        ctx.error(
            ty.span(),
            "a `bitstream` field needs `bits`",
            "list its members, first bit first: `bits = [{ name = \"number\", bits = 12 }, ...]`",
        );
        return None;
    };
    let members = lower_bits(ctx, bits.get_ref(), 64, MemberSite::Stream, enums, &|m| {
        if m.length_of.is_some() || m.value.is_some() {
            Some("`length_of` and `value` apply to header bitfields only")
        } else {
            None
        }
    });
    let total: u32 = members.iter().map(|m| m.width).sum();
    if bits.get_ref().is_empty() {
        ctx.error(
            bits.span(),
            "a bit stream with no members",
            "list at least one member, or remove the field",
        );
        return None;
    }
    Some((total.div_ceil(8) as usize, FieldKind::BitStream { members }))
}
