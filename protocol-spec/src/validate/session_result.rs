//! Rules of a command's `result` (`COMMAND_LONG = { ..., answer = "COMMAND_ACK", result = {
//! field = "result", accept = [0], progress = [5] } }`): the field is one of the answer the
//! request expects (a header field the sender sets, or an integer field of the answer's
//! payload at a fixed position), and the values fit it, success and progress apart. Lowers
//! them to [`ir::Verdict`]s.
//!
//! Why the values of success and not those of refusal: a value the spec does not list (a
//! result a newer peer adds) must not be taken for success, and success is one value in the
//! protocols in view (MAVLink's `MAV_RESULT_ACCEPTED`, a servo's error byte 0).

use toml::Spanned;

use super::Ctx;
use super::session_match::{answer_struct, answering_command, value};
use crate::ir::{self, Exchange, Frame, PairValue, Struct, Verdict};
use crate::spec::model::SInt;

/// Every command's `result`, lowered, in command order; `None` after an error.
pub(super) fn lower_verdicts(
    ctx: &mut Ctx<'_>,
    f: &Frame,
    commands: &[ir::Command],
    structs: &[Struct],
    exchanges: &[Exchange],
    directions: &[ir::Direction],
) -> Option<Vec<Verdict>> {
    let spec = ctx.spec;
    let scope = Scope {
        f,
        commands,
        structs,
        exchanges,
        directions,
    };
    let mut out = Vec::new();
    let mut ok = true;
    for (ci, c) in commands.iter().enumerate() {
        let Some(r) = spec
            .commands
            .iter()
            .find(|(n, _)| n.get_ref() == &c.name)
            .and_then(|(_, d)| d.get_ref().result.as_ref())
        else {
            continue;
        };
        match lower_verdict(ctx, &scope, ci, r) {
            Some(v) => out.push(v),
            None => ok = false,
        }
    }
    ok.then_some(out)
}

/// What a `result` is read against: the session's frame format, the commands, their
/// payloads and exchanges.
struct Scope<'a> {
    f: &'a Frame,
    commands: &'a [ir::Command],
    structs: &'a [Struct],
    exchanges: &'a [Exchange],
    directions: &'a [ir::Direction],
}

/// One command's `result`.
fn lower_verdict(
    ctx: &mut Ctx<'_>,
    s: &Scope<'_>,
    ci: usize,
    r: &Spanned<crate::spec::model::ResultDef>,
) -> Option<Verdict> {
    let rd = r.get_ref();
    let (f, commands) = (s.f, s.commands);
    // Rule: a command that reads a result expects an answer that carries a command.
    let Some(answer) = answering_command(s.exchanges, ci) else {
        ctx.error(
            r.span(),
            format!(
                "command `{}` reads a result from an answer it does not expect",
                commands.get(ci)?.name
            ),
            "give the command an `answer`: `reply` or the command that answers",
        );
        return None;
    };
    let payload = answer_struct(commands, s.directions, answer).and_then(|si| s.structs.get(si));
    let at = value(ctx, &rd.field, f, payload, "answer")?;
    let max = max_of(f, at);
    let accept = values(ctx, &rd.accept, max, "accept");
    let progress = match &rd.progress {
        Some(p) => values(ctx, p, max, "progress"),
        None => Some(Vec::new()),
    };
    let (accept, progress) = (accept?, progress?);
    check_apart(ctx, r, &accept, &progress)?;
    Some(Verdict {
        command: ci,
        value: at,
        field: rd.field.get_ref().clone(),
        accept,
        progress,
    })
}

/// The largest value the field holds (its raw bits).
fn max_of(f: &Frame, at: PairValue) -> u64 {
    let bits = match at {
        PairValue::Header(vi) => f.values.get(vi).map_or(64, |v| v.width),
        PairValue::Payload { scalar, .. } => {
            u32::try_from(scalar.prim.size().saturating_mul(8)).unwrap_or(64)
        }
    };
    if bits >= 64 {
        u64::MAX
    } else {
        (1u64 << bits) - 1
    }
}

/// Rule: a list of values is not empty (`accept`; `progress` may be), and each value lies in
/// 0 to the field's largest.
fn values(ctx: &mut Ctx<'_>, list: &Spanned<Vec<SInt>>, max: u64, key: &str) -> Option<Vec<u64>> {
    if key == "accept" && list.get_ref().is_empty() {
        ctx.error(
            list.span(),
            "`accept` lists no value, so no answer could mean success".to_string(),
            "list the values that mean success: `accept = [0]`",
        );
        return None;
    }
    let mut out = Vec::new();
    let mut ok = true;
    for v in list.get_ref() {
        match u64::try_from(*v.get_ref()) {
            Ok(n) if n <= max => out.push(n),
            _ => {
                ctx.error(
                    v.span(),
                    format!(
                        "`{key}` value {} does not fit the field (0 to {max})",
                        v.get_ref()
                    ),
                    "write a value the answer's field can hold",
                );
                ok = false;
            }
        }
    }
    ok.then_some(out)
}

/// Rule: no value means both success and progress.
fn check_apart(
    ctx: &mut Ctx<'_>,
    r: &Spanned<crate::spec::model::ResultDef>,
    accept: &[u64],
    progress: &[u64],
) -> Option<()> {
    let Some(both) = progress.iter().find(|v| accept.contains(v)) else {
        return Some(());
    };
    let span = r
        .get_ref()
        .progress
        .as_ref()
        .map_or_else(|| r.span(), Spanned::span);
    ctx.error(
        span,
        format!("value {both} is in both `accept` and `progress`"),
        "a value means success or that the request is in progress, not both: remove it from one",
    );
    None
}
