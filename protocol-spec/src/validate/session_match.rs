//! Rules of a command's `match` (`COMMAND_LONG = { ..., match = { command = "command", sysid =
//! "target_system" } }`): each key names a field of the command's request, each value the field
//! of its answer that holds the same value; a field is a header field the sender sets or a
//! fixed-position integer field of the payload. Lowers them to [`ir::Pair`]s.

use super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{
    self, AnswerKind, Exchange, FieldKind, Frame, Pair, PairValue, Role, Struct, ValueType,
};
use crate::spec::model::SStr;

/// The most values an answer repeats under other names (the runtime's
/// `SessionRules::MAX_PAIRS`).
const MAX_PAIRS: usize = protocol_runtime::session::SessionRules::MAX_PAIRS;

/// The payloads a `match` reads: the request's struct, and the answer's.
struct Sides<'a> {
    request: Option<&'a Struct>,
    answer: Option<&'a Struct>,
}

/// Every command's `match`, lowered, in command order; `None` after an error.
pub(super) fn lower_pairs(
    ctx: &mut Ctx<'_>,
    f: &Frame,
    commands: &[ir::Command],
    structs: &[Struct],
    exchanges: &[Exchange],
    directions: &[ir::Direction],
) -> Option<Vec<Pair>> {
    let spec = ctx.spec;
    let mut pairs = Vec::new();
    let mut ok = true;
    for (ci, c) in commands.iter().enumerate() {
        let Some(m) = spec
            .commands
            .iter()
            .find(|(n, _)| n.get_ref() == &c.name)
            .and_then(|(_, d)| d.get_ref().match_fields.as_ref())
        else {
            continue;
        };
        // Rule: a command that matches its answer expects one that carries a command.
        let answer = match answering_command(exchanges, ci) {
            Some(k) => k,
            None => {
                ctx.error(
                    m.span(),
                    format!("command `{}` matches an answer it does not expect", c.name),
                    "give the command an `answer`: `reply` or the command that answers",
                );
                ok = false;
                continue;
            }
        };
        // Rule: at most `MAX_PAIRS` values per command.
        if m.get_ref().len() > MAX_PAIRS {
            ctx.error(
                m.span(),
                format!(
                    "`match` names {} fields; an answer repeats at most {MAX_PAIRS}",
                    m.get_ref().len()
                ),
                "keep the fields that identify a request",
            );
            ok = false;
            continue;
        }
        let sides = Sides {
            request: request_struct(commands, ci).and_then(|si| structs.get(si)),
            answer: answer_struct(commands, directions, answer).and_then(|si| structs.get(si)),
        };
        for (from_name, to_name) in m.get_ref() {
            let from = value(ctx, from_name, f, sides.request, "request");
            let to = value(ctx, to_name, f, sides.answer, "answer");
            match (from, to) {
                (Some(from), Some(to)) => pairs.push(Pair {
                    command: ci,
                    from,
                    to,
                    names: (from_name.get_ref().clone(), to_name.get_ref().clone()),
                }),
                _ => ok = false,
            }
        }
    }
    ok.then_some(pairs)
}

/// The request's struct of command `ci` (index into the structs): its first direction's, or
/// its only payload's.
pub(super) fn request_struct(commands: &[ir::Command], ci: usize) -> Option<usize> {
    commands.get(ci)?.payloads.first().copied().flatten()
}

/// The struct of an answer that command `answer` carries (index into the structs): the
/// response direction's struct when it carries one in place of a command, else the command's
/// payload in the response direction (its only payload without directions).
pub(super) fn answer_struct(
    commands: &[ir::Command],
    directions: &[ir::Direction],
    answer: usize,
) -> Option<usize> {
    if let Some((si, _)) = directions.get(1).and_then(|d| d.message) {
        return Some(si);
    }
    let c = commands.get(answer)?;
    c.payloads
        .get(usize::from(!directions.is_empty()))
        .copied()
        .flatten()
}

/// The command whose frame answers a request of command `ci` (itself for a reply or a
/// direction's message), when the request expects one that carries a command.
pub(super) fn answering_command(exchanges: &[Exchange], ci: usize) -> Option<usize> {
    match exchanges.get(ci).map(|e| e.answer) {
        Some(AnswerKind::Reply | AnswerKind::Message) => Some(ci),
        Some(AnswerKind::Command(k)) => Some(k),
        _ => None,
    }
}

/// Rule: a matched field is a header field the sender sets or a fixed-position integer field
/// of the payload (`side` says whose), and not both.
pub(super) fn value(
    ctx: &mut Ctx<'_>,
    n: &SStr,
    f: &Frame,
    payload: Option<&Struct>,
    side: &str,
) -> Option<PairValue> {
    let name = n.get_ref();
    let header = f.values.iter().position(|v| &v.name == name);
    let field = payload.and_then(|s| s.fields.iter().position(|fl| &fl.name == name));
    match (header, field, payload) {
        (Some(_), Some(_), Some(s)) => {
            ctx.error(
                n.span(),
                format!(
                    "`{name}` names both a header field of frame `{}` and a field of `{}`",
                    f.name, s.name
                ),
                "a matched field must be one or the other: rename one of them",
            );
            None
        }
        (Some(vi), _, _) => header_value(ctx, n, f, vi),
        (None, Some(fi), Some(s)) => payload_value(ctx, n, f, s, fi),
        _ => {
            let payload_names = payload.into_iter().flat_map(|s| s.fields.iter());
            let names = f
                .values
                .iter()
                .map(|v| v.name.as_str())
                .chain(payload_names.map(|fl| fl.name.as_str()));
            let help = match did_you_mean(name, names) {
                Some(b) => format!("did you mean `{b}`?"),
                None => format!(
                    "name a header field of frame `{}` or a field of the {side}'s payload",
                    f.name
                ),
            };
            ctx.error(n.span(), format!("the {side} has no field `{name}`"), help);
            None
        }
    }
}

/// Rule: a header field that a `match` reads is one the sender sets.
fn header_value(ctx: &mut Ctx<'_>, n: &SStr, f: &Frame, vi: usize) -> Option<PairValue> {
    if matches!(f.values.get(vi)?.role, Role::User { .. }) {
        return Some(PairValue::Header(vi));
    }
    ctx.error(
        n.span(),
        format!(
            "header field `{}` is computed by the codec (a length, constant, dispatch or ack field), so it identifies no request",
            n.get_ref()
        ),
        "name a header field the sender sets",
    );
    None
}

/// Rule: a payload field that a `match` reads is an integer (or an enum's integer) at a fixed
/// position (no field of variable size before it), in a format without byte stuffing.
fn payload_value(
    ctx: &mut Ctx<'_>,
    n: &SStr,
    f: &Frame,
    s: &Struct,
    fi: usize,
) -> Option<PairValue> {
    let field = s.fields.get(fi)?;
    let scalar = match &field.kind {
        FieldKind::Value {
            ty:
                ValueType::Scalar {
                    scalar,
                    scale: None,
                },
            count: None,
        }
        | FieldKind::Value {
            ty: ValueType::Enum(_, scalar),
            count: None,
        } if !scalar.prim.is_float() => Some(*scalar),
        _ => None,
    };
    let fixed = s.fields.iter().take(fi).all(|b| {
        matches!(
            b.kind,
            FieldKind::Padding
                | FieldKind::Value { .. }
                | FieldKind::Bits { .. }
                | FieldKind::BitStream { .. }
                | FieldKind::Packed { .. }
        )
    });
    let problem = if scalar.is_none() {
        Some("is not an unscaled integer")
    } else if !fixed {
        Some("follows a field of variable size, so its position is not fixed")
    } else if f.stuffing.is_some() {
        Some("lies in a payload that frame stuffs, which a session does not unstuff")
    } else {
        None
    };
    if let Some(problem) = problem {
        ctx.error(
            n.span(),
            format!("field `{}` of `{}` {problem}", n.get_ref(), s.name),
            "match an integer field at a fixed position, or a header field",
        );
        return None;
    }
    Some(PairValue::Payload {
        offset: field.offset,
        scalar: scalar?,
    })
}
