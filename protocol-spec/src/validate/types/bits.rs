//! Rules for bits: bitfield members (widths, names and member types), the reserved bits above
//! them, and bit-packed arrays.

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, unknown_type};
use super::super::{Ctx, text};
use super::fields::{lower_count, lower_scale};
use super::{Enums, mask};
use crate::ir::{BitMember, BitOrder, ByteOrder, Constant, FieldKind, Prim, Scalar};
use crate::spec::model::{BitDef, FieldDef, PackedDef, SStr};

/// Rule: bit members have snake_case names, unique, at least one bit each, and together no
/// more bits than their word; a member's type is `bool` (one bit), an unsigned integer wide
/// enough, or an enum whose values fit the member. `extra` rejects keys the context forbids.
pub(crate) fn lower_bits(
    ctx: &mut Ctx<'_>,
    bits: &[Spanned<BitDef>],
    word: Prim,
    enums: &Enums,
    extra: &dyn Fn(&BitDef) -> Option<&'static str>,
) -> Vec<BitMember> {
    let word_bits = (word.size() * 8) as u32;
    let mut shift = 0u32;
    let mut members: Vec<BitMember> = Vec::new();
    for b in bits {
        let m = b.get_ref();
        if let Some(msg) = extra(m) {
            ctx.error(b.span(), msg, "remove the key");
        }
        check_snake_name(ctx, &m.name, "bit member");
        let width = *m.bits.get_ref();
        if width <= 0 || width > i64::from(word_bits) {
            ctx.error(
                m.bits.span(),
                format!("bit member `{}` has {width} bits", m.name.get_ref()),
                format!("a member has 1 to {word_bits} bits"),
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
        let (prim, enum_index) = match &m.ty {
            None if width == 1 => (Prim::Bool, None),
            None => (smallest_uint(width), None),
            Some(t) => match parse_prim(t.get_ref(), ByteOrder::Little) {
                Some(s) if s.prim == Prim::Bool && width == 1 => (Prim::Bool, None),
                Some(s) if s.prim.is_unsigned() && (s.prim.size() * 8) as u32 >= width => {
                    (s.prim, None)
                }
                Some(_) => {
                    ctx.error(
                        t.span(),
                        format!(
                            "type `{}` cannot hold the {width} bits of `{}`",
                            t.get_ref(),
                            m.name.get_ref()
                        ),
                        "use `bool` for one bit, or an unsigned integer at least as wide",
                    );
                    (smallest_uint(width), None)
                }
                None => match enums.by_name.get(t.get_ref()) {
                    Some(&i) => {
                        let e = &enums.enums[i];
                        if let Some(v) = e.variants.iter().find(|v| v.value > mask(width)) {
                            ctx.error(t.span(), format!("enum `{}` has value {} (`{}`), which does not fit in {width} bits", e.name, v.value, v.name), "widen the member or narrow the enum");
                        }
                        (smallest_uint(width), Some(i))
                    }
                    None => {
                        let mut known = vec![
                            "bool".to_string(),
                            "u8".into(),
                            "u16".into(),
                            "u32".into(),
                            "u64".into(),
                        ];
                        known.extend(enums.enums.iter().map(|e| e.name.clone()));
                        unknown_type(ctx, t, &known, "a bit member's type");
                        (smallest_uint(width), None)
                    }
                },
            },
        };
        members.push(BitMember {
            name: m.name.get_ref().clone(),
            doc: text(&m.doc),
            shift,
            width,
            prim,
            enum_index,
        });
        shift += width;
    }
    if shift > word_bits {
        let span = bits.last().map(Spanned::span).unwrap_or_default();
        ctx.error(
            span,
            format!("the bit members add up to {shift} bits, but the word has {word_bits}"),
            "shrink the members or use a wider word type",
        );
    }
    members
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
