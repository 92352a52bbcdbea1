//! Rules for how frames are told apart: the dispatch key, acknowledgements and bare headers.

use super::super::Ctx;
use super::Kind;
use super::length::Layout;
use crate::diag::did_you_mean;
use crate::ir::{Check, HeaderValue, Length, Pos, Role};
use crate::spec::model::{FrameDef, SStr};

/// Rule: the dispatch key names header fields (before the payload) that are not the length or
/// a constant. Gives the key's value indices and marks those values as dispatch values.
pub(super) fn lower_dispatch(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    values: &mut [HeaderValue],
    ok: &mut bool,
) -> Vec<usize> {
    let mut dispatch = Vec::new();
    let Some(keys) = &def.dispatch else {
        return dispatch;
    };
    for k in keys.get_ref() {
        match values.iter().position(|v| &v.name == k.get_ref()) {
            Some(vi) if matches!(values[vi].at, Pos::End(_)) => {
                ctx.error(
                    k.span(),
                    format!(
                        "`{}` comes after the payload, so it cannot be a dispatch key",
                        k.get_ref()
                    ),
                    "dispatch on a header field",
                );
                *ok = false;
            }
            Some(vi) => match values[vi].role {
                Role::User { .. } => {
                    values[vi].role = Role::Dispatch;
                    dispatch.push(vi);
                }
                _ => {
                    ctx.error(
                        k.span(),
                        format!(
                            "`{}` cannot be a dispatch key: it is the length or a constant",
                            k.get_ref()
                        ),
                        "dispatch on a field that holds the command id",
                    );
                    *ok = false;
                }
            },
            None => {
                let help = match did_you_mean(k.get_ref(), values.iter().map(|v| v.name.as_str())) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "name a header field of this frame".to_string(),
                };
                ctx.error(
                    k.span(),
                    format!(
                        "frame `{}` has no header field `{}`",
                        fname.get_ref(),
                        k.get_ref()
                    ),
                    help,
                );
                *ok = false;
            }
        }
    }
    dispatch
}

/// Rule: an acknowledgement flag is a one-bit header value set by the sender, which equals 0 or
/// 1 in an acknowledgement; the dispatch fields, absent from acknowledgements, are the last
/// header fields before the payload. Gives the flag's value index and the bytes of an
/// acknowledgement's header, and marks the flag's role.
pub(super) fn lower_ack(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    lay: &Layout<'_, '_>,
    values: &mut [HeaderValue],
    dispatch: &[usize],
    ok: &mut bool,
) -> Option<(usize, usize)> {
    let a = def.ack.as_ref()?;
    let a_def = a.get_ref();
    let Some(vi) = values.iter().position(|v| &v.name == a_def.field.get_ref()) else {
        ctx.error(
            a_def.field.span(),
            format!(
                "frame `{}` has no header field `{}`",
                fname.get_ref(),
                a_def.field.get_ref()
            ),
            "name the one-bit flag that marks acknowledgements",
        );
        *ok = false;
        return None;
    };
    if values[vi].width != 1 || !matches!(values[vi].role, Role::User { .. }) {
        ctx.error(
            a_def.field.span(),
            format!(
                "`{}` is not a one-bit field set by the sender",
                a_def.field.get_ref()
            ),
            "the acknowledgement flag is a one-bit member of a header field's `bits`",
        );
        *ok = false;
        return None;
    }
    let equals = *a_def.equals.get_ref();
    if !(0..=1).contains(&equals) {
        ctx.error(
            a_def.equals.span(),
            "a one-bit flag equals 0 or 1",
            "write `equals = 1` (or 0)",
        );
        *ok = false;
    }
    let (ack_header_len, words) = dispatch_words_before_payload(lay, dispatch);
    if dispatch.is_empty() || words != dispatch.len() {
        ctx.error(a.span(), "acknowledgements need the dispatch fields to be the last header fields before the payload", "move the dispatch fields right before the `payload` element (acknowledgements are the frames without them)");
        *ok = false;
    }
    values[vi].role = Role::Ack(equals.clamp(0, 1) as u64);
    Some((vi, ack_header_len))
}

/// Rule: a frame format with acknowledgements has no check that folds in a byte per command
/// (`extra = "command"`): an acknowledgement carries no command, so its check would have no
/// byte to fold in, and the bytes in the key's place are data, not an id.
pub(super) fn check_ack_extra(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    checks: &[(Check, usize)],
    ok: &mut bool,
) {
    let (Some(a), Some((c, _))) = (&def.ack, checks.iter().find(|(c, _)| c.extra.is_some())) else {
        return;
    };
    ctx.error(
        a.span(),
        format!(
            "frame `{}` has acknowledgements, but its check `{}` folds in a byte per command (`extra = \"command\"`)",
            fname.get_ref(),
            c.name
        ),
        "an acknowledgement carries no command, so no byte to fold in: remove `ack`, or the check's `extra`",
    );
    *ok = false;
}

/// The header without the words right before the payload that hold only dispatch values: its
/// length, and how many dispatch values those words hold.
fn dispatch_words_before_payload(lay: &Layout<'_, '_>, dispatch: &[usize]) -> (usize, usize) {
    let mut header_len = lay.header_len;
    let mut words = 0;
    for e in lay.els[..lay.pi].iter().rev() {
        match &e.kind {
            Kind::Word(_, idx) if idx.iter().all(|v| dispatch.contains(v)) && !idx.is_empty() => {
                header_len -= e.size;
                words += idx.len();
            }
            _ => break,
        }
    }
    (header_len, words)
}

/// Rule: a bare header needs a length field (its value says the frame is the header alone).
/// Gives the bare header's length: an acknowledgement's header when the frame has them.
pub(super) fn lower_bare_header(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    length: &Length,
    header_len: usize,
    ack: Option<(usize, usize)>,
    ok: &mut bool,
) -> Option<usize> {
    let b = def.bare_header.as_ref().filter(|b| *b.get_ref())?;
    if !matches!(length, Length::Field { .. }) {
        ctx.error(
            b.span(),
            "a bare header needs a length field",
            "only a frame whose length field can say \"header only\" may be a bare header",
        );
        *ok = false;
    }
    Some(ack.map_or(header_len, |(_, n)| n))
}
