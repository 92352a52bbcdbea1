//! Rules for bitfield members: widths, names and member types.

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, unknown_type};
use super::super::{Ctx, text};
use super::{Enums, mask};
use crate::ir::{BitMember, ByteOrder, Prim};
use crate::spec::model::BitDef;

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
