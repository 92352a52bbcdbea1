//! Rules for empty directions (`empty = true`): a direction besides `request` and `response`
//! whose frames carry the header and no payload, whatever the command (MSP's error replies,
//! `!`, which answer a command the flight controller refuses). The header field that tells it
//! is checked as any direction's (`commands.rs`); what is here is which names may be empty,
//! and what a `[session]` beside one may not ask (its frames refuse requests: a session
//! matches requests only by what they repeat).

use std::collections::HashMap;

use toml::Spanned;

use super::Ctx;
use super::names::{check_snake_name, pascal_case};
use crate::diag::did_you_mean;
use crate::ir::{Direction, DirectionRule, Frame};
use crate::spec::model::{DirectionDef, SStr, SessionDef};

/// Rule: `request` and `response` hold the commands' payloads, so neither is empty; any other
/// direction is empty (`empty = true`), has a snake_case name whose Rust form is its own, and is
/// told by a header field (no `given`, no `message`). Gives whether the direction is empty, or
/// `None` when it is refused (the error is reported).
pub(super) fn check_empty(
    ctx: &mut Ctx<'_>,
    name: &SStr,
    def: &Spanned<DirectionDef>,
) -> Option<bool> {
    let n = name.get_ref();
    let d = def.get_ref();
    let empty = d.empty.as_ref().filter(|e| *e.get_ref());
    if n == "request" || n == "response" {
        if let Some(e) = empty {
            ctx.error(
                e.span(),
                format!("direction `{n}` holds the commands' {n} payloads, so it cannot be empty"),
                "declare a direction of its own for the frames without payload, such as `error = { field = ..., equals = ..., empty = true }`",
            );
            return None;
        }
        return Some(false);
    }
    let Some(e) = empty else {
        let help = match did_you_mean(n, ["request", "response"]) {
            Some(b) => format!("did you mean `{b}`?"),
            None => "the directions are `request` and `response`; a direction whose frames carry no payload says `empty = true`".to_string(),
        };
        ctx.error(name.span(), format!("unknown direction `{n}`"), help);
        return None;
    };
    if !check_snake_name(ctx, name, "direction name") || !check_rust_name(ctx, name) {
        return None;
    }
    if let Some(span) = [
        d.given.as_ref().map(Spanned::span),
        d.message.as_ref().map(Spanned::span),
    ]
    .into_iter()
    .flatten()
    .next()
    {
        ctx.error(
            span,
            format!("empty direction `{n}` is told by a header field, so it is not given to the decoder"),
            "remove `given` and `message`, and name the field that tells it: `{ field = \"direction\", equals = 0x21, empty = true }`",
        );
        return None;
    }
    Some(e.get_ref() == &true)
}

/// Whether a direction says `empty = true` (its own rules are [`check_empty`]'s, so the rules
/// over the paired directions leave it out).
pub(super) fn is_empty(def: &Spanned<DirectionDef>) -> bool {
    def.get_ref().empty.as_ref().is_some_and(|e| *e.get_ref())
}

/// Rule: an empty direction's Rust name (its variant of `Message`) is no other direction's.
fn check_rust_name(ctx: &mut Ctx<'_>, name: &SStr) -> bool {
    let mut seen: HashMap<String, &str> = HashMap::new();
    for k in ctx.spec.directions.keys() {
        let rust = pascal_case(k.get_ref());
        if k.get_ref() == name.get_ref() {
            break;
        }
        seen.insert(rust, k.get_ref());
    }
    let rust = pascal_case(name.get_ref());
    let clash = seen.get(&rust).copied().or(["request", "response"]
        .into_iter()
        .find(|o| *o != name.get_ref() && pascal_case(o) == rust));
    if let Some(other) = clash {
        ctx.error(
            name.span(),
            format!(
                "directions `{other}` and `{}` both become the Rust name `{rust}`",
                name.get_ref()
            ),
            "rename one so their PascalCase forms differ",
        );
        return false;
    }
    true
}

/// Rule: with an empty direction and a `[session]`, a frame of the empty direction refuses
/// the open request of its command (MSP's error reply; the runtime's
/// `SessionRules::refusals`), so the session matches requests by values an error reply
/// repeats: `sequence` and `match` do not name the header field that tells an empty direction
/// (an error reply holds its own value there, never the request's), and no command is answered
/// once by each id it lists (`answers`: the error reply of one device would end the request
/// the others still answer). Gives whether it holds.
pub(super) fn check_refusals(
    ctx: &mut Ctx<'_>,
    s: &SessionDef,
    f: &Frame,
    directions: &[Direction],
) -> bool {
    let Some(empty) = directions.iter().find(|d| d.empty) else {
        return true;
    };
    let mut ok = true;
    let told: Vec<&str> = directions
        .iter()
        .filter(|d| d.empty)
        .filter_map(|d| match d.rule.in_frame(f) {
            DirectionRule::Equals { value, .. } | DirectionRule::InSet { value, .. } => {
                f.values.get(value).map(|v| v.name.as_str())
            }
            DirectionRule::Given => None,
        })
        .collect();
    let named = s.sequence.iter().map(|n| (n, "sequence")).chain(
        s.match_fields
            .iter()
            .flat_map(|m| m.get_ref().iter().map(|n| (n, "match"))),
    );
    for (n, key) in named {
        if told.contains(&n.get_ref().as_str()) {
            ctx.error(
                n.span(),
                format!(
                    "`{key}` names `{}`, the header field that tells the empty direction `{}`: an error reply holds its own value there, so it never repeats the request's",
                    n.get_ref(),
                    empty.name
                ),
                "match answers by other header fields; the error reply of a request is the frame of the empty direction that carries its command",
            );
            ok = false;
        }
    }
    let spec = ctx.spec;
    for (name, c) in &spec.commands {
        if let Some(a) = &c.get_ref().answers {
            ctx.error(
                a.span(),
                format!(
                    "command `{}` is answered once by each id it lists, and the empty direction `{}` refuses a request by one frame: one device's error reply would end the request the others still answer",
                    name.get_ref(),
                    empty.name
                ),
                "remove `answers` and send the request to each device, or remove the empty direction",
            );
            ok = false;
        }
    }
    ok
}
