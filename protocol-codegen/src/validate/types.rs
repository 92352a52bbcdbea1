//! Rules for constants, enums and payload structs: names, value ranges, field types, arrays,
//! padding, bitfields, scaling, and struct sizes (with reference cycles reported).

use std::collections::HashMap;

use toml::Spanned;

use super::names::{
    check_pascal_name, check_screaming_name, check_snake_name, parse_byte_order, parse_prim,
    pascal_case, prim_spellings, unknown_type,
};
use super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{
    BitMember, Constant, Endian, Enum, EnumVariant, Field, FieldKind, Prim, Rounding, Scalar,
    Scale, Struct, UnknownPolicy, ValueType,
};
use crate::spec::model::{BitDef, ConstantDef, CountDef, FieldDef, SStr, StructDef};

/// Rule: constants have SCREAMING_SNAKE_CASE names and non-negative values.
pub(crate) fn lower_constants(ctx: &mut Ctx<'_>) -> Vec<Constant> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    for (name, def) in &spec.constants {
        check_screaming_name(ctx, name, "constant");
        let (value, doc) = match def.get_ref() {
            ConstantDef::Bare(v) => (*v, String::new()),
            ConstantDef::Full(f) => (f.value, f.doc.clone().unwrap_or_default()),
        };
        if value < 0 {
            ctx.error(
                def.span(),
                format!("constant `{}` is negative", name.get_ref()),
                "constants are counts and values: use 0 or more",
            );
            continue;
        }
        out.push(Constant {
            name: name.get_ref().clone(),
            value: value as u64,
            doc,
        });
    }
    out
}

/// The enums, with a name index for references.
pub(crate) struct Enums {
    pub enums: Vec<Enum>,
    pub by_name: HashMap<String, usize>,
}

/// Does `value` (an i64 from TOML) fit in `prim`? Returns its two's complement bits.
pub(crate) fn fit(value: i64, prim: Prim) -> Option<u64> {
    let bits = (prim.size() * 8) as u32;
    if prim.is_signed() {
        let min = -(1i128 << (bits - 1));
        let max = (1i128 << (bits - 1)) - 1;
        let v = i128::from(value);
        (min..=max)
            .contains(&v)
            .then(|| (value as u64) & mask(bits))
    } else {
        (value >= 0 && (bits == 64 || (value as u64) <= mask(bits))).then_some(value as u64)
    }
}

/// A mask of the low `bits` bits.
pub(crate) fn mask(bits: u32) -> u64 {
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// Rule: an enum has a PascalCase name, an integer type, at least one variant,
/// SCREAMING_SNAKE_CASE variant names whose Rust names do not collide, values that fit the
/// type and are unique, and an unknown-value policy of `reject` or `keep`.
pub(crate) fn lower_enums(ctx: &mut Ctx<'_>) -> Enums {
    let spec = ctx.spec;
    let mut enums = Vec::new();
    let mut by_name = HashMap::new();
    for (name, def) in &spec.enums {
        check_pascal_name(ctx, name, "enum");
        let d = def.get_ref();
        let scalar = match parse_prim(d.ty.get_ref(), ctx.default_endian) {
            Some(s) if s.prim.is_signed() || s.prim.is_unsigned() => s,
            _ => {
                ctx.error(
                    d.ty.span(),
                    format!("enum type `{}` is not an integer type", d.ty.get_ref()),
                    "use `u8`, `u16`, `i16be`, ...",
                );
                Scalar {
                    prim: Prim::U8,
                    endian: Endian::Little,
                }
            }
        };
        let unknown = match d.unknown.as_ref().map(|u| u.get_ref().as_str()) {
            None | Some("reject") => UnknownPolicy::Reject,
            Some("keep") => UnknownPolicy::Keep,
            Some(other) => {
                let span = d.unknown.as_ref().map(Spanned::span).unwrap_or_default();
                ctx.error(span, format!("unknown policy `{other}`"), "write `unknown = \"reject\"` (decoding fails) or `unknown = \"keep\"` (an `Unknown(raw)` variant)");
                UnknownPolicy::Reject
            }
        };
        if d.values.is_empty() {
            ctx.error(
                def.span(),
                format!("enum `{}` has no values", name.get_ref()),
                "add `values = { NAME = 0, ... }`",
            );
        }
        let mut variants: Vec<EnumVariant> = Vec::new();
        for (vname, vdef) in &d.values {
            check_screaming_name(ctx, vname, "enum value");
            let (raw, doc) = match vdef.get_ref() {
                ConstantDef::Bare(v) => (*v, String::new()),
                ConstantDef::Full(f) => (f.value, f.doc.clone().unwrap_or_default()),
            };
            let Some(value) = fit(raw, scalar.prim) else {
                ctx.error(
                    vdef.span(),
                    format!(
                        "value {raw} of `{}` does not fit in {}",
                        vname.get_ref(),
                        scalar.prim.rust_name()
                    ),
                    "use a wider enum type or a smaller value",
                );
                continue;
            };
            let rust_name = pascal_case(vname.get_ref());
            if let Some(prev) = variants.iter().find(|v| v.value == value) {
                ctx.error(
                    vdef.span(),
                    format!(
                        "value {raw} of `{}` is already used by `{}`",
                        vname.get_ref(),
                        prev.name
                    ),
                    "give every enum value its own number",
                );
            } else if let Some(prev) = variants.iter().find(|v| v.rust_name == rust_name) {
                ctx.error(
                    vname.span(),
                    format!(
                        "`{}` and `{}` both become the Rust variant `{rust_name}`",
                        prev.name,
                        vname.get_ref()
                    ),
                    "rename one so their PascalCase forms differ",
                );
            } else if unknown == UnknownPolicy::Keep && rust_name == "Unknown" {
                ctx.error(vname.span(), "a value named `UNKNOWN` collides with the `Unknown(raw)` variant of `unknown = \"keep\"`", "rename it");
            } else {
                variants.push(EnumVariant {
                    name: vname.get_ref().clone(),
                    rust_name,
                    value,
                    doc,
                });
            }
        }
        by_name.insert(name.get_ref().clone(), enums.len());
        enums.push(Enum {
            name: name.get_ref().clone(),
            doc: text(&d.doc),
            prim: scalar.prim,
            variants,
            unknown,
        });
    }
    Enums { enums, by_name }
}

/// The structs in dependency order, with a name index.
pub(crate) struct Structs {
    pub structs: Vec<Struct>,
    pub by_name: HashMap<String, usize>,
    /// Per struct: the `size` names it could not resolve itself, with the span of each `size`
    /// value and the names of the fields before it (for diagnostics where it is used).
    pub size_refs: HashMap<String, Vec<SizeRef>>,
}

/// A `size` a struct could not resolve itself: the field it names, the span of the `size`
/// value, and the names of the fields before it.
pub(crate) type SizeRef = (String, std::ops::Range<usize>, Vec<String>);

/// Rule: structs have PascalCase names and resolve in dependency order; a struct that
/// contains itself, directly or not, is an error (its size would be infinite).
pub(crate) fn lower_structs(ctx: &mut Ctx<'_>, enums: &Enums, constants: &[Constant]) -> Structs {
    let spec = ctx.spec;
    for name in spec.structs.keys() {
        check_pascal_name(ctx, name, "struct");
    }
    let mut out = Structs {
        structs: Vec::new(),
        by_name: HashMap::new(),
        size_refs: HashMap::new(),
    };
    let mut state: HashMap<String, Visit> = HashMap::new();
    for name in spec.structs.keys() {
        visit_struct(
            ctx,
            name.get_ref(),
            &mut state,
            &mut out,
            enums,
            constants,
            None,
        );
    }
    out
}

#[derive(Clone, Copy, PartialEq)]
enum Visit {
    InProgress,
    Done,
}

fn visit_struct(
    ctx: &mut Ctx<'_>,
    name: &str,
    state: &mut HashMap<String, Visit>,
    out: &mut Structs,
    enums: &Enums,
    constants: &[Constant],
    from: Option<&SStr>,
) -> Option<usize> {
    match state.get(name) {
        Some(Visit::Done) => return out.by_name.get(name).copied(),
        Some(Visit::InProgress) => {
            if let Some(r) = from {
                ctx.error(r.span(), format!("struct `{name}` contains itself"), "a struct cannot hold itself, directly or through other structs: its size would be infinite");
            }
            return None;
        }
        None => {}
    }
    let spec = ctx.spec;
    let (_, def) = spec.structs.iter().find(|(k, _)| k.get_ref() == name)?;
    state.insert(name.to_string(), Visit::InProgress);
    let d: &StructDef = def.get_ref();
    let endian = match &d.byte_order {
        Some(o) => parse_byte_order(ctx, o).unwrap_or(ctx.default_endian),
        None => ctx.default_endian,
    };
    // Resolve the structs this one refers to first, so indices point backwards.
    for f in d.fields.get_ref() {
        if let Some(ty) = &f.get_ref().ty {
            if spec.structs.keys().any(|k| k.get_ref() == ty.get_ref()) {
                visit_struct(ctx, ty.get_ref(), state, out, enums, constants, Some(ty));
            }
        }
    }
    let mut fields: Vec<Field> = Vec::new();
    let mut offset = 0usize;
    for f in d.fields.get_ref() {
        if let Some(mut field) = lower_field(ctx, f, endian, out, enums, constants, offset) {
            if f.get_ref().optional.as_ref().is_some_and(|o| *o.get_ref()) {
                field.kind = FieldKind::Optional(Box::new(field.kind));
            }
            if !field.name.is_empty() && fields.iter().any(|x| x.name == field.name) {
                let span = f
                    .get_ref()
                    .name
                    .as_ref()
                    .map(Spanned::span)
                    .unwrap_or(f.span());
                ctx.error(
                    span,
                    format!("field `{}` appears twice in struct `{name}`", field.name),
                    "rename one of the fields",
                );
                continue;
            }
            offset += field.size;
            fields.push(field);
        }
    }
    if d.fields.get_ref().is_empty() {
        ctx.error(
            d.fields.span(),
            format!("struct `{name}` has no fields"),
            "a command without payload names no struct; remove the struct or add fields",
        );
    }
    // Rule: what takes every byte left (variable bytes without `size`, a repeated group, an
    // optional field) can only be the last field; sized bytes must name an earlier integer
    // field of this struct, or be resolved by the struct that repeats this one.
    let mut min_size = 0usize;
    let mut unresolved = Vec::new();
    for (i, f) in fields.iter().enumerate() {
        let span = || {
            d.fields
                .get_ref()
                .iter()
                .find(|x| {
                    x.get_ref()
                        .name
                        .as_ref()
                        .is_some_and(|n| n.get_ref() == &f.name)
                })
                .map_or(d.fields.span(), Spanned::span)
        };
        let tail = match &f.kind {
            FieldKind::Bytes {
                size_from: None, ..
            } => Some("variable bytes"),
            FieldKind::Group { .. } => Some("a repeated group"),
            FieldKind::Optional(_) => Some("an optional field"),
            _ => None,
        };
        if let Some(what) = tail {
            if i + 1 != fields.len() {
                ctx.error(
                    span(),
                    format!("`{}` is {what} but not the last field of `{name}`", f.name),
                    "it takes every byte left in the payload: move it to the end",
                );
            }
        }
        match &f.kind {
            FieldKind::Bytes {
                size_from: Some(src),
                ..
            } => {
                let prior = fields[..i].iter().find(|x| &x.name == src);
                match prior {
                    Some(x) if matches!(&x.kind, FieldKind::Value { ty: ValueType::Scalar { scalar, scale: None }, count: None } if scalar.prim.is_unsigned()) => {}
                    Some(_) => ctx.error(span(), format!("`{src}` is not an unsigned integer field, so it cannot give the size of `{}`", f.name), "name an earlier `u8`/`u16`/`u32` field that holds the number of bytes"),
                    None => {
                        unresolved.push(src.clone());
                        let def = d.fields.get_ref().iter().find(|x| x.get_ref().name.as_ref().is_some_and(|n| n.get_ref() == &f.name));
                        let span = def.and_then(|x| x.get_ref().size.as_ref()).map_or(d.fields.span(), Spanned::span);
                        let earlier = fields[..i].iter().filter(|x| !x.name.is_empty()).map(|x| x.name.clone()).collect();
                        out.size_refs.entry(name.to_string()).or_default().push((src.clone(), span, earlier));
                    }
                }
            }
            FieldKind::Group { elem, .. } => {
                // The element's sized bytes may name fields of this struct before the group.
                for need in &out.structs[*elem].context {
                    if !fields[..i].iter().any(|x| &x.name == need) {
                        ctx.error(span(), format!("the elements of `{}` take their size from `{need}`, which `{name}` does not have before the group", f.name), format!("add an integer field `{need}` before `{}`", f.name));
                    }
                }
            }
            FieldKind::Bytes { .. } | FieldKind::Optional(_) => {}
            _ => min_size += f.size,
        }
    }
    state.insert(name.to_string(), Visit::Done);
    let index = out.structs.len();
    out.by_name.insert(name.to_string(), index);
    out.structs.push(Struct {
        name: name.to_string(),
        doc: text(&d.doc),
        fields,
        size: offset,
        min_size,
        context: unresolved,
    });
    Some(index)
}

/// Rule: a field is either `{ pad = N }` (N > 0, nothing else but `doc`) or a named value with a
/// type; `count` makes a fixed array (> 0); `bits` splits an unsigned integer into members
/// whose widths add up to at most the integer's width; `scale`/`offset` apply to integers only.
fn lower_field(
    ctx: &mut Ctx<'_>,
    f: &Spanned<FieldDef>,
    endian: Endian,
    structs: &Structs,
    enums: &Enums,
    constants: &[Constant],
    offset: usize,
) -> Option<Field> {
    let d = f.get_ref();
    if let Some(pad) = &d.pad {
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
        let size = *pad.get_ref() as usize;
        return Some(Field {
            name: String::new(),
            doc: text(&d.doc),
            offset,
            size,
            kind: FieldKind::Padding,
            unit: String::new(),
        });
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
    let Some(ty) = &d.ty else {
        ctx.error(
            f.span(),
            format!("field `{}` has no `type`", name.get_ref()),
            "add `type = \"u8\"` (or another primitive, struct or enum)",
        );
        return None;
    };
    let count = match &d.count {
        None => None,
        Some(c) => match c.get_ref() {
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
                    let help = match did_you_mean(cname, constants.iter().map(|k| k.name.as_str()))
                    {
                        Some(b) => format!("did you mean `{b}`?"),
                        None => "declare it under `[constants]`, or write a number".to_string(),
                    };
                    ctx.error(c.span(), format!("unknown constant `{cname}`"), help);
                    None
                }
            },
        },
    };
    if ty.get_ref() == "bytes" {
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
        let max = *max.get_ref() as usize;
        let size_from = d.size.as_ref().map(|s| s.get_ref().clone());
        return Some(Field {
            name: name.get_ref().clone(),
            doc: text(&d.doc),
            offset,
            size: max,
            kind: FieldKind::Bytes { max, size_from },
            unit: text(&d.unit),
        });
    }
    if let Some(sz) = &d.size {
        ctx.error(
            sz.span(),
            "`size` applies to `type = \"bytes\"` fields",
            "remove `size`",
        );
    }
    if d.repeat.as_ref().is_some_and(|r| *r.get_ref()) {
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
        let Some(max) = d.max.as_ref().filter(|m| *m.get_ref() > 0) else {
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
        let max = *max.get_ref() as usize;
        let size = structs.structs[elem].size * max;
        return Some(Field {
            name: name.get_ref().clone(),
            doc: text(&d.doc),
            offset,
            size,
            kind: FieldKind::Group { elem, max },
            unit: text(&d.unit),
        });
    }
    if let Some(max) = &d.max {
        ctx.error(
            max.span(),
            "`max` applies to `type = \"bytes\"` fields and repeated groups",
            "remove `max`, or use `count` for a fixed array",
        );
    }
    let scalar = parse_prim(ty.get_ref(), endian);
    let unit = text(&d.unit);
    let doc = text(&d.doc);
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
        let members = lower_bits(ctx, bits.get_ref(), word.prim, enums, &|m| {
            if m.length_of.is_some() || m.value.is_some() {
                Some("`length_of` and `value` apply to header bitfields only")
            } else {
                None
            }
        });
        return Some(Field {
            name: name.get_ref().clone(),
            doc,
            offset,
            size: word.prim.size(),
            kind: FieldKind::Bits { word, members },
            unit,
        });
    }
    let (elem, elem_size) = if let Some(scalar) = scalar {
        let scale = match (&d.scale, &d.offset) {
            (None, None) => None,
            (s, o) => {
                if !(scalar.prim.is_signed() || scalar.prim.is_unsigned()) {
                    let span = s
                        .as_ref()
                        .or(o.as_ref())
                        .map(Spanned::span)
                        .unwrap_or(f.span());
                    ctx.error(
                        span,
                        format!("`scale` applies to integer fields, not `{}`", ty.get_ref()),
                        "remove `scale`/`offset`, or use an integer wire type",
                    );
                    None
                } else {
                    let factor = s.as_ref().map_or(1.0, |s| *s.get_ref());
                    if factor == 0.0 || !factor.is_finite() {
                        let span = s.as_ref().map(Spanned::span).unwrap_or(f.span());
                        ctx.error(
                            span,
                            "a scale factor must be a finite number other than 0",
                            "write e.g. `scale = 0.001` for mm/s on the wire and m/s in Rust",
                        );
                    }
                    let physical = if scalar.prim.size() <= 2 {
                        Prim::F32
                    } else {
                        Prim::F64
                    };
                    let rounding = match d.rounding.as_ref().map(|r| r.get_ref().as_str()) {
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
                    };
                    let clamp = match &d.clamp {
                        None => None,
                        Some(c) => match c.get_ref().as_slice() {
                            [lo, hi] if lo.get_ref() <= hi.get_ref() => {
                                Some((*lo.get_ref(), *hi.get_ref()))
                            }
                            _ => {
                                ctx.error(
                                    c.span(),
                                    "`clamp` is not `[min, max]` with min <= max",
                                    "write the physical limits, e.g. `clamp = [-1.5, 1.5]`",
                                );
                                None
                            }
                        },
                    };
                    Some(Scale {
                        factor,
                        offset: o.as_ref().map_or(0.0, |o| *o.get_ref()),
                        physical,
                        rounding,
                        clamp,
                    })
                }
            }
        };
        (ValueType::Scalar { scalar, scale }, scalar.prim.size())
    } else if let Some(&i) = structs.by_name.get(ty.get_ref()) {
        reject_scale(ctx, d, "a struct");
        if structs.structs[i].min_size != structs.structs[i].size {
            ctx.error(ty.span(), format!("struct `{}` ends with variable bytes, so it cannot be a field of another struct", ty.get_ref()), "use it as a command's payload, or give the inner bytes a fixed `count`");
        }
        (ValueType::Struct(i), structs.structs[i].size)
    } else if let Some(&i) = enums.by_name.get(ty.get_ref()) {
        reject_scale(ctx, d, "an enum");
        let e = &enums.enums[i];
        let s = Scalar {
            prim: e.prim,
            endian,
        };
        (ValueType::Enum(i, s), e.prim.size())
    } else {
        if !ctx.spec.structs.keys().any(|k| k.get_ref() == ty.get_ref()) {
            let mut known = prim_spellings();
            known.extend(ctx.spec.structs.keys().map(|k| k.get_ref().clone()));
            known.extend(ctx.spec.enums.keys().map(|k| k.get_ref().clone()));
            unknown_type(ctx, ty, &known, "a field type");
        }
        return None;
    };
    let size = elem_size * count.unwrap_or(1);
    Some(Field {
        name: name.get_ref().clone(),
        doc,
        offset,
        size,
        kind: FieldKind::Value { ty: elem, count },
        unit,
    })
}

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
            Some(t) => match parse_prim(t.get_ref(), Endian::Little) {
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
                        if let Some(v) = e
                            .variants
                            .iter()
                            .find(|v| v.value > super::types::mask(width))
                        {
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

fn smallest_uint(width: u32) -> Prim {
    match width {
        0..=8 => Prim::U8,
        9..=16 => Prim::U16,
        17..=32 => Prim::U32,
        _ => Prim::U64,
    }
}
