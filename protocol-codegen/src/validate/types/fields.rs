//! Rules for one field of a payload struct: padding, names and types, arrays, variable bytes,
//! NUL-terminated text, repeated groups, bitfields and scaling.

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, prim_spellings, unknown_type};
use super::super::{Ctx, text};
use super::bits::{lower_bits, smallest_uint};
use super::{Enums, Structs};
use crate::diag::did_you_mean;
use crate::ir::{
    BitMember, BitOrder, ByteOrder, Constant, Field, FieldKind, Prim, Rounding, Scalar, Scale,
    ValueType,
};
use crate::spec::model::{CountDef, FieldDef, PackedDef, SStr};

/// Rule: a field is either `{ pad = N }` (N > 0, nothing else but `doc`) or a named value with a
/// type; `count` makes a fixed array (> 0); `bits` splits an unsigned integer into members
/// whose widths add up to at most the integer's width; `scale`/`offset` apply to integers only.
pub(super) fn lower_field(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    endian: ByteOrder,
    structs: &Structs,
    enums: &Enums,
    constants: &[Constant],
    offset: usize,
) -> Option<Field> {
    let d = f.get_ref();
    if let Some(pad) = &d.pad {
        return lower_padding(ctx, f, pad, offset);
    }
    let Some(name) = &d.name else {
        ctx.error(
            f.span(),
            "a field needs a `name` (or is a padding entry `{ pad = N }`)",
            "add `name = \"...\"`",
        );
        return None;
    };
    check_snake_name(ctx, name, "field name");
    if let Some(packed) = &d.packed {
        let kind = lower_packed(ctx, f, packed, constants)?;
        let FieldKind::Packed { count, bits, .. } = kind else {
            return None;
        };
        let size = (count * bits as usize).div_ceil(8);
        return Some(Field {
            name: name.get_ref().clone(),
            doc: text(&d.doc),
            offset,
            size,
            kind,
            unit: text(&d.unit),
        });
    }
    let Some(ty) = &d.ty else {
        ctx.error(
            f.span(),
            format!("field `{}` has no `type`", name.get_ref()),
            "add `type = \"u8\"` (or another primitive, struct or enum)",
        );
        return None;
    };
    for (key, span) in [
        ("prefix", d.prefix.as_ref().map(Spanned::span)),
        ("byte_order", d.byte_order.as_ref().map(Spanned::span)),
    ] {
        if let Some(span) = span {
            ctx.error(
                span,
                format!("`{key}` applies to check fields"),
                format!("add `check = \"algorithm\"` and `over`, or remove `{key}`"),
            );
        }
    }
    if let (Some(r), None) = (&d.reserved, &d.bits) {
        ctx.error(
            r.span(),
            "`reserved` applies to fields with `bits`",
            "remove `reserved`",
        );
    }
    let count = lower_count(ctx, d, constants);
    let field = |size, kind, doc: &Option<SStr>| Field {
        name: name.get_ref().clone(),
        doc: text(doc),
        offset,
        size,
        kind,
        unit: text(&d.unit),
    };
    if ty.get_ref() == "bytes" {
        let (max, size_from) = lower_bytes(ctx, f, name, ty, count)?;
        return Some(field(max, FieldKind::Bytes { max, size_from }, &d.doc));
    }
    if ty.get_ref() == "cstr" {
        let max = lower_nul_text(ctx, f, name, ty, count)?;
        return Some(field(max + 1, FieldKind::NulText { max }, &d.doc));
    }
    let repeat = d.repeat.as_ref().is_some_and(|r| *r.get_ref());
    let of_struct = structs.by_name.contains_key(ty.get_ref())
        || ctx.spec.structs.keys().any(|k| k.get_ref() == ty.get_ref());
    if let Some(sz) = d.size.as_ref().filter(|_| !repeat || of_struct) {
        ctx.error(
            sz.span(),
            "`size` applies to `type = \"bytes\"` fields and repeated primitives",
            "remove `size`",
        );
    }
    if repeat && of_struct {
        let (elem, max) = lower_group(ctx, f, name, ty, structs)?;
        let size = structs.structs[elem].size * max;
        return Some(field(size, FieldKind::Group { elem, max }, &d.doc));
    }
    if repeat {
        let scalar = parse_prim(ty.get_ref(), endian);
        let (elem, elem_size) = lower_value_type(ctx, f, ty, scalar, endian, structs, enums)?;
        let max = lower_array(ctx, f, name, &elem, count)?;
        let size_from = d.size.as_ref().map(|s| s.get_ref().clone());
        let kind = FieldKind::Array {
            ty: elem,
            max,
            size_from,
        };
        return Some(field(elem_size * max, kind, &d.doc));
    }
    if let Some(max) = &d.max {
        ctx.error(
            max.span(),
            "`max` applies to `type = \"bytes\"` fields and repeated groups",
            "remove `max`, or use `count` for a fixed array",
        );
    }
    let scalar = parse_prim(ty.get_ref(), endian);
    if let Some(bits) = &d.bits {
        let Some(word) = scalar.filter(|s| s.prim.is_unsigned()) else {
            ctx.error(
                ty.span(),
                format!(
                    "a field with `bits` must be an unsigned integer, not `{}`",
                    ty.get_ref()
                ),
                "use `u8`, `u16`, `u32` or `u64`",
            );
            return None;
        };
        if count.is_some() {
            ctx.error(
                f.span(),
                "a bitfield cannot be an array",
                "remove `count`, or wrap the bitfield in a struct and make an array of it",
            );
        }
        let mut members = lower_bits(ctx, bits.get_ref(), word.prim, enums, &|m| {
            if m.length_of.is_some() || m.value.is_some() {
                Some("`length_of` and `value` apply to header bitfields only")
            } else {
                None
            }
        });
        members.extend(lower_reserved_bits(ctx, d, name, word.prim, &members));
        let kind = FieldKind::Bits { word, members };
        return Some(field(word.prim.size(), kind, &d.doc));
    }
    let (elem, elem_size) = lower_value_type(ctx, f, ty, scalar, endian, structs, enums)?;
    let kind = FieldKind::Value { ty: elem, count };
    Some(field(elem_size * count.unwrap_or(1), kind, &d.doc))
}

/// Rule: the bits of a payload bitfield word above its members are never silently zeroed:
/// `reserved = "keep"` (the default) holds them in one more member, `<field>_reserved`, the
/// smallest unsigned type that fits them, so that decoding then encoding gives the same
/// bytes; `reserved = "zero"` declares them reserved-zero (written as zero, ignored when
/// read). `reserved` is `"keep"` or `"zero"`, and the kept member's name is not a member's
/// already. Gives the member that keeps them, if any.
fn lower_reserved_bits(
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
fn lower_packed(
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

/// Rule: a padding entry takes only `pad` (and `doc`), at least one byte.
fn lower_padding(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    pad: &Spanned<i64>,
    offset: usize,
) -> Option<Field> {
    let d = f.get_ref();
    if d.name.is_some()
        || d.ty.is_some()
        || d.count.is_some()
        || d.bits.is_some()
        || d.scale.is_some()
    {
        ctx.error(
            f.span(),
            "a padding entry takes only `pad` (and `doc`)",
            "write the padding as its own entry, e.g. `{ pad = 3 }`, and the field as another",
        );
    }
    if *pad.get_ref() <= 0 {
        ctx.error(
            pad.span(),
            "padding must be at least one byte",
            "remove the entry or use `pad = 1` or more",
        );
        return None;
    }
    Some(Field {
        name: String::new(),
        doc: text(&d.doc),
        offset,
        size: *pad.get_ref() as usize,
        kind: FieldKind::Padding,
        unit: String::new(),
    })
}

/// Rule: an array count is a number of at least 1, or a constant that is.
fn lower_count(ctx: &mut Ctx<'_>, d: &FieldDef, constants: &[Constant]) -> Option<usize> {
    let c = d.count.as_ref()?;
    match c.get_ref() {
        CountDef::Literal(n) if *n > 0 => Some(*n as usize),
        CountDef::Literal(_) => {
            ctx.error(
                c.span(),
                "an array count must be at least 1",
                "use `count = 1` or more",
            );
            None
        }
        CountDef::Constant(cname) => match constants.iter().find(|k| &k.name == cname) {
            Some(k) if k.value > 0 => Some(k.value as usize),
            Some(_) => {
                ctx.error(
                    c.span(),
                    format!("constant `{cname}` is 0, not a valid array count"),
                    "set the constant to 1 or more",
                );
                None
            }
            None => {
                let help = match did_you_mean(cname, constants.iter().map(|k| k.name.as_str())) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "declare it under `[constants]`, or write a number".to_string(),
                };
                ctx.error(c.span(), format!("unknown constant `{cname}`"), help);
                None
            }
        },
    }
}

/// Rule: variable bytes have a `max` of at least 1 and take only `name`, `type`, `max`,
/// `size`, `unit` and `doc`. Gives the most bytes and the field that holds their number.
fn lower_bytes(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    ty: &SStr,
    count: Option<usize>,
) -> Option<(usize, Option<String>)> {
    let d = f.get_ref();
    let Some(max) = &d.max else {
        ctx.error(
            ty.span(),
            format!("variable bytes `{}` need a `max`", name.get_ref()),
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
            "variable bytes take only `name`, `type`, `max`, `unit` and `doc`",
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
fn lower_nul_text(
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
fn lower_array(
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
fn lower_group(
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

/// Rule: a value's type is a primitive, a struct of fixed size, or an enum; only a primitive
/// takes scaling keys. Gives the element type and its size.
fn lower_value_type(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    ty: &SStr,
    scalar: Option<Scalar>,
    endian: ByteOrder,
    structs: &Structs,
    enums: &Enums,
) -> Option<(ValueType, usize)> {
    let d = f.get_ref();
    if let Some(scalar) = scalar {
        let scale = lower_scale(ctx, f, ty.get_ref(), scalar);
        return Some((ValueType::Scalar { scalar, scale }, scalar.prim.size()));
    }
    if let Some(len) = lower_text(ctx, ty) {
        reject_scale(ctx, d, "text");
        return len.map(|n| (ValueType::Text(n), n));
    }
    if let Some(&i) = structs.by_name.get(ty.get_ref()) {
        reject_scale(ctx, d, "a struct");
        if structs.structs[i].min_size != structs.structs[i].size {
            ctx.error(ty.span(), format!("struct `{}` ends with variable bytes, so it cannot be a field of another struct", ty.get_ref()), "use it as a command's payload, or give the inner bytes a fixed `count`");
        }
        return Some((ValueType::Struct(i), structs.structs[i].size));
    }
    if let Some(&i) = enums.by_name.get(ty.get_ref()) {
        reject_scale(ctx, d, "an enum");
        let e = &enums.enums[i];
        let s = Scalar {
            prim: e.prim,
            endian,
        };
        return Some((ValueType::Enum(i, s), e.prim.size()));
    }
    if !ctx.spec.structs.keys().any(|k| k.get_ref() == ty.get_ref()) {
        let mut known = prim_spellings();
        known.extend(ctx.spec.structs.keys().map(|k| k.get_ref().clone()));
        known.extend(ctx.spec.enums.keys().map(|k| k.get_ref().clone()));
        unknown_type(ctx, ty, &known, "a field type");
    }
    None
}

/// The most bytes of a `char[N]` text field.
const MAX_TEXT_LEN: usize = 65535;

/// Rule: `char[N]` is N bytes of NUL-padded text, N from 1 to [`MAX_TEXT_LEN`]. `None` when
/// `ty` is no `char[...]` type; `Some(None)` when its length is wrong (reported).
fn lower_text(ctx: &mut Ctx<'_>, ty: &SStr) -> Option<Option<usize>> {
    let inner = ty.get_ref().strip_prefix("char[")?.strip_suffix(']')?;
    match inner.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_TEXT_LEN).contains(&n) => Some(Some(n)),
        _ => {
            ctx.error(
                ty.span(),
                format!(
                    "`{}` has no text length: `char[N]` takes N from 1 to {MAX_TEXT_LEN}",
                    ty.get_ref()
                ),
                "write the field's size in bytes, as C's `char name[30]` is `char[30]`",
            );
            Some(None)
        }
    }
}

/// Rule: `scale` and `offset` apply to integer fields; the factor is finite and not 0; the
/// physical value is the Rust type a derive's field declares (`f32` or `f64`), else an `f32`
/// for wire integers of up to two bytes and an `f64` for wider ones.
fn lower_scale(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    ty: &str,
    scalar: Scalar,
) -> Option<Scale> {
    let d = f.get_ref();
    if d.scale.is_none() && d.offset.is_none() {
        return None;
    }
    let (s, o) = (&d.scale, &d.offset);
    if !(scalar.prim.is_signed() || scalar.prim.is_unsigned()) {
        let span = s
            .as_ref()
            .or(o.as_ref())
            .map(Spanned::span)
            .unwrap_or(f.span());
        ctx.error(
            span,
            format!("`scale` applies to integer fields, not `{ty}`"),
            "remove `scale`/`offset`, or use an integer wire type",
        );
        return None;
    }
    let factor = s.as_ref().map_or(1.0, |s| *s.get_ref());
    if factor == 0.0 || !factor.is_finite() {
        let span = s.as_ref().map(Spanned::span).unwrap_or(f.span());
        ctx.error(
            span,
            "a scale factor must be a finite number other than 0",
            "write e.g. `scale = 0.001` for mm/s on the wire and m/s in Rust",
        );
    }
    let declared = d
        .rust
        .as_ref()
        .and_then(|r| Prim::from_rust_name(r.get_ref()))
        .filter(|p| p.is_float());
    let physical = match declared {
        Some(p) => p,
        None if scalar.prim.size() <= 2 => Prim::F32,
        None => Prim::F64,
    };
    Some(Scale {
        factor,
        offset: o.as_ref().map_or(0.0, |o| *o.get_ref()),
        physical,
        rounding: lower_rounding(ctx, d),
        clamp: lower_clamp(ctx, d),
    })
}

/// Rule: `rounding` is `"nearest"` (the default) or `"truncate"`.
fn lower_rounding(ctx: &mut Ctx<'_>, d: &FieldDef) -> Rounding {
    match d.rounding.as_ref().map(|r| r.get_ref().as_str()) {
        None | Some("nearest") => Rounding::Nearest,
        Some("truncate") => Rounding::Truncate,
        Some(other) => {
            let span = d.rounding.as_ref().map(Spanned::span).unwrap_or_default();
            ctx.error(
                span,
                format!("unknown rounding `{other}`"),
                "write `\"nearest\"` (halves away from zero) or `\"truncate\"` (toward zero, as a C cast)",
            );
            Rounding::Nearest
        }
    }
}

/// Rule: `clamp` is `[min, max]` with min <= max.
fn lower_clamp(ctx: &mut Ctx<'_>, d: &FieldDef) -> Option<(f64, f64)> {
    let c = d.clamp.as_ref()?;
    match c.get_ref().as_slice() {
        [lo, hi] if lo.get_ref() <= hi.get_ref() => Some((*lo.get_ref(), *hi.get_ref())),
        _ => {
            ctx.error(
                c.span(),
                "`clamp` is not `[min, max]` with min <= max",
                "write the physical limits, e.g. `clamp = [-1.5, 1.5]`",
            );
            None
        }
    }
}
/// Rule: rounding, clamping and scaling apply to scaled integer fields, not to `what`.
fn reject_scale(ctx: &mut Ctx<'_>, d: &FieldDef, what: &str) {
    for (key, span) in [
        ("rounding", d.rounding.as_ref().map(Spanned::span)),
        ("clamp", d.clamp.as_ref().map(Spanned::span)),
    ] {
        if let Some(span) = span {
            ctx.error(
                span,
                format!("`{key}` applies to scaled integer fields, not to {what}"),
                format!("remove `{key}`"),
            );
        }
    }
    if let Some(s) = &d.scale {
        ctx.error(
            s.span(),
            format!("`scale` applies to integer fields, not to {what}"),
            "remove `scale`",
        );
    }
}
