//! Rules of `[registers]` (a device's register map) and of a command's `registers` (the
//! request fields that select a run of it, and the bytes that hold the values): names,
//! addresses, types and access of the registers, that no two overlap, and that every field a
//! command names exists and is of the kind its role needs. Lowers them to [`ir::RegisterMap`].

use std::collections::HashSet;

use toml::Spanned;

use super::names::{check_snake_name, parse_byte_order, parse_prim, prim_spellings, unknown_type};
use super::registers_each::{RunFields, lower_run_fields, member, run_struct};
use super::session_match::{answer_struct, answering_command, request_struct};
use super::{Ctx, text};
use crate::diag::did_you_mean;
use crate::ir::{self, Access, FieldKind, Register, Select, Struct, ValueType};
use crate::spec::model::{FieldDef, RegisterDef, SStr, SelectDef};

/// Lowers `[registers]` and the commands' `registers`; without the table, rule: no command
/// selects registers.
pub(super) fn lower_registers(
    ctx: &mut Ctx<'_>,
    commands: &[ir::Command],
    structs: &[Struct],
    directions: &[ir::Direction],
    session: Option<&ir::Session>,
) -> Option<ir::RegisterMap> {
    let spec = ctx.spec;
    let selecting = spec
        .commands
        .iter()
        .filter_map(|(n, d)| Some((n, d.get_ref().registers.as_ref()?)));
    let Some(def) = spec.registers.as_ref() else {
        for (name, sel) in selecting {
            ctx.error(
                sel.span(),
                format!(
                    "command `{}` selects registers, but the spec has no `[registers]`",
                    name.get_ref()
                ),
                "declare the device's register map in a `[registers]` table",
            );
        }
        return None;
    };
    let d = def.get_ref();
    let order = match &d.byte_order {
        Some(o) => parse_byte_order(ctx, o).unwrap_or(ctx.default_endian),
        None => ctx.default_endian,
    };
    let mut registers = lower_map(ctx, &d.map, order);
    registers.sort_by_key(|(r, _)| r.address);
    check_overlaps(ctx, &registers);
    let registers: Vec<Register> = registers.into_iter().map(|(r, _)| r).collect();
    let exchanges = session.map_or(&[][..], |s| s.exchanges.as_slice());
    let sides = Sides {
        commands,
        structs,
        directions,
        exchanges,
        registers: &registers,
    };
    let mut selects = Vec::new();
    for (ci, c) in commands.iter().enumerate() {
        let Some(sel) = spec
            .commands
            .iter()
            .find(|(n, _)| n.get_ref() == &c.name)
            .and_then(|(_, d)| d.get_ref().registers.as_ref())
        else {
            continue;
        };
        if let Some(s) = lower_select(ctx, &sides, ci, sel) {
            selects.push(s);
        }
    }
    Some(ir::RegisterMap {
        doc: text(&d.doc),
        registers,
        selects,
    })
}

/// Rule: `map` lists at least one register; each has a snake_case name of its own (not `map`,
/// the generated list's name), an address from 0 to 2^32 - 1, a primitive type (scaled as a struct field is) and an access
/// of `r`, `w` or `rw`. Gives each lowered register with the spans of its entry's type and
/// address, in spec order.
fn lower_map(
    ctx: &mut Ctx<'_>,
    map: &Spanned<Vec<Spanned<RegisterDef>>>,
    order: ir::ByteOrder,
) -> Vec<(Register, RegisterSpans)> {
    if map.get_ref().is_empty() {
        ctx.error(
            map.span(),
            "`[registers]` lists no registers",
            "add entries such as `{ name = \"led\", address = 25, type = \"u8\" }`, or remove the table",
        );
    }
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for entry in map.get_ref() {
        let r = entry.get_ref();
        let named = check_snake_name(ctx, &r.name, "register name");
        if named && r.name.get_ref() == "map" {
            ctx.error(
                r.name.span(),
                "register name `map` is taken: the generated `registers::MAP` lists the map",
                "name the register after what it holds, e.g. `map_select`",
            );
        } else if named && !seen.insert(r.name.get_ref().clone()) {
            ctx.error(
                r.name.span(),
                format!("register `{}` is declared twice", r.name.get_ref()),
                "give each register a name of its own",
            );
        }
        let address = u32::try_from(*r.address.get_ref()).ok();
        if address.is_none() {
            ctx.error(
                r.address.span(),
                format!(
                    "register address {} is outside 0 to 4294967295",
                    r.address.get_ref()
                ),
                "write the register's address as the device's manual gives it",
            );
        }
        let ty = lower_type(ctx, entry, order);
        let access = lower_access(ctx, r.access.as_ref());
        if let (Some(address), Some(ty)) = (address, ty) {
            let size = match &ty {
                ValueType::Scalar { scalar, .. } => scalar.prim.size(),
                _ => 0,
            };
            let spans = RegisterSpans {
                address: r.address.span(),
                ty: r.ty.span(),
            };
            let register = Register {
                name: r.name.get_ref().clone(),
                address,
                size,
                ty,
                unit: text(&r.unit),
                access,
                doc: text(&r.doc),
            };
            out.push((register, spans));
        }
    }
    out
}

/// Where a register's entry writes its address and type.
struct RegisterSpans {
    address: std::ops::Range<usize>,
    ty: std::ops::Range<usize>,
}

/// Rule: a register's type is a primitive (not a struct, an enum or text); `scale` and
/// `offset` follow the rules of a struct field's.
fn lower_type(
    ctx: &mut Ctx<'_>,
    entry: &Spanned<RegisterDef>,
    order: ir::ByteOrder,
) -> Option<ValueType> {
    let r = entry.get_ref();
    let Some(scalar) = parse_prim(r.ty.get_ref(), order) else {
        let spec = ctx.spec;
        let named = spec.structs.keys().chain(spec.enums.keys());
        if named.into_iter().any(|k| k.get_ref() == r.ty.get_ref()) {
            ctx.error(
                r.ty.span(),
                format!("register type `{}` is not a primitive", r.ty.get_ref()),
                "a register holds one value: give it a primitive type (`u8`, `i16`, `u32be`, ...)",
            );
        } else {
            unknown_type(ctx, &r.ty, &prim_spellings(), "a register type");
        }
        return None;
    };
    // A register's scaling is a struct field's: the one rule reads it from a field's keys.
    let as_field = FieldDef {
        scale: r.scale.clone(),
        offset: r.offset.clone(),
        ..FieldDef::default()
    };
    let as_field = Spanned::new(entry.span(), as_field);
    let scale = super::types::lower_scale(ctx, &as_field, r.ty.get_ref(), scalar);
    Some(ValueType::Scalar { scalar, scale })
}

/// Rule: `access` is `"r"`, `"w"` or `"rw"` (the default).
fn lower_access(ctx: &mut Ctx<'_>, access: Option<&SStr>) -> Access {
    match access.map(|a| a.get_ref().as_str()) {
        None | Some("rw") => Access::ReadWrite,
        Some("r") => Access::Read,
        Some("w") => Access::Write,
        Some(other) => {
            let span = access.map(Spanned::span).unwrap_or_default();
            ctx.error(
                span,
                format!("unknown register access `{other}`"),
                "write `\"r\"` (read only), `\"w\"` (write only) or `\"rw\"` (both)",
            );
            Access::ReadWrite
        }
    }
}

/// Rule: registers do not overlap: no two share an address, and each one's bytes end at or
/// before the next register's address. `registers` is in address order.
fn check_overlaps(ctx: &mut Ctx<'_>, registers: &[(Register, RegisterSpans)]) {
    for pair in registers.windows(2) {
        let [(a, a_spans), (b, b_spans)] = pair else {
            continue;
        };
        let gap = u64::from(b.address.saturating_sub(a.address));
        if gap == 0 {
            ctx.error(
                b_spans.address.clone(),
                format!(
                    "registers `{}` and `{}` share address {}",
                    a.name, b.name, b.address
                ),
                "give each register the address of its first byte",
            );
        } else if a.size as u64 > gap {
            ctx.error(
                a_spans.ty.clone(),
                format!(
                    "register `{}` is {} bytes at address {}, but `{}` starts {gap} bytes after it",
                    a.name, a.size, a.address, b.name
                ),
                format!(
                    "give `{}` a type of at most {gap} bytes, or correct one of the addresses",
                    a.name
                ),
            );
        }
    }
}

/// What a command's `registers` is checked against.
struct Sides<'a> {
    commands: &'a [ir::Command],
    structs: &'a [Struct],
    directions: &'a [ir::Direction],
    exchanges: &'a [ir::Exchange],
    registers: &'a [Register],
}

/// Rule: a command that selects registers has a request struct; `address` (and `length`)
/// name its unscaled integer fields (or its group element's, [`lower_run_fields`]), `data`
/// its `bytes` field, `answer` the `bytes` field of the answer the request expects; at least
/// one of `data` and `answer` is given, and `length` only with `answer`.
fn lower_select(
    ctx: &mut Ctx<'_>,
    sides: &Sides<'_>,
    ci: usize,
    sel: &Spanned<SelectDef>,
) -> Option<Select> {
    let name = &sides.commands.get(ci)?.name;
    let s = sel.get_ref();
    let Some(request) = request_struct(sides.commands, ci) else {
        ctx.error(
            sel.span(),
            format!("command `{name}` has no request payload whose fields select registers"),
            "give the command a request struct with the address field",
        );
        return None;
    };
    let rs = sides.structs.get(request)?;
    let run = lower_run_fields(ctx, name, s, rs)?;
    let run_struct = run_struct(&run, rs, sides.structs)?;
    let side = match run {
        RunFields::Request => "request",
        RunFields::PerDevice(_) => "group element",
    };
    let address = int_field(ctx, &member(&s.address), run_struct, side);
    if let Some(field) = address {
        check_reach(ctx, &s.address, field, sides.registers);
    }
    let length = s
        .length
        .as_ref()
        .map(|n| int_field(ctx, &member(n), run_struct, side).map(|f| f.name.clone()));
    let data = s.data.as_ref().map(|n| bytes_field(ctx, n, rs, "request"));
    let answer = s.answer.as_ref().map(|n| answer_field(ctx, sides, ci, n));
    if s.data.is_none() && s.answer.is_none() {
        ctx.error(
            sel.span(),
            "`registers` names neither `data` (the request's values) nor `answer` (the answer's)",
            "add `answer = \"FIELD\"` for a read, or `data = \"FIELD\"` for a write",
        );
        return None;
    }
    if let (Some(l), None) = (&s.length, &s.answer) {
        ctx.error(
            l.span(),
            "`length` counts the bytes an answer carries, but `registers` names no `answer`",
            "remove `length` (a write's data says its own length), or name the answer's field",
        );
        return None;
    }
    Some(Select {
        command: ci,
        request,
        address: address?.name.clone(),
        length: resolved(length)?,
        data: resolved(data)?,
        answer: resolved(answer)?,
        each: match run {
            RunFields::Request => None,
            RunFields::PerDevice(p) => Some(p),
        },
    })
}

/// An optional key's lowered value: `None` when the key was given but failed to lower.
fn resolved<T>(key: Option<Option<T>>) -> Option<Option<T>> {
    match key {
        Some(None) => None,
        Some(Some(v)) => Some(Some(v)),
        None => Some(None),
    }
}

/// The field of `s` that `n` names, or an error with the nearest name.
fn field<'a>(ctx: &mut Ctx<'_>, n: &SStr, s: &'a Struct, side: &str) -> Option<&'a ir::Field> {
    let found = s.fields.iter().find(|f| &f.name == n.get_ref());
    if found.is_none() {
        let names = s.fields.iter().map(|f| f.name.as_str());
        let help = match did_you_mean(n.get_ref(), names) {
            Some(b) => format!("did you mean `{b}`?"),
            None => format!("name a field of the {side}'s struct `{}`", s.name),
        };
        ctx.error(
            n.span(),
            format!("the {side} `{}` has no field `{}`", s.name, n.get_ref()),
            help,
        );
    }
    found
}

/// Rule: a field that holds an address or a length is an unscaled integer.
fn int_field<'a>(ctx: &mut Ctx<'_>, n: &SStr, s: &'a Struct, side: &str) -> Option<&'a ir::Field> {
    let f = field(ctx, n, s, side)?;
    match &f.kind {
        FieldKind::Value {
            ty:
                ValueType::Scalar {
                    scalar,
                    scale: None,
                },
            count: None,
        } if scalar.prim.is_signed() || scalar.prim.is_unsigned() => Some(f),
        _ => {
            ctx.error(
                n.span(),
                format!(
                    "field `{}` of `{}` is not an unscaled integer, so it selects no registers",
                    f.name, s.name
                ),
                format!("name an integer field of the {side} (a `u8`, `u16`, ... without `scale`)"),
            );
            None
        }
    }
}

/// Rule: the address field's type holds the address of every register.
fn check_reach(ctx: &mut Ctx<'_>, n: &SStr, f: &ir::Field, registers: &[Register]) {
    let (
        Some(last),
        FieldKind::Value {
            ty: ValueType::Scalar { scalar, .. },
            ..
        },
    ) = (registers.last(), &f.kind)
    else {
        return;
    };
    let bits = scalar.prim.size() * 8 - usize::from(scalar.prim.is_signed());
    let max = if bits >= 32 {
        u64::from(u32::MAX)
    } else {
        (1u64 << bits) - 1
    };
    if u64::from(last.address) > max {
        ctx.error(
            n.span(),
            format!(
                "field `{}` (`{}`) cannot hold address {} of register `{}`",
                f.name,
                scalar.prim.spec_name(),
                last.address,
                last.name
            ),
            "widen the address field, or correct the register's address",
        );
    }
}

/// Rule: a field that holds register values is `bytes`.
fn bytes_field(ctx: &mut Ctx<'_>, n: &SStr, s: &Struct, side: &str) -> Option<String> {
    let f = field(ctx, n, s, side)?;
    if matches!(f.kind, FieldKind::Bytes { .. }) {
        return Some(f.name.clone());
    }
    ctx.error(
        n.span(),
        format!(
            "field `{}` of `{}` is not `bytes`, so it holds no register values",
            f.name, s.name
        ),
        format!("name the {side}'s `bytes` field that holds the registers' bytes"),
    );
    None
}

/// Rule: `answer` names a `bytes` field of the answer the command's request expects (its
/// `[session]` answer, which carries a command or the response direction's struct).
fn answer_field(
    ctx: &mut Ctx<'_>,
    sides: &Sides<'_>,
    ci: usize,
    n: &SStr,
) -> Option<(usize, String)> {
    let name = &sides.commands.get(ci)?.name;
    let answer = answering_command(sides.exchanges, ci)
        .and_then(|k| answer_struct(sides.commands, sides.directions, k));
    let Some(si) = answer else {
        ctx.error(
            n.span(),
            format!("command `{name}` selects registers in an answer it does not expect"),
            "declare the answer in `[session]` (or the command's `answer`): it carries the values",
        );
        return None;
    };
    let s = sides.structs.get(si)?;
    Some((si, bytes_field(ctx, n, s, "answer")?))
}
