//! Rules for what each check covers, and the positions of checks and trailers.

use toml::Spanned;

use super::super::Ctx;
use super::Kind;
use super::length::Layout;
use crate::ir::{Check, HeaderValue, Pos, Trailer};
use crate::layout::word_field;

/// Rule: a check says what it covers (`over`); it covers bytes before it (`frame` means all of
/// them), never its own bytes, and a check inside the header covers only header bytes. Places
/// each check and sets its range.
pub(super) fn lower_coverage(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    checks: &mut [(Check, usize)],
    ok: &mut bool,
) {
    for (check, ei) in checks {
        let Some(edef) = lay.els[*ei].def else {
            continue;
        };
        let at = lay.start_of(*ei);
        let over = edef.get_ref().over.as_ref();
        let range = match over {
            None => {
                ctx.error(edef.span(), format!("check `{}` does not say what it covers", check.name), "add `over = \"frame\"` (every byte before the check) or `over = \"first..last\"`");
                *ok = false;
                continue;
            }
            Some(s) => match lay.parse_range(ctx, s) {
                None => {
                    *ok = false;
                    continue;
                }
                Some(r) => r,
            },
        };
        let (from, to) = match range {
            None => (Pos::Start(0), at),
            Some((ia, ib)) => {
                if ia <= *ei && *ei <= ib {
                    ctx.error(over.map_or(0..0, Spanned::span), format!("check `{}` covers its own bytes", check.name), "a check covers bytes before it: end the range at the element before the check");
                    *ok = false;
                    continue;
                }
                if ib > *ei {
                    ctx.error(
                        over.map_or(0..0, Spanned::span),
                        format!("check `{}` covers bytes after it", check.name),
                        "cover only elements before the check",
                    );
                    *ok = false;
                    continue;
                }
                (lay.start_of(ia), lay.end_of(ib))
            }
        };
        check.at = at;
        check.from = from;
        check.to = to;
    }
}

/// Each trailer at its element's position.
pub(super) fn place_trailers(lay: &Layout<'_, '_>, trailers: &mut [Trailer]) {
    for (i, e) in lay.els.iter().enumerate() {
        if let Kind::Trailer(ti) = e.kind {
            trailers[ti].at = lay.start_of(i);
        }
    }
}

/// Rule: a check that folds in a per-command byte is in a frame format with one dispatch
/// field, and covers it (the key is read from the covered bytes), from a position counted
/// from the frame start. Sets where the key sits, from the first covered byte.
pub(super) fn lower_extra_keys(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    checks: &mut [(Check, usize)],
    values: &[HeaderValue],
    dispatch: &[usize],
    ok: &mut bool,
) {
    for (check, ei) in checks {
        let Some(extra) = &mut check.extra else {
            continue;
        };
        let span = lay.els[*ei]
            .def
            .and_then(|d| d.get_ref().extra.as_ref())
            .map_or(0..0, Spanned::span);
        let &[value] = dispatch else {
            ctx.error(span, format!("check `{}` folds in a byte per command, but its frame has {} dispatch fields", check.name, dispatch.len()), "a per-command byte is picked by one dispatch field: give the frame `dispatch = [\"FIELD\"]` with one field");
            *ok = false;
            continue;
        };
        let v = &values[value];
        let mut field = word_field(v);
        let covered = match (check.from, v.at, check.to) {
            (Pos::Start(from), Pos::Start(at), to) => {
                let inside = at >= from
                    && match to {
                        Pos::Start(to) => at + usize::from(field.size) <= to,
                        Pos::End(_) => true,
                    };
                inside.then(|| at - from)
            }
            _ => None,
        };
        let Some(offset) = covered else {
            ctx.error(span, format!("check `{}` folds in a byte per command, but does not cover the dispatch field `{}`", check.name, v.name), "the byte is picked by the command id the check covers: extend `over` to cover the dispatch field");
            *ok = false;
            continue;
        };
        field.at = Pos::Start(offset);
        extra.value = value;
        extra.key = field;
    }
}
