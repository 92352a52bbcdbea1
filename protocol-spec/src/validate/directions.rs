//! Rules for directions the decoder is given (`given = true`): no header field tells them
//! apart, the decoding side knows which way its frames go (Dynamixel Protocol 1.0's instruction
//! and status packets share one layout). A given direction may carry one struct in every frame
//! in place of the dispatch key and a command's payload (a status packet has no command).

use toml::Spanned;

use super::Ctx;
use super::types::Structs;
use crate::diag::did_you_mean;
use crate::ir::{DirectionRule, Element, Frame};
use crate::spec::model::DirectionDef;

/// Rule: a given direction says `given = true` and names no header field (`field`, `in`,
/// `equals`); `message` is only for a given direction. Gives the rule and the carried struct.
pub(super) fn lower_given(
    ctx: &mut Ctx<'_>,
    n: &str,
    def: &Spanned<DirectionDef>,
    frame: &Frame,
    structs: &Structs,
) -> Option<(DirectionRule, Option<(usize, usize)>)> {
    let d = def.get_ref();
    let Some(given) = d.given.as_ref().filter(|g| *g.get_ref()) else {
        let span = d.given.as_ref().map_or_else(|| def.span(), |g| g.span());
        ctx.error(
            span,
            format!("direction `{n}` carries a `message`, but it is not given to the decoder"),
            "write `given = true`: a struct in place of the command is for a direction no header field tells",
        );
        return None;
    };
    if let Some(span) = [
        d.field.as_ref().map(Spanned::span),
        d.in_set.as_ref().map(Spanned::span),
        d.equals.as_ref().map(Spanned::span),
    ]
    .into_iter()
    .flatten()
    .next()
    {
        ctx.error(
            span,
            format!("direction `{n}` is given to the decoder, so no header field tells it"),
            "remove `field`, `in` and `equals`, or remove `given` to let the header tell the direction",
        );
        return None;
    }
    if frame.ack.is_some() {
        ctx.error(
            given.span(),
            format!(
                "frame `{}` has acknowledgements, which a given direction does not combine with",
                frame.name
            ),
            "tell the directions by a header field, or remove the frame's `ack`",
        );
        return None;
    }
    let message = match &d.message {
        Some(m) => Some(lower_message(ctx, n, m, frame, structs)?),
        None => None,
    };
    Some((DirectionRule::Given, message))
}

/// Rule: a direction's `message` names a struct; the first frame's dispatch fields are the last
/// header fields before the payload (the struct takes their bytes), the frame has no byte
/// stuffing or trailing-zero truncation and no check folding in a byte per command (such a
/// frame has no command), and the struct fits the bytes the frame carries there.
fn lower_message(
    ctx: &mut Ctx<'_>,
    n: &str,
    m: &Spanned<String>,
    frame: &Frame,
    structs: &Structs,
) -> Option<(usize, usize)> {
    let Some(&si) = structs.by_name.get(m.get_ref()) else {
        if !ctx.spec.structs.keys().any(|k| k.get_ref() == m.get_ref()) {
            let help =
                match did_you_mean(m.get_ref(), structs.structs.iter().map(|s| s.name.as_str())) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "declare it as `[structs.NAME]`".to_string(),
                };
            ctx.error(m.span(), format!("unknown struct `{}`", m.get_ref()), help);
        }
        return None;
    };
    let Some(start) = keyless_header_len(frame) else {
        ctx.error(
            m.span(),
            format!(
                "direction `{n}` carries `{}` in place of the dispatch key, but frame `{}`'s dispatch fields are not the last header fields before the payload",
                m.get_ref(),
                frame.name
            ),
            "move the dispatch fields right before the `payload` element",
        );
        return None;
    };
    if frame.stuffing.is_some() || frame.truncate_zeros {
        ctx.error(
            m.span(),
            format!(
                "frame `{}` stuffs or truncates its payloads, which a direction's `message` does not combine with",
                frame.name
            ),
            "carry the struct as the commands' payload instead",
        );
        return None;
    }
    if let Some(c) = frame.checks.iter().find(|c| c.extra.is_some()) {
        ctx.error(
            m.span(),
            format!(
                "direction `{n}` carries `{}` in place of a command, but check `{}` of frame `{}` folds in a byte per command (`extra = \"command\"`)",
                m.get_ref(),
                c.name,
                frame.name
            ),
            "a frame without a command has no byte to fold in: carry the struct as a command's payload, or remove the check's `extra`",
        );
        return None;
    }
    let key = frame.header_len - start;
    let s = &structs.structs[si];
    let (lo, hi) = (frame.payload_min + key, frame.payload_max + key);
    if s.min_size > hi || s.size < lo {
        ctx.error(
            m.span(),
            format!(
                "struct `{}` takes {} to {} bytes, but a frame `{}` carries {lo} to {hi} bytes after its header without the dispatch key",
                s.name, s.min_size, s.size, frame.name
            ),
            "fit the struct to the frame, or the frame's `payload` bounds to the struct",
        );
        return None;
    }
    Some((si, start))
}

/// The header's length without the words right before the payload that hold only dispatch
/// values, all of which they must hold; `None` when the frame has no dispatch key or a dispatch
/// value lies elsewhere.
fn keyless_header_len(frame: &Frame) -> Option<usize> {
    let payload = frame
        .elements
        .iter()
        .position(|e| matches!(e, Element::Payload))?;
    let mut len = frame.header_len;
    let mut held = 0;
    for e in frame.elements[..payload].iter().rev() {
        match e {
            Element::Word { scalar, values, .. }
                if !values.is_empty() && values.iter().all(|v| frame.dispatch.contains(v)) =>
            {
                len -= scalar.prim.size();
                held += values.len();
            }
            _ => break,
        }
    }
    (!frame.dispatch.is_empty() && held == frame.dispatch.len()).then_some(len)
}

/// Rule: the directions are all given to the decoder, or all told by header fields (a direction
/// with neither has its own error).
pub(super) fn check_given_agree(ctx: &mut Ctx<'_>) {
    let spec = ctx.spec;
    let given =
        |d: &Spanned<DirectionDef>| d.get_ref().given.is_some() || d.get_ref().message.is_some();
    let (mut given_one, mut told_one) = (None, None);
    // An empty direction is told by a header field, a rule of its own.
    for (name, def) in spec
        .directions
        .iter()
        .filter(|(_, d)| !super::directions_empty::is_empty(d))
    {
        if given(def) {
            given_one = given_one.or(Some(name));
        } else if def.get_ref().field.is_some() {
            told_one = told_one.or(Some(name));
        }
    }
    if let (Some(g), Some(t)) = (given_one, told_one) {
        ctx.error(
            t.span(),
            format!(
                "direction `{}` is told by a header field, but direction `{}` is given to the decoder",
                t.get_ref(),
                g.get_ref()
            ),
            "give both directions to the decoder (`given = true`), or tell both by header fields",
        );
    }
}
