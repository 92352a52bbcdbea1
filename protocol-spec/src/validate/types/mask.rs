//! Rules for the fields a mask announces: a value present when a bit of an earlier field is
//! set (`when = { field, bit }`), and an array of one element per set bit (`mask`). The mask
//! is a plain unsigned integer field of the same struct, read before what it announces.

use toml::Spanned;

use super::super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{Field, FieldKind, ValueType};
use crate::spec::model::{FieldDef, SStr, WhenDef};

/// Rule: `mask` applies to a repeated primitive or enum (`repeat = true` with `max`), and
/// takes the place of `size`: a field takes one of the two.
pub(super) fn check_mask_site(ctx: &mut Ctx<'_>, d: &FieldDef, of_struct: bool) {
    let Some(mask) = &d.mask else {
        return;
    };
    let repeat = d.repeat.as_ref().is_some_and(|r| *r.get_ref());
    let ty = d.ty.as_ref().map_or("", |t| t.get_ref().as_str());
    let other_kind = ["bytes", "str", "cstr", "bitstream"].contains(&ty)
        || d.packed.is_some()
        || d.bits.is_some()
        || of_struct;
    if !repeat || other_kind {
        ctx.error(
            mask.span(),
            "`mask` applies to repeated primitives and enums",
            "write `repeat = true` and `max` on a primitive or enum field, or remove `mask`",
        );
    } else if d.size.is_some() {
        ctx.error(
            mask.span(),
            "a repeated field takes `size` or `mask`, not both",
            "`size` counts the elements by a field's value, `mask` by its set bits: keep one",
        );
    }
}

/// Rule: a field announced by a mask bit (`when`) is not also `optional`, has a fixed size
/// and one Rust field (a value, a struct of fixed size, a fixed or packed array), and names
/// a bit within the width of its mask, an earlier unsigned integer field of the struct.
/// Gives the field's kind wrapped in [`FieldKind::When`].
pub(super) fn lower_when(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    w: &Spanned<WhenDef>,
    field: &Field,
    fields: &[Field],
    later: &[Spanned<FieldDef>],
) -> Option<FieldKind> {
    let d = f.get_ref();
    if let Some(o) = d.optional.as_ref().filter(|o| *o.get_ref()) {
        ctx.error(
            o.span(),
            format!("field `{}` takes both `when` and `optional`", field.name),
            "`optional` is present when bytes remain, `when` when a mask bit is set: keep one",
        );
        return None;
    }
    // Bit members are fields of the Rust struct themselves, which an `Option` cannot hold.
    let fixed = matches!(
        field.kind,
        FieldKind::Value { .. } | FieldKind::Packed { .. }
    );
    if !fixed {
        ctx.error(
            w.span(),
            format!(
                "field `{}` has no fixed size, so a mask bit cannot announce it",
                field.name
            ),
            "give `when` to a value, a fixed or packed array, or a struct of fixed size (which may hold a bitfield)",
        );
        return None;
    }
    let WhenDef { field: mask, bit } = w.get_ref();
    let width = mask_width(ctx, mask, &field.name, fields, later)?;
    let b = *bit.get_ref();
    if !(0..i64::from(width)).contains(&b) {
        ctx.error(
            bit.span(),
            format!(
                "bit {b} is outside `{}`, which has {width} bits",
                mask.get_ref()
            ),
            format!("name a bit from 0 to {}", width - 1),
        );
        return None;
    }
    Some(FieldKind::When {
        kind: Box::new(field.kind.clone()),
        mask: mask.get_ref().clone(),
        bit: b as u32,
    })
}

/// Rule: an array counted by a mask (`mask`) holds at most as many elements as the mask has
/// bits (a larger `max` is never reached), and its mask is an earlier unsigned integer field
/// of the struct.
pub(super) fn check_mask_array(
    ctx: &mut Ctx<'_>,
    span: std::ops::Range<usize>,
    field: &Field,
    fields: &[Field],
    later: &[Spanned<FieldDef>],
) {
    let FieldKind::Array {
        max,
        size_from: Some(src),
        by_mask: true,
        ..
    } = &field.kind
    else {
        return;
    };
    let mask = Spanned::new(span.clone(), src.clone());
    let Some(width) = mask_width(ctx, &mask, &field.name, fields, later) else {
        return;
    };
    if *max > width as usize {
        ctx.error(
            span,
            format!(
                "`{}` holds up to {max} elements, but its mask `{src}` has {width} bits",
                field.name
            ),
            format!("lower `max` to {width} at most, or widen `{src}`"),
        );
    }
}

/// The width in bits of the mask field `mask` that announces `what`: an unsigned integer
/// field (unscaled, not an array) among `fields`, the fields before it; `None` with an error
/// when it is not one, comes later (`later`) or does not exist.
fn mask_width(
    ctx: &mut Ctx<'_>,
    mask: &SStr,
    what: &str,
    fields: &[Field],
    later: &[Spanned<FieldDef>],
) -> Option<u32> {
    let name = mask.get_ref();
    if let Some(prior) = fields.iter().find(|x| &x.name == name) {
        if let FieldKind::Value {
            ty:
                ValueType::Scalar {
                    scalar,
                    scale: None,
                },
            count: None,
        } = &prior.kind
        {
            if scalar.prim.is_unsigned() {
                return Some(scalar.prim.bits());
            }
        }
        ctx.error(
            mask.span(),
            format!(
                "`{name}` is not an unsigned integer field, so its bits cannot announce `{what}`"
            ),
            "name an earlier `u8`/`u16`/`u32`/`u64` field without `scale`, `count` or `bits`",
        );
        return None;
    }
    let is_later = later.iter().any(|x| {
        x.get_ref()
            .name
            .as_ref()
            .is_some_and(|n| n.get_ref() == name)
    });
    if is_later {
        ctx.error(
            mask.span(),
            format!("the mask `{name}` comes after `{what}`, which it announces"),
            format!("move `{name}` before `{what}`: a decoder reads the mask first"),
        );
    } else {
        let known = fields.iter().map(|x| x.name.as_str());
        let help = match did_you_mean(name, known) {
            Some(b) => format!("did you mean `{b}`?"),
            None => "name an earlier unsigned integer field of this struct".to_string(),
        };
        ctx.error(
            mask.span(),
            format!("no field `{name}` before `{what}`"),
            help,
        );
    }
    None
}
