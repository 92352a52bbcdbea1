//! Rules for what each check covers, and the positions of checks and trailers.

use toml::Spanned;

use super::super::Ctx;
use super::Kind;
use super::length::Layout;
use crate::ir::{Check, HeaderValue, Pos, Trailer};
use crate::layout::word_field;

/// Rule: a check says what it covers (`over`): a run of elements before it (`frame` means all
/// of them) or after it, never its own bytes. A check before the payload that covers only
/// header bytes is a header check; one that covers the payload or bytes after it (a header CRC
/// of the payload that follows) is verified once the frame is complete, as a check after the
/// payload is, and filled by the encoder after the bytes it covers. Places each check and sets
/// its range; answers the elements each check covers (`None` where it failed).
pub(super) fn lower_coverage(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    checks: &mut [(Check, usize)],
    ok: &mut bool,
) -> Vec<Option<(usize, usize)>> {
    let mut runs = vec![None; checks.len()];
    for ((check, ei), run) in checks.iter_mut().zip(&mut runs) {
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
            None => {
                *run = Some((0, ei.saturating_sub(1)));
                (Pos::Start(0), at)
            }
            Some((ia, ib)) => {
                if ia <= *ei && *ei <= ib {
                    ctx.error(over.map_or(0..0, Spanned::span), format!("check `{}` covers its own bytes", check.name), "a check covers the elements before it or those after it: end the range at the element before the check, or start it at the one after");
                    *ok = false;
                    continue;
                }
                // A check before the elements it covers is a header check only while they
                // are all in the header.
                if ia > *ei && ib >= lay.pi {
                    check.header = false;
                }
                *run = Some((ia, ib));
                (lay.start_of(ia), lay.end_of(ib))
            }
        };
        check.at = at;
        check.from = from;
        check.to = to;
    }
    runs
}

/// Rule: a check that covers another check's bytes is computed after it. Header checks are
/// computed first, then the others, each in spec order; only a check stored before the bytes
/// it covers can break this (a header check over a check of the payload, or a check over a
/// later one).
pub(super) fn check_coverage_order(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    checks: &[(Check, usize)],
    runs: &[Option<(usize, usize)>],
    ok: &mut bool,
) {
    // The place of a check in the order checks are computed: header checks first.
    let rank = |i: usize| (!checks[i].0.header, i);
    for (ci, run) in runs.iter().enumerate() {
        let Some((ia, ib)) = *run else { continue };
        let (check, ei) = &checks[ci];
        for (di, (other, ej)) in checks.iter().enumerate() {
            if di == ci || !(ia..=ib).contains(ej) || rank(di) < rank(ci) {
                continue;
            }
            let span = lay.els[*ei]
                .def
                .and_then(|d| d.get_ref().over.as_ref())
                .map_or(0..0, Spanned::span);
            ctx.error(
                span,
                format!(
                    "check `{}` covers check `{}`, which is computed after it",
                    check.name, other.name
                ),
                "a check covers only checks computed before it (header checks, then the others in layout order): end the range before that check",
            );
            *ok = false;
        }
    }
}

/// Rule: a frame format that may be a bare header has no check stored in its header that
/// covers the payload (a bare frame has no payload for it to cover, and is sealed and
/// verified through its header checks alone).
pub(super) fn check_bare_header(
    ctx: &mut Ctx<'_>,
    lay: &Layout<'_, '_>,
    checks: &[(Check, usize)],
    bare: bool,
    ok: &mut bool,
) {
    for (check, ei) in checks {
        if !bare || check.header || *ei > lay.pi {
            continue;
        }
        let span = lay.els[*ei].def.map_or(0..0, Spanned::span);
        ctx.error(
            span,
            format!(
                "check `{}` sits in the header and covers the payload, but the frame may be a bare header",
                check.name
            ),
            "move the check after the payload, or remove `bare_header`",
        );
        *ok = false;
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
