//! Rules of a command's `answers` (`SYNC_READ = { ..., answers = { each = "ids", by = "id" } }`):
//! the request lists the ids that answer it, once each, in its payload (`each`: a repeated
//! `u8` field, or a `u8` field of repeated elements of a fixed size, at a fixed position), and
//! each answer names its sender in a header field (`by`) of at most 8 bits. Lowers them to
//! [`ir::Fanout`]s.
//!
//! Why one-byte ids: the requester keeps the ids still to answer as a fixed 256-bit set per
//! open request (no heap), and the buses in view (Dynamixel, Feetech) address at most 253
//! devices with a byte.

use toml::Spanned;

use super::Ctx;
use super::session_match::{answering_command, request_struct};
use crate::diag::did_you_mean;
use crate::ir::{self, Exchange, Fanout, FieldKind, Frame, Prim, Role, Scalar, Struct, ValueType};
use crate::spec::model::{AnswersDef, SStr};

/// Every command's `answers`, lowered, in command order; `None` after an error.
pub(super) fn lower_fanouts(
    ctx: &mut Ctx<'_>,
    f: &Frame,
    commands: &[ir::Command],
    structs: &[Struct],
    exchanges: &[Exchange],
) -> Option<Vec<Fanout>> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    let mut ok = true;
    for (ci, c) in commands.iter().enumerate() {
        let Some(a) = spec
            .commands
            .iter()
            .find(|(n, _)| n.get_ref() == &c.name)
            .and_then(|(_, d)| d.get_ref().answers.as_ref())
        else {
            continue;
        };
        match lower_fanout(ctx, f, commands, structs, exchanges, ci, a) {
            Some(fo) => out.push(fo),
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// One command's `answers`.
fn lower_fanout(
    ctx: &mut Ctx<'_>,
    f: &Frame,
    commands: &[ir::Command],
    structs: &[Struct],
    exchanges: &[Exchange],
    ci: usize,
    a: &Spanned<AnswersDef>,
) -> Option<Fanout> {
    let name = &commands.get(ci)?.name;
    // Rule: a command answered by several frames expects an answer that carries a command.
    if answering_command(exchanges, ci).is_none() {
        ctx.error(
            a.span(),
            format!("command `{name}` lists the ids that answer it, but expects no answer"),
            "give the command an `answer`: the command that answers (`\"STATUS\"`) or `reply`",
        );
        return None;
    }
    let ad = a.get_ref();
    let request = request_struct(commands, ci).and_then(|si| structs.get(si));
    let listed = listed_ids(ctx, &ad.each, request, structs, name);
    let by = sender_field(ctx, &ad.by, f);
    let ((first, stride), by) = (listed?, by?);
    Some(Fanout {
        command: ci,
        first,
        stride,
        by,
        names: (ad.each.get_ref().clone(), ad.by.get_ref().clone()),
    })
}

/// Rule: `each` names a repeated `u8` field of the request's payload (`ids`), or a `u8` field
/// of its repeated elements of a fixed size (`servos.id`), after fields of a fixed size only;
/// returns the first id's offset and the bytes from one to the next.
fn listed_ids(
    ctx: &mut Ctx<'_>,
    each: &SStr,
    request: Option<&Struct>,
    structs: &[Struct],
    command: &str,
) -> Option<(usize, usize)> {
    let path = each.get_ref();
    let (outer, inner) = match path.split_once('.') {
        Some((o, i)) => (o, Some(i)),
        None => (path.as_str(), None),
    };
    let Some(s) = request else {
        ctx.error(
            each.span(),
            format!("command `{command}` has no request payload to list ids in"),
            "give the command a payload whose last field lists the ids (`repeat = true`)",
        );
        return None;
    };
    let Some(fi) = s.fields.iter().position(|fl| fl.name == outer) else {
        let help = match did_you_mean(outer, s.fields.iter().map(|fl| fl.name.as_str())) {
            Some(b) => format!("did you mean `{b}`?"),
            None => format!("name a repeated field of `{}`", s.name),
        };
        ctx.error(
            each.span(),
            format!("the request `{}` has no field `{outer}`", s.name),
            help,
        );
        return None;
    };
    let field = s.fields.get(fi)?;
    let fixed_before = s.fields.iter().take(fi).all(|b| fixed_size(&b.kind));
    let found = match (&field.kind, inner) {
        (FieldKind::Array { ty, size_from, .. }, None) if is_u8(ty) && size_from.is_none() => {
            Ok((field.offset, 1))
        }
        (FieldKind::Group { elem, .. }, Some(member)) => {
            element_id(structs.get(*elem)?, member).map(|(at, size)| (field.offset + at, size))
        }
        (_, None) => Err(format!(
            "field `{outer}` of `{}` is not a `u8` repeated to the end of the payload",
            s.name
        )),
        (_, Some(_)) => Err(format!(
            "field `{outer}` of `{}` is not a repeated struct",
            s.name
        )),
    };
    let problem = match found {
        Ok(_) if !fixed_before => Err(format!(
            "field `{outer}` of `{}` follows a field of variable size, so its ids have no fixed place",
            s.name
        )),
        other => other,
    };
    problem.map_err(|message| {
        ctx.error(
            each.span(),
            message,
            "list the ids as `{ name = \"ids\", type = \"u8\", repeat = true }`, or name a `u8` of repeated elements: `servos.id`",
        );
    })
    .ok()
}

/// The offset of `member` in the repeated element `e`, and the element's size: `member` is a
/// `u8` field and `e` has a fixed size.
fn element_id(e: &Struct, member: &str) -> Result<(usize, usize), String> {
    let Some(m) = e.fields.iter().find(|fl| fl.name == member) else {
        let hint = did_you_mean(member, e.fields.iter().map(|fl| fl.name.as_str()))
            .map_or_else(String::new, |b| format!(" (did you mean `{b}`?)"));
        return Err(format!(
            "the element `{}` has no field `{member}`{hint}",
            e.name
        ));
    };
    let is_id = matches!(&m.kind, FieldKind::Value { ty, count: None } if is_u8(ty));
    if !is_id {
        return Err(format!("field `{member}` of `{}` is not a `u8`", e.name));
    }
    if e.min_size != e.size || e.size == 0 {
        return Err(format!("the element `{}` has no fixed size", e.name));
    }
    Ok((m.offset, e.size))
}

/// True for an unscaled `u8`.
fn is_u8(ty: &ValueType) -> bool {
    matches!(
        ty,
        ValueType::Scalar {
            scalar: Scalar { prim: Prim::U8, .. },
            scale: None,
        }
    )
}

/// True for a field whose size does not depend on the payload.
fn fixed_size(kind: &FieldKind) -> bool {
    matches!(
        kind,
        FieldKind::Padding
            | FieldKind::Value { .. }
            | FieldKind::Bits { .. }
            | FieldKind::BitStream { .. }
            | FieldKind::Packed { .. }
    )
}

/// Rule: `by` is a header field the sender sets, of at most 8 bits.
fn sender_field(ctx: &mut Ctx<'_>, by: &SStr, f: &Frame) -> Option<usize> {
    let name = by.get_ref();
    let Some(vi) = f.values.iter().position(|v| &v.name == name) else {
        let help = match did_you_mean(name, f.values.iter().map(|v| v.name.as_str())) {
            Some(b) => format!("did you mean `{b}`?"),
            None => format!(
                "name the header field of frame `{}` that holds the device's id",
                f.name
            ),
        };
        ctx.error(
            by.span(),
            format!("frame `{}` has no header field `{name}`", f.name),
            help,
        );
        return None;
    };
    let v = f.values.get(vi)?;
    let problem = if !matches!(v.role, Role::User { .. }) {
        Some("is computed by the codec (a length, constant, dispatch or ack field)")
    } else if v.width > 8 {
        Some("is wider than 8 bits (ids that answer a request are one byte)")
    } else {
        None
    };
    if let Some(problem) = problem {
        ctx.error(
            by.span(),
            format!("header field `{name}` {problem}"),
            "name a one-byte header field the sender sets: the answering device's id",
        );
        return None;
    }
    Some(vi)
}
