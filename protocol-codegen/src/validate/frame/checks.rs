//! Rules for what each check covers, and the positions of checks and trailers.

use toml::Spanned;

use super::super::Ctx;
use super::Kind;
use super::length::Layout;
use crate::ir::{Check, Pos, Trailer};

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
