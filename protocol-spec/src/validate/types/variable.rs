//! Rules for fields of variable size: sized bytes and text, NUL-terminated text, repeated values and
//! repeated groups.

use toml::Spanned;

use super::super::Ctx;
use super::Structs;
use crate::ir::ValueType;
use crate::spec::model::{FieldDef, SStr};

/// Rule: variable bytes and text without a terminator (`type = "str"`) have a `max` of at
/// least 1 and take only `name`, `type`, `max`, `size`, `unit` and `doc`. Gives the most bytes
/// and the field that holds their number.
pub(super) fn lower_bytes(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    ty: &SStr,
    count: Option<usize>,
) -> Option<(usize, Option<String>)> {
    let d = f.get_ref();
    let (what, need) = if ty.get_ref() == "str" {
        ("text", "needs")
    } else {
        ("variable bytes", "need")
    };
    let Some(max) = &d.max else {
        ctx.error(
            ty.span(),
            format!("{what} `{}` {need} a `max`", name.get_ref()),
            "add `max = N`: the most bytes the field can hold (decoders store them inline)",
        );
        return None;
    };
    if *max.get_ref() <= 0 {
        ctx.error(
            max.span(),
            "`max` must be at least 1",
            "use the largest number of bytes the field may carry",
        );
        return None;
    }
    if count.is_some() || d.bits.is_some() || d.scale.is_some() {
        ctx.error(
            f.span(),
            format!(
                "{what} `{}` {} only `name`, `type`, `max`, `size`, `unit` and `doc`",
                name.get_ref(),
                if need == "needs" { "takes" } else { "take" }
            ),
            "remove the other keys",
        );
    }
    let size_from = d.size.as_ref().map(|s| s.get_ref().clone());
    Some((*max.get_ref() as usize, size_from))
}

/// The most bytes of a NUL-terminated text, as of a `char[N]`.
const MAX_NUL_TEXT_LEN: usize = 65534;

/// Rule: NUL-terminated text (`type = "cstr"`) has a `max` of 1 to [`MAX_NUL_TEXT_LEN`]
/// bytes of text (the NUL not counted) and takes only `name`, `type`, `max`, `optional` and
/// `doc`. Gives `max`.
pub(super) fn lower_nul_text(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    ty: &SStr,
    count: Option<usize>,
) -> Option<usize> {
    let d = f.get_ref();
    if count.is_some()
        || d.bits.is_some()
        || d.scale.is_some()
        || d.size.is_some()
        || d.repeat.is_some()
        || d.unit.is_some()
    {
        ctx.error(
            f.span(),
            format!(
                "NUL-terminated text `{}` takes only `name`, `type`, `max`, `optional` and `doc`",
                name.get_ref()
            ),
            "remove the other keys (an array of texts is `char[N]` with `count`)",
        );
    }
    let Some(max) = &d.max else {
        ctx.error(
            ty.span(),
            format!("NUL-terminated text `{}` needs a `max`", name.get_ref()),
            "add `max = N`: the most bytes of text, the NUL not counted (decoders store them inline)",
        );
        return None;
    };
    match usize::try_from(*max.get_ref()) {
        Ok(n) if (1..=MAX_NUL_TEXT_LEN).contains(&n) => Some(n),
        _ => {
            ctx.error(
                max.span(),
                format!("`max` of a NUL-terminated text is 1 to {MAX_NUL_TEXT_LEN}"),
                "give the most bytes of text, the NUL not counted",
            );
            None
        }
    }
}

/// Rule: a variable-length array repeats a primitive (scaled or not) or an enum, at most
/// `max` (at least 1) times, and has no `count` (a fixed array) or `bits`. Gives `max`.
pub(super) fn lower_array(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    elem: &ValueType,
    count: Option<usize>,
) -> Option<usize> {
    let d = f.get_ref();
    if !matches!(elem, ValueType::Scalar { .. } | ValueType::Enum(..)) {
        ctx.error(
            d.ty.as_ref().map_or(f.span(), Spanned::span),
            format!("`{}` repeats text: a variable-length array repeats a primitive, an enum or a struct", name.get_ref()),
            "use `count` for a fixed array of texts",
        );
        return None;
    }
    if count.is_some() || d.bits.is_some() {
        ctx.error(
            f.span(),
            format!(
                "variable-length array `{}` takes no `count` or `bits`",
                name.get_ref()
            ),
            "remove `count` (`repeat` and `max` make the array variable) or `repeat`",
        );
    }
    let Some(max) = d.max.as_ref().filter(|m| *m.get_ref() > 0) else {
        ctx.error(
            f.span(),
            format!(
                "variable-length array `{}` needs `max`, the most elements (at least 1)",
                name.get_ref()
            ),
            "add `max = N`: decoders store the elements inline",
        );
        return None;
    };
    Some(*max.get_ref() as usize)
}

/// Rule: a repeated group repeats a struct, at most `max` (at least 1) times. Gives the
/// element struct and `max`.
pub(super) fn lower_group(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    ty: &SStr,
    structs: &Structs,
) -> Option<(usize, usize)> {
    let Some(&elem) = structs.by_name.get(ty.get_ref()) else {
        ctx.error(
            ty.span(),
            format!(
                "a repeated group repeats a struct, and `{}` is not one",
                ty.get_ref()
            ),
            "declare the element as `[structs.NAME]`",
        );
        return None;
    };
    let Some(max) = f.get_ref().max.as_ref().filter(|m| *m.get_ref() > 0) else {
        ctx.error(
            f.span(),
            format!(
                "repeated group `{}` needs `max`, the most elements",
                name.get_ref()
            ),
            "add `max = N`: decoders store the elements inline",
        );
        return None;
    };
    Some((elem, *max.get_ref() as usize))
}
