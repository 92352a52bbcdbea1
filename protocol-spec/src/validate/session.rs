//! Rules of `[session]` and the per-command `answer`, `timeout_ms` and `retries` (`match` is
//! [`super::session_match`]'s, `result` [`super::session_result`]'s, `answers`
//! [`super::session_answers`]'s, `periodic`
//! [`super::session_periodic`]'s): the names
//! they use (a frame format, commands, header fields) exist and fit what they are used for,
//! the numbers are in range. Lowers the table to [`ir::Session`].

use std::ops::Range;

use toml::Spanned;

use super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{self, AnswerKind, Exchange, Frame, PacketKind, Role};
use crate::spec::model::{SInt, SStr, SessionDef};

/// The help for an unknown command where only a command may stand.
const NAME_ONE: &str = "name a command of `[commands]`";
/// The timeout of a request without `timeout_ms`, in milliseconds.
const DEFAULT_TIMEOUT_MS: u32 = 100;
/// The longest timeout or watchdog period, in milliseconds (an hour).
const MAX_MS: i64 = 3_600_000;
/// The largest backoff factor.
const MAX_BACKOFF: i64 = 8;
/// The most header values `match` names (the runtime's `SessionRules::MAX_ECHO`).
const MAX_MATCH: usize = protocol_runtime::session::SessionRules::MAX_ECHO;

/// Lowers `[session]`; without it, rule: no command says `answer`, `timeout_ms` or `retries`.
pub(super) fn lower_session(
    ctx: &mut Ctx<'_>,
    frames: &[Frame],
    commands: &[ir::Command],
    structs: &[ir::Struct],
    directions: &[ir::Direction],
) -> Option<ir::Session> {
    let spec = ctx.spec;
    let Some(def) = spec.session.as_ref() else {
        check_no_command_keys(ctx);
        return None;
    };
    let s = def.get_ref();
    let fi = lower_frame(ctx, s, def.span(), frames)?;
    let f = frames.get(fi)?;
    if !super::directions_empty::check_refusals(ctx, s, f, directions) {
        return None;
    }
    // An answer direction that carries one struct in place of a command.
    let message = directions.get(1).is_some_and(|d| d.message.is_some());
    let answer = match &s.answer {
        Some(a) => lower_answer(ctx, a, f, commands, message)?,
        None => AnswerKind::None,
    };
    let timeout = s
        .timeout_ms
        .as_ref()
        .map_or(Some(DEFAULT_TIMEOUT_MS), |t| ms(ctx, t, "timeout_ms"))?;
    let retries = s.retries.as_ref().map_or(Some(0), |r| retries(ctx, r))?;
    let backoff = s.backoff.as_ref().map_or(Some(1), |b| backoff(ctx, b))?;
    let default = Exchange {
        command: 0,
        answer,
        timeout_ms: timeout,
        retries,
        backoff,
    };
    let exchanges = lower_exchanges(ctx, default, f, commands, message);
    let sequence = s.sequence.as_ref().and_then(|n| header_value(ctx, n, f));
    let echo = lower_match(ctx, s, f);
    let swap = lower_addresses(ctx, s, f);
    let nack = s
        .nack
        .as_ref()
        .and_then(|n| command(ctx, n, commands, NAME_ONE));
    let handshake = lower_handshake(ctx, s, commands, &exchanges);
    let watchdog = s.watchdog.as_ref().and_then(|w| {
        let wd = w.get_ref();
        Some(ir::Watchdog {
            command: command(ctx, &wd.command, commands, NAME_ONE)?,
            period_ms: ms(ctx, &wd.period_ms, "period_ms")?,
            doc: super::text(&wd.doc),
        })
    });
    let modes = s.modes.as_ref().and_then(|m| lower_modes(ctx, m, f));
    let pairs = exchanges
        .as_ref()
        .and_then(|e| super::session_match::lower_pairs(ctx, f, commands, structs, e, directions));
    let periodic = super::session_periodic::lower_periodic(ctx, s.periodic.as_ref(), commands);
    let verdicts = exchanges.as_ref().and_then(|e| {
        super::session_result::lower_verdicts(ctx, f, commands, structs, e, directions)
    });
    let fanouts = exchanges
        .as_ref()
        .and_then(|e| super::session_answers::lower_fanouts(ctx, f, commands, structs, e));
    Some(ir::Session {
        frame: fi,
        default,
        doc: super::text(&s.doc),
        sequence,
        echo: echo?,
        swap: swap?,
        nack,
        handshake: handshake?,
        watchdog,
        modes,
        exchanges: exchanges?,
        pairs: pairs?,
        verdicts: verdicts?,
        periodic: periodic?,
        fanouts: fanouts?,
    })
}

/// Rule: a command's `answer`, `timeout_ms` and `retries` need a `[session]` table (which says
/// the frame format and how answers are matched).
fn check_no_command_keys(ctx: &mut Ctx<'_>) {
    let spec = ctx.spec;
    for (name, c) in &spec.commands {
        let c = c.get_ref();
        let spans = [
            c.answer.as_ref().map(Spanned::span),
            c.timeout_ms.as_ref().map(Spanned::span),
            c.retries.as_ref().map(Spanned::span),
            c.match_fields.as_ref().map(Spanned::span),
            c.result.as_ref().map(Spanned::span),
            c.answers.as_ref().map(Spanned::span),
        ];
        if let Some(span) = spans.into_iter().flatten().next() {
            ctx.error(
                span,
                format!(
                    "command `{}` says how it is answered, but the spec has no `[session]`",
                    name.get_ref()
                ),
                "add a `[session]` table (at least `[session]` alone: its defaults apply)",
            );
        }
    }
}

/// Rule: `frame` names a frame format that carries the commands (default: the first format).
fn lower_frame(
    ctx: &mut Ctx<'_>,
    s: &SessionDef,
    table: Range<usize>,
    frames: &[Frame],
) -> Option<usize> {
    let (fi, span) = match &s.frame {
        Some(n) => {
            let Some(fi) = frames.iter().position(|f| &f.name == n.get_ref()) else {
                let help = match did_you_mean(n.get_ref(), frames.iter().map(|f| f.name.as_str())) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "name a `[frames.NAME]` table".to_string(),
                };
                ctx.error(n.span(), format!("unknown frame `{}`", n.get_ref()), help);
                return None;
            };
            (fi, n.span())
        }
        None => (0, table),
    };
    let f = frames.get(fi)?;
    if !matches!(
        f.packet,
        PacketKind::Command | PacketKind::Commands | PacketKind::Can
    ) {
        ctx.error(
            span,
            format!("frame `{}` carries no commands, so no conversation", f.name),
            "name a frame format with `dispatch` in the session's `frame`",
        );
        return None;
    }
    Some(fi)
}

/// Rule: an answer is `"none"`, `"reply"`, `"ack"` (on a format with acknowledgements),
/// `"message"` (in a spec whose response direction carries one struct) or the name of a
/// command.
fn lower_answer(
    ctx: &mut Ctx<'_>,
    a: &SStr,
    f: &Frame,
    commands: &[ir::Command],
    message: bool,
) -> Option<AnswerKind> {
    match a.get_ref().as_str() {
        "none" => Some(AnswerKind::None),
        "reply" => Some(AnswerKind::Reply),
        "message" if message => Some(AnswerKind::Message),
        "message" => {
            ctx.error(
                a.span(),
                "`message` answers, but no response direction carries one struct".to_string(),
                "give `[directions] response` a `message`, or answer with `reply` or a command",
            );
            None
        }
        "ack" if f.ack.is_some() => Some(AnswerKind::Ack),
        "ack" => {
            ctx.error(
                a.span(),
                format!(
                    "`ack` answers, but frame `{}` has no acknowledgements",
                    f.name
                ),
                "give the frame `ack = { field, equals }`, or answer with `reply` or a command",
            );
            None
        }
        _ => command(
            ctx,
            a,
            commands,
            "an answer is `none`, `reply`, `ack`, `message` or a command's name",
        )
        .map(AnswerKind::Command),
    }
}

/// Rule: a command name names a command (did you mean; else `otherwise`).
pub(super) fn command(
    ctx: &mut Ctx<'_>,
    n: &SStr,
    commands: &[ir::Command],
    otherwise: &str,
) -> Option<usize> {
    if let Some(i) = commands.iter().position(|c| &c.name == n.get_ref()) {
        return Some(i);
    }
    let help = match did_you_mean(n.get_ref(), commands.iter().map(|c| c.name.as_str())) {
        Some(b) => format!("did you mean `{b}`?"),
        None => otherwise.to_string(),
    };
    ctx.error(n.span(), format!("unknown command `{}`", n.get_ref()), help);
    None
}

/// Rule: a milliseconds value is 1 to an hour.
pub(super) fn ms(ctx: &mut Ctx<'_>, v: &SInt, key: &str) -> Option<u32> {
    let n = *v.get_ref();
    if (1..=MAX_MS).contains(&n) {
        return u32::try_from(n).ok();
    }
    ctx.error(
        v.span(),
        format!("`{key}` is {n}, outside 1 to {MAX_MS} milliseconds"),
        "write a positive number of milliseconds",
    );
    None
}

/// Rule: `retries` is 0 to 255.
fn retries(ctx: &mut Ctx<'_>, v: &SInt) -> Option<u8> {
    let n = *v.get_ref();
    u8::try_from(n).ok().or_else(|| {
        ctx.error(
            v.span(),
            format!("`retries` is {n}, outside 0 to 255"),
            "write how many times a request is sent again",
        );
        None
    })
}

/// Rule: `backoff` is 1 (a fixed wait) to 8.
fn backoff(ctx: &mut Ctx<'_>, v: &SInt) -> Option<u8> {
    let n = *v.get_ref();
    if (1..=MAX_BACKOFF).contains(&n) {
        return u8::try_from(n).ok();
    }
    ctx.error(
        v.span(),
        format!("`backoff` is {n}, outside 1 to {MAX_BACKOFF}"),
        "write the factor each retry's wait grows by: 1 for a fixed wait, 2 to double it",
    );
    None
}

/// Each command's exchange: the session's defaults, overridden by its own keys.
fn lower_exchanges(
    ctx: &mut Ctx<'_>,
    default: Exchange,
    f: &Frame,
    commands: &[ir::Command],
    message: bool,
) -> Option<Vec<Exchange>> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    let mut ok = true;
    for (ci, c) in commands.iter().enumerate() {
        let mut e = Exchange {
            command: ci,
            ..default
        };
        let def = spec
            .commands
            .iter()
            .find(|(n, _)| n.get_ref() == &c.name)
            .map(|(_, d)| d.get_ref());
        if let Some(d) = def {
            if let Some(a) = &d.answer {
                e.answer = lower_answer(ctx, a, f, commands, message).unwrap_or_else(|| {
                    ok = false;
                    e.answer
                });
            }
            if let Some(t) = &d.timeout_ms {
                e.timeout_ms = ms(ctx, t, "timeout_ms").unwrap_or_else(|| {
                    ok = false;
                    e.timeout_ms
                });
            }
            if let Some(r) = &d.retries {
                e.retries = retries(ctx, r).unwrap_or_else(|| {
                    ok = false;
                    e.retries
                });
            }
        }
        out.push(e);
    }
    ok.then_some(out)
}

/// Rule: a field the session reads is a header value of its frame format that the user sets
/// (not the length, a constant, a dispatch field or the acknowledgement flag).
fn header_value(ctx: &mut Ctx<'_>, n: &SStr, f: &Frame) -> Option<usize> {
    let Some(vi) = f.values.iter().position(|v| &v.name == n.get_ref()) else {
        let help = match did_you_mean(n.get_ref(), f.values.iter().map(|v| v.name.as_str())) {
            Some(b) => format!("did you mean `{b}`?"),
            None => format!("name a header field of frame `{}`", f.name),
        };
        ctx.error(
            n.span(),
            format!("frame `{}` has no header field `{}`", f.name, n.get_ref()),
            help,
        );
        return None;
    };
    if !matches!(f.values.get(vi)?.role, Role::User { .. }) {
        ctx.error(
            n.span(),
            format!(
                "header field `{}` is computed by the codec (a length, constant, dispatch or ack field), so a session cannot set it",
                n.get_ref()
            ),
            "name a header field the sender sets",
        );
        return None;
    }
    Some(vi)
}

/// Rule: `match` names at most two header values.
fn lower_match(ctx: &mut Ctx<'_>, s: &SessionDef, f: &Frame) -> Option<Vec<usize>> {
    let Some(m) = &s.match_fields else {
        return Some(Vec::new());
    };
    if m.get_ref().len() > MAX_MATCH {
        ctx.error(
            m.span(),
            format!(
                "`match` names {} header fields; an answer repeats at most {MAX_MATCH} (and the numbered field)",
                m.get_ref().len()
            ),
            "keep the fields that identify a request",
        );
        return None;
    }
    let values: Vec<Option<usize>> = m
        .get_ref()
        .iter()
        .map(|n| header_value(ctx, n, f))
        .collect();
    values.into_iter().collect()
}

/// Rule: `addresses` names two header values, the sender's and the receiver's.
fn lower_addresses(ctx: &mut Ctx<'_>, s: &SessionDef, f: &Frame) -> Option<Option<(usize, usize)>> {
    let Some(a) = &s.addresses else {
        return Some(None);
    };
    let [from, to] = a.get_ref().as_slice() else {
        ctx.error(
            a.span(),
            format!(
                "`addresses` names {} header field{}, not two",
                a.get_ref().len(),
                if a.get_ref().len() == 1 { "" } else { "s" }
            ),
            "write `addresses = [\"sender\", \"receiver\"]`: an answer swaps them",
        );
        return None;
    };
    let (from, to) = (header_value(ctx, from, f), header_value(ctx, to, f));
    Some(Some((from?, to?)))
}

/// Rule: the handshake names a command whose request expects an answer.
fn lower_handshake(
    ctx: &mut Ctx<'_>,
    s: &SessionDef,
    commands: &[ir::Command],
    exchanges: &Option<Vec<Exchange>>,
) -> Option<Option<usize>> {
    let Some(h) = &s.handshake else {
        return Some(None);
    };
    let ci = command(ctx, h, commands, NAME_ONE)?;
    let answered = exchanges
        .as_ref()
        .and_then(|e| e.get(ci))
        .is_none_or(|e| e.answer != AnswerKind::None);
    if !answered {
        ctx.error(
            h.span(),
            format!(
                "the handshake `{}` expects no answer, so it can never be done",
                h.get_ref()
            ),
            "give the command an `answer` (or the session a default `answer`)",
        );
        return None;
    }
    Some(Some(ci))
}

/// Rule: `modes` names a header value, and each range is `[first, last]` with first ≤ last,
/// within the field.
fn lower_modes(
    ctx: &mut Ctx<'_>,
    m: &Spanned<crate::spec::model::ModesDef>,
    f: &Frame,
) -> Option<ir::Modes> {
    let md = m.get_ref();
    let value = header_value(ctx, &md.field, f)?;
    let width = f.values.get(value)?.width;
    let max = if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    };
    let mut range = |r: &Option<Spanned<Vec<SInt>>>| -> Option<Option<(u64, u64)>> {
        let Some(r) = r else { return Some(None) };
        let pair = match r.get_ref().as_slice() {
            [a, b] => u64::try_from(*a.get_ref())
                .ok()
                .zip(u64::try_from(*b.get_ref()).ok()),
            _ => None,
        };
        match pair {
            Some((a, b)) if a <= b && b <= max => Some(Some((a, b))),
            _ => {
                ctx.error(
                    r.span(),
                    format!("a mode's values are `[first, last]`, first ≤ last ≤ {max}"),
                    "write the inclusive range of the field's values",
                );
                None
            }
        }
    };
    let none = range(&md.none);
    let once = range(&md.once);
    Some(ir::Modes {
        value,
        none: none?,
        once: once?,
    })
}
