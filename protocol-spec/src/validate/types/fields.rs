//! Rules for one field of a payload struct: padding, names and types, arrays, variable bytes
//! and text, NUL-terminated text, repeated groups, bitfields and scaling.

use toml::Spanned;

use super::super::names::{check_snake_name, parse_prim, prim_spellings, unknown_type};
use super::super::{Ctx, text};
use super::bits::{MemberSite, lower_bits, lower_packed, lower_reserved_bits, lower_stream};
use super::mask::check_mask_site;
use super::variable::{lower_array, lower_bytes, lower_group, lower_nul_text};
use super::{Enums, Structs};
use crate::diag::did_you_mean;
use crate::ir::{ByteOrder, Constant, Field, FieldKind, Prim, Rounding, Scalar, Scale, ValueType};
use crate::spec::model::{CountDef, FieldDef, SStr};

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
    let inverted = check_invert(ctx, d, endian);
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
    reject_keys_of_other_kinds(ctx, d);
    let count = lower_count(ctx, d, constants);
    let field = |size, kind, doc: &Option<SStr>| Field {
        name: name.get_ref().clone(),
        doc: text(doc),
        offset,
        size,
        kind,
        unit: text(&d.unit),
    };
    if ty.get_ref() == "bitstream" {
        let (size, kind) = lower_stream(ctx, f, ty, enums)?;
        return Some(field(size, kind, &d.doc));
    }
    if ty.get_ref() == "bytes" || ty.get_ref() == "str" {
        let text = ty.get_ref() == "str";
        let (max, size_from) = lower_bytes(ctx, f, name, ty, count)?;
        let kind = FieldKind::Bytes {
            max,
            size_from,
            text,
        };
        return Some(field(max, kind, &d.doc));
    }
    if ty.get_ref() == "cstr" {
        let max = lower_nul_text(ctx, f, name, ty, count)?;
        return Some(field(max + 1, FieldKind::NulText { max }, &d.doc));
    }
    let repeat = d.repeat.as_ref().is_some_and(|r| *r.get_ref());
    let of_struct = structs.by_name.contains_key(ty.get_ref())
        || ctx.spec.structs.keys().any(|k| k.get_ref() == ty.get_ref());
    check_mask_site(ctx, d, of_struct);
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
        let scalar = parse_prim(ty.get_ref(), endian).map(|s| invert(s, inverted));
        let (elem, elem_size) = lower_value_type(ctx, f, ty, scalar, endian, structs, enums)?;
        let max = lower_array(ctx, f, name, &elem, count)?;
        let by_mask = d.mask.is_some() && d.size.is_none();
        let size_from = d.size.as_ref().or(d.mask.as_ref());
        let kind = FieldKind::Array {
            ty: elem,
            max,
            size_from: size_from.map(|s| s.get_ref().clone()),
            by_mask,
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
    let scalar = parse_prim(ty.get_ref(), endian).map(|s| invert(s, inverted));
    if d.bits.is_some() {
        let (word, kind) = lower_bitfield(ctx, f, name, ty, scalar, count, enums)?;
        return Some(field(word.prim.size(), kind, &d.doc));
    }
    let (elem, elem_size) = lower_value_type(ctx, f, ty, scalar, endian, structs, enums)?;
    let kind = FieldKind::Value { ty: elem, count };
    Some(field(elem_size * count.unwrap_or(1), kind, &d.doc))
}

/// Rule: `invert` applies to `bool` fields (single, arrays or repeated), not to bitfields.
/// Gives whether the field's bools are inverted.
fn check_invert(ctx: &mut Ctx<'_>, d: &FieldDef, endian: ByteOrder) -> bool {
    let Some(inv) = &d.invert else {
        return false;
    };
    let is_bool = d.packed.is_none()
        && d.bits.is_none()
        && d.ty
            .as_ref()
            .and_then(|t| parse_prim(t.get_ref(), endian))
            .is_some_and(|s| s.prim == Prim::Bool);
    if !is_bool {
        ctx.error(
            inv.span(),
            "`invert` applies to `bool` fields",
            "remove `invert`, or give the field `type = \"bool\"`",
        );
        return false;
    }
    *inv.get_ref()
}

/// The inverted form of a `bool` scalar when `inverted`; any other scalar as it is.
fn invert(s: Scalar, inverted: bool) -> Scalar {
    match s.prim {
        Prim::Bool if inverted => Scalar {
            prim: Prim::BoolInverted,
            ..s
        },
        _ => s,
    }
}

/// Rule: `prefix` and `byte_order` apply to check fields, `reserved` to fields with `bits`.
fn reject_keys_of_other_kinds(ctx: &mut Ctx<'_>, d: &FieldDef) {
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
}

/// Rule: a payload bitfield is an unsigned integer word, not an array; its members follow the
/// bit member rules (without the header-only `length_of` and `value`), and the bits above
/// them are kept or declared reserved. Gives the word and the field's kind.
fn lower_bitfield(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    name: &SStr,
    ty: &SStr,
    scalar: Option<Scalar>,
    count: Option<usize>,
    enums: &Enums,
) -> Option<(Scalar, FieldKind)> {
    let d = f.get_ref();
    let bits = d.bits.as_ref()?;
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
    let word_bits = (word.prim.size() * 8) as u32;
    let site = MemberSite::Word;
    let mut members = lower_bits(ctx, bits.get_ref(), word_bits, site, enums, &|m| {
        if m.length_of.is_some() || m.value.is_some() {
            Some("`length_of` and `value` apply to header bitfields only")
        } else {
            None
        }
    });
    members.extend(lower_reserved_bits(ctx, d, name, word.prim, &members));
    Some((word, FieldKind::Bits { word, members }))
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
pub(super) fn lower_count(
    ctx: &mut Ctx<'_>,
    d: &FieldDef,
    constants: &[Constant],
) -> Option<usize> {
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
        known.extend(["bytes", "cstr", "str"].map(String::from));
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

/// Rule: `scale` and `offset` apply to number fields (integers and floats, not `bool`); the
/// factor is finite and not 0; the physical value is the Rust type a derive's field declares
/// (`f32` or `f64`), else an `f32` for wire numbers of up to two bytes and an `f64` for wider
/// ones; `rounding` applies to integer wire types only (a float takes the quotient as it is).
pub(crate) fn lower_scale(
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
    if scalar.prim.is_bool() {
        let span = s
            .as_ref()
            .or(o.as_ref())
            .map(Spanned::span)
            .unwrap_or(f.span());
        ctx.error(
            span,
            format!("`scale` applies to number fields, not `{ty}`"),
            "remove `scale`/`offset`, or use an integer or float wire type",
        );
        return None;
    }
    if let (true, Some(r)) = (scalar.prim.is_float(), &d.rounding) {
        ctx.error(
            r.span(),
            format!("`rounding` applies to scaled integer fields, not `{ty}`"),
            "remove `rounding`: a float wire value takes the quotient as it is",
        );
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
            format!("`scale` applies to number fields, not to {what}"),
            "remove `scale`",
        );
    }
}
