//! Rules for payload structs as a whole: dependency order and cycles, unique field names, and
//! which fields may take the bytes left in a payload.

use std::collections::HashMap;

use toml::Spanned;

use super::super::names::{check_pascal_name, parse_byte_order};
use super::super::{Ctx, text};
use super::Enums;
use super::carried::lower_carries;
use super::checks::{lower_check_field, resolve_check_runs};
use super::fields::lower_field;
use super::mask::{check_mask_array, lower_when};
use crate::ir::{ByteOrder, Constant, Field, FieldKind, Struct, ValueType};
use crate::spec::model::{SStr, StructDef};

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
    // A derive's nested payloads of the user's crate: their own `Payload` impls know their size.
    for f in ctx.foreign.iter().filter(|f| f.repr.is_none()) {
        out.by_name.insert(f.path.clone(), out.structs.len());
        out.structs.push(Struct {
            name: f.path.clone(),
            doc: String::new(),
            fields: Vec::new(),
            size: 0,
            min_size: 0,
            context: Vec::new(),
            base_size: None,
            carries: Vec::new(),
            foreign: true,
        });
    }
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

/// Lower struct `name` after the structs it refers to (reached through `from`, the reference
/// that names it). Gives its index in `out`.
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
    let fields = lower_fields(ctx, name, d, endian, out, enums, constants);
    let (min_size, unresolved) = check_tail_fields(ctx, name, d, &fields, out);
    let base_size = lower_base_size(ctx, name, d, &fields);
    let carries = lower_carries(ctx, d, &fields);
    state.insert(name.to_string(), Visit::Done);
    let index = out.structs.len();
    out.by_name.insert(name.to_string(), index);
    out.structs.push(Struct {
        name: name.to_string(),
        doc: text(&d.doc),
        size: fields.iter().map(|f| f.size).sum(),
        fields,
        min_size,
        context: unresolved,
        foreign: false,
        base_size,
        carries,
    });
    Some(index)
}

/// Rule: a struct has fields, each named once. Gives the fields at their offsets.
fn lower_fields(
    ctx: &mut Ctx<'_>,
    name: &str,
    d: &StructDef,
    endian: ByteOrder,
    out: &Structs,
    enums: &Enums,
    constants: &[Constant],
) -> Vec<Field> {
    let mut fields: Vec<Field> = Vec::new();
    let mut offset = 0usize;
    for (k, f) in d.fields.get_ref().iter().enumerate() {
        let lowered = match &f.get_ref().name {
            Some(n) if f.get_ref().check.is_some() => {
                lower_check_field(ctx, f, n, name, endian, offset)
            }
            _ => lower_field(ctx, f, endian, out, enums, constants, offset),
        };
        if let Some(mut field) = lowered {
            if f.get_ref().optional.as_ref().is_some_and(|o| *o.get_ref()) {
                field.kind = FieldKind::Optional(Box::new(field.kind));
            }
            let later = &d.fields.get_ref()[k + 1..];
            if let Some(w) = &f.get_ref().when {
                match lower_when(ctx, f, w, &field, &fields, later) {
                    Some(kind) => field.kind = kind,
                    None => continue,
                }
            }
            if let Some(m) = &f.get_ref().mask {
                check_mask_array(ctx, m.span(), &field, &fields, later);
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
    check_member_names(ctx, name, d, &fields);
    resolve_check_runs(ctx, name, d, &mut fields);
    if d.fields.get_ref().is_empty() {
        ctx.error(
            d.fields.span(),
            format!("struct `{name}` has no fields"),
            "a command without payload names no struct; remove the struct or add fields",
        );
    }
    fields
}

/// Rule: a bit member is a field of the generated struct, so its name is no other field's
/// and no other bitfield's member's.
fn check_member_names(ctx: &mut Ctx<'_>, name: &str, d: &StructDef, fields: &[Field]) {
    let rust_names = |f: &Field| -> Vec<String> {
        match &f.kind {
            FieldKind::Padding => Vec::new(),
            kind if kind.members().is_some() => kind
                .members()
                .unwrap_or_default()
                .iter()
                .map(|m| m.name.clone())
                .collect(),
            _ => vec![f.name.clone()],
        }
    };
    for (i, f) in fields.iter().enumerate() {
        let Some(members) = f.kind.members() else {
            continue;
        };
        for m in members {
            let clash = fields
                .iter()
                .enumerate()
                .any(|(j, other)| j != i && rust_names(other).contains(&m.name));
            if clash {
                let span = d
                    .fields
                    .get_ref()
                    .iter()
                    .find(|x| {
                        x.get_ref()
                            .name
                            .as_ref()
                            .is_some_and(|n| n.get_ref() == &f.name)
                    })
                    .map_or(d.fields.span(), Spanned::span);
                ctx.error(
                    span,
                    format!(
                        "bit member `{}` of `{}` is also a field of struct `{name}`",
                        m.name, f.name
                    ),
                    "rename one: the members of a bitfield are fields of the struct",
                );
            }
        }
    }
}

/// Rule: what takes every byte left (variable bytes without `size`, a repeated group, an
/// optional field) can only be the last field; sized bytes must name an earlier integer
/// field of this struct, or be resolved by the struct that repeats this one. Gives the
/// struct's smallest size and the `size` names left to the struct that repeats it.
fn check_tail_fields(
    ctx: &mut Ctx<'_>,
    name: &str,
    d: &StructDef,
    fields: &[Field],
    out: &mut Structs,
) -> (usize, Vec<String>) {
    let mut min_size = 0usize;
    let mut unresolved = Vec::new();
    for (i, f) in fields.iter().enumerate() {
        let def_of = || {
            d.fields.get_ref().iter().find(|x| {
                x.get_ref()
                    .name
                    .as_ref()
                    .is_some_and(|n| n.get_ref() == &f.name)
            })
        };
        let span = || def_of().map_or(d.fields.span(), Spanned::span);
        let tail = match &f.kind {
            FieldKind::Bytes {
                size_from: None,
                text: false,
                ..
            } => Some("variable bytes"),
            FieldKind::Bytes {
                size_from: None,
                text: true,
                ..
            } => Some("text to the end of the payload"),
            FieldKind::Array {
                size_from: None, ..
            } => Some("a variable-length array"),
            FieldKind::Group { .. } => Some("a repeated group"),
            FieldKind::Optional(_) => Some("an optional field"),
            _ => None,
        };
        // Variable bytes may leave the bytes of the checks after them.
        let checks_after = fields[i + 1..]
            .iter()
            .all(|x| matches!(x.kind, FieldKind::Check(_)));
        let bytes = matches!(f.kind, FieldKind::Bytes { .. });
        if let Some(what) = tail {
            if i + 1 != fields.len() && !(bytes && checks_after) {
                let help = if bytes {
                    "it takes every byte left in the payload but the checks after it: move it to the end, before the checks only"
                } else {
                    "it takes every byte left in the payload: move it to the end"
                };
                ctx.error(
                    span(),
                    format!("`{}` is {what} but not the last field of `{name}`", f.name),
                    help,
                );
            }
        }
        match &f.kind {
            // A mask is a field of this struct, checked where the field is lowered.
            FieldKind::Array { by_mask: true, .. } => {}
            FieldKind::Bytes {
                size_from: Some(src),
                ..
            }
            | FieldKind::Array {
                size_from: Some(src),
                ..
            } => {
                let prior = fields[..i].iter().find(|x| &x.name == src);
                match prior {
                    Some(x) if matches!(&x.kind, FieldKind::Value { ty: ValueType::Scalar { scalar, scale: None }, count: None } if scalar.prim.is_unsigned()) => {}
                    Some(_) => ctx.error(span(), format!("`{src}` is not an unsigned integer field, so it cannot give the size of `{}`", f.name), "name an earlier `u8`/`u16`/`u32` field that holds the number of bytes or elements"),
                    None => {
                        unresolved.push(src.clone());
                        let span = def_of().and_then(|x| x.get_ref().size.as_ref()).map_or(d.fields.span(), Spanned::span);
                        let earlier = fields[..i].iter().filter(|x| !x.name.is_empty()).map(|x| x.name.clone()).collect();
                        out.size_refs.entry(name.to_string()).or_default().push((src.clone(), span, earlier));
                    }
                }
            }
            FieldKind::Group { elem, .. } => {
                let inner = &out.structs[*elem];
                if inner
                    .fields
                    .iter()
                    .any(|x| matches!(x.kind, FieldKind::Check(_) | FieldKind::NulText { .. }))
                {
                    ctx.error(span(), format!("the elements of `{}` hold a check or NUL-terminated text, which a repeated element cannot", f.name), format!("move them out of `{}`", inner.name));
                }
                let masked = |x: &Field| {
                    matches!(
                        x.kind,
                        FieldKind::When { .. } | FieldKind::Array { by_mask: true, .. }
                    )
                };
                if inner.fields.iter().any(masked) {
                    ctx.error(span(), format!("the elements of `{}` hold fields a mask announces (`when` or `mask`), which a repeated element cannot", f.name), format!("move them out of `{}`", inner.name));
                }
                // The element's sized bytes may name fields of this struct before the group.
                for need in &out.structs[*elem].context {
                    if !fields[..i].iter().any(|x| &x.name == need) {
                        ctx.error(span(), format!("the elements of `{}` take their size from `{need}`, which `{name}` does not have before the group", f.name), format!("add an integer field `{need}` before `{}`", f.name));
                    }
                }
            }
            FieldKind::Bytes { .. }
            | FieldKind::Array { .. }
            | FieldKind::Optional(_)
            | FieldKind::When { .. } => {}
            // The empty text: its NUL.
            FieldKind::NulText { .. } => min_size += 1,
            _ => min_size += f.size,
        }
    }
    (min_size, unresolved)
}

/// Rule: extension fields (`extension = true`) end a struct: every field after the first one
/// is an extension too, and the struct has a fixed size (a format without extensions carries
/// the bytes before them). Gives the size of the fields before the first extension field.
fn lower_base_size(
    ctx: &mut Ctx<'_>,
    name: &str,
    d: &StructDef,
    fields: &[Field],
) -> Option<usize> {
    let defs = d.fields.get_ref();
    let is_ext = |f: &Spanned<crate::spec::model::FieldDef>| {
        f.get_ref().extension.as_ref().is_some_and(|e| *e.get_ref())
    };
    let first = defs.iter().position(is_ext)?;
    let first_name = defs[first]
        .get_ref()
        .name
        .as_ref()
        .map_or("", |n| n.get_ref().as_str());
    let mut ok = true;
    for f in defs.iter().skip(first + 1).filter(|f| !is_ext(f)) {
        let field = f
            .get_ref()
            .name
            .as_ref()
            .map_or("padding", |n| n.get_ref().as_str());
        ctx.error(
            f.span(),
            format!("field `{field}` of struct `{name}` follows the extension field `{first_name}` but is not one"),
            "extension fields end a struct: mark it `extension = true`, or move it before the first extension field",
        );
        ok = false;
    }
    let variable = fields.iter().any(|f| {
        matches!(
            f.kind,
            FieldKind::Bytes { .. }
                | FieldKind::Group { .. }
                | FieldKind::Optional(_)
                | FieldKind::When { .. }
                | FieldKind::Array { by_mask: true, .. }
        )
    });
    if variable {
        ctx.error(
            defs[first].span(),
            format!("struct `{name}` has extension fields but no fixed size"),
            "a format without extensions carries the bytes before them: give the struct a fixed size (no `bytes`, `repeat` or `optional` field)",
        );
        ok = false;
    }
    // The fields before the first extension field, as lowered (each def lowers to at most one).
    let base = defs
        .iter()
        .take(first)
        .filter_map(|def| match def.get_ref().name.as_ref() {
            Some(n) => fields
                .iter()
                .find(|f| &f.name == n.get_ref())
                .map(|f| f.size),
            None => def
                .get_ref()
                .pad
                .as_ref()
                .map(|p| usize::try_from(*p.get_ref()).unwrap_or(0)),
        })
        .sum();
    ok.then_some(base)
}
