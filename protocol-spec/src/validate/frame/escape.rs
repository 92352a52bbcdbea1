//! Rules for a frame format's byte escaping (`escape`): the flag and escape bytes, the
//! reserved bytes and their substitutes (the XOR form or a table), and the frame around them
//! (opened and closed by the flag, alone on its link, not stuffed as well).

use std::collections::BTreeSet;

use toml::Spanned;

use super::super::Ctx;
use super::{El, Kind};
use crate::ir::{Escape, Trailer, Transport};
use crate::spec::model::{EscapeDef, FrameDef, SInt};

/// Lowers `escape`, running every rule; `None` (with the errors recorded) if one fails.
pub(super) fn lower_escape(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    els: &[El<'_>],
    trailers: &[Trailer],
    transport: Transport,
    ok: &mut bool,
) -> Option<Escape> {
    let spanned = def.escape.as_ref()?;
    let d = spanned.get_ref();
    let before = ctx.diags.len();
    let flag = byte(ctx, &d.flag);
    let esc = byte(ctx, &d.escape);
    let (pairs, xor) = lower_pairs(ctx, spanned);
    let lowered = match (flag, esc, pairs) {
        (Some(flag), Some(escape), Some(pairs)) => {
            check_flag_and_escape(ctx, d, flag, escape, &pairs);
            Some(Escape {
                flag,
                escape,
                pairs,
                xor,
            })
        }
        _ => None,
    };
    // (A frame that cannot be escaped at all is not also told where its flags go.)
    if check_setting(ctx, def, spanned, transport) {
        if let Some(e) = &lowered {
            check_delimiters(ctx, def, e.flag, els, trailers);
        }
    }
    if ctx.diags.len() != before {
        *ok = false;
        return None;
    }
    lowered
}

/// Rule: the flag, the escape byte, `xor` and every listed value are bytes.
fn byte(ctx: &mut Ctx<'_>, v: &SInt) -> Option<u8> {
    match u8::try_from(*v.get_ref()) {
        Ok(b) => Some(b),
        Err(_) => {
            ctx.error(
                v.span(),
                format!("{} is not a byte", v.get_ref()),
                "use a value from 0x00 to 0xFF",
            );
            None
        }
    }
}

/// Rule: the substitutes are given either as `xor` with `bytes` or as a `map` of pairs
/// `[reserved, substitute]`; the reserved bytes are distinct, and so are the substitutes.
fn lower_pairs(
    ctx: &mut Ctx<'_>,
    spanned: &Spanned<EscapeDef>,
) -> (Option<Vec<[u8; 2]>>, Option<u8>) {
    let d = spanned.get_ref();
    let pairs = match (&d.xor, &d.bytes, &d.map) {
        (Some(x), Some(bytes), None) => {
            let mask = byte(ctx, x);
            let listed: Vec<Option<u8>> = bytes.get_ref().iter().map(|b| byte(ctx, b)).collect();
            if bytes.get_ref().is_empty() {
                ctx.error(
                    bytes.span(),
                    "the escaped bytes are empty",
                    "list the reserved bytes, the flag and the escape byte among them, e.g. `bytes = [0x7E, 0x7D]`",
                );
            }
            let mask = mask.filter(|m| {
                if *m == 0 {
                    ctx.error(
                        x.span(),
                        "`xor = 0` leaves every reserved byte as it is",
                        "use the link's mask, e.g. `xor = 0x20` (HDLC, PPP)",
                    );
                }
                *m != 0
            });
            let listed: Option<Vec<u8>> = listed.into_iter().collect();
            return (
                mask.zip(listed)
                    .map(|(m, l)| l.iter().map(|b| [*b, b ^ m]).collect())
                    .and_then(|p| distinct(ctx, bytes.span(), p)),
                mask,
            );
        }
        (None, None, Some(map)) => lower_map(ctx, map),
        (Some(_), None, None) | (None, Some(_), None) => {
            ctx.error(
                spanned.span(),
                "`xor` and `bytes` go together",
                "give both: `xor = 0x20, bytes = [0x7E, 0x7D]` (each listed byte goes as the escape byte and the byte XOR `xor`)",
            );
            None
        }
        (None, None, None) => {
            ctx.error(
                spanned.span(),
                "the escape has no substitutes",
                "add `xor = 0x20, bytes = [...]` (HDLC, PPP) or `map = [[0xC0, 0xDC], [0xDB, 0xDD]]` (SLIP)",
            );
            None
        }
        (_, _, Some(map)) => {
            ctx.error(
                map.span(),
                "`map` replaces `xor` and `bytes`",
                "keep either `map` or `xor` with `bytes`",
            );
            None
        }
    };
    (pairs, None)
}

/// The pairs of a `map`, each `[reserved, substitute]`.
fn lower_map(ctx: &mut Ctx<'_>, map: &Spanned<Vec<Spanned<Vec<SInt>>>>) -> Option<Vec<[u8; 2]>> {
    if map.get_ref().is_empty() {
        ctx.error(
            map.span(),
            "the escape map is empty",
            "list each reserved byte with its substitute, e.g. `map = [[0xC0, 0xDC], [0xDB, 0xDD]]`",
        );
        return None;
    }
    let mut pairs = Vec::new();
    let mut whole = true;
    for pair in map.get_ref() {
        match pair.get_ref().as_slice() {
            [reserved, sub] => match (byte(ctx, reserved), byte(ctx, sub)) {
                (Some(r), Some(s)) => pairs.push([r, s]),
                _ => whole = false,
            },
            _ => {
                ctx.error(
                    pair.span(),
                    "an escape map entry is a pair `[reserved, substitute]`",
                    "write two bytes, e.g. `[0xC0, 0xDC]`",
                );
                whole = false;
            }
        }
    }
    if !whole {
        return None;
    }
    distinct(ctx, map.span(), pairs)
}

/// Rule: no reserved byte is listed twice, and no two share a substitute (a receiver could
/// not tell them apart).
fn distinct(
    ctx: &mut Ctx<'_>,
    span: std::ops::Range<usize>,
    pairs: Vec<[u8; 2]>,
) -> Option<Vec<[u8; 2]>> {
    let mut reserved = BTreeSet::new();
    let mut subs = BTreeSet::new();
    for [r, s] in &pairs {
        if !reserved.insert(*r) {
            ctx.error(
                span.clone(),
                format!("the escaped byte {r:#04X} is listed twice"),
                "list each reserved byte once",
            );
            return None;
        }
        if !subs.insert(*s) {
            ctx.error(
                span.clone(),
                format!("two escaped bytes share the substitute {s:#04X}"),
                "give each reserved byte a substitute of its own",
            );
            return None;
        }
    }
    Some(pairs)
}

/// Rule: the flag and the escape byte differ, both are escaped (else either could appear as
/// itself inside a frame), and no substitute is the flag (sent after the escape byte, it
/// would close the frame).
fn check_flag_and_escape(
    ctx: &mut Ctx<'_>,
    d: &EscapeDef,
    flag: u8,
    escape: u8,
    pairs: &[[u8; 2]],
) {
    if flag == escape {
        ctx.error(
            d.escape.span(),
            "the escape byte is the flag",
            "use a byte of its own, e.g. `escape = 0x7D` beside `flag = 0x7E`",
        );
        return;
    }
    let span = d
        .map
        .as_ref()
        .map(Spanned::span)
        .or(d.bytes.as_ref().map(Spanned::span))
        .unwrap_or(d.flag.span());
    for (what, b) in [("flag", flag), ("escape byte", escape)] {
        if !pairs.iter().any(|[r, _]| *r == b) {
            ctx.error(
                span.clone(),
                format!("the {what} {b:#04X} is not among the escaped bytes"),
                format!("add {b:#04X}: inside a frame it must go escaped"),
            );
        }
    }
    if let Some([r, s]) = pairs.iter().find(|[_, s]| *s == flag) {
        ctx.error(
            span,
            format!("the substitute of {r:#04X} is the flag {s:#04X}"),
            "choose a substitute other than the flag (it would close the frame)",
        );
    }
}

/// Rule: escaping is a serial framing of the spec's one frame format, and replaces byte
/// stuffing rather than adding to it. `false` when it does not apply.
fn check_setting(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    spanned: &Spanned<EscapeDef>,
    t: Transport,
) -> bool {
    let why = if def.stuffing.is_some() {
        Some((
            "byte stuffing and byte escaping of one frame are not supported together",
            "remove `stuffing`: the escape already keeps reserved bytes out of the frame",
        ))
    } else if t != Transport::Serial {
        Some((
            "a CAN frame is delimited by the bus, not by flag bytes",
            "remove `escape`, or use `transport = \"serial\"`",
        ))
    } else if def.bare_header.as_ref().is_some_and(|b| *b.get_ref()) {
        Some((
            "a bare header has no closing flag",
            "remove `bare_header`: an escaped frame always ends with its flag",
        ))
    } else if ctx.spec.frames.len() > 1 {
        Some((
            "byte escaping is supported on a spec of one frame format",
            "remove `escape`, or keep one `[frames.NAME]` table",
        ))
    } else {
        None
    };
    if let Some((message, help)) = why {
        ctx.error(spanned.span(), message, help);
        return false;
    }
    true
}

/// Rule: the flag opens and closes every frame: the layout's first element is `sync = [flag]`
/// and its last a `trailer = [flag]`.
fn check_delimiters(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    flag: u8,
    els: &[El<'_>],
    trailers: &[Trailer],
) {
    let layout = def.layout.get_ref();
    match els.first().map(|e| (&e.kind, e.def)) {
        Some((Kind::Sync(bytes), _)) if bytes.as_slice() == [flag] => {}
        other => {
            let span = other
                .and_then(|(_, d)| d)
                .map_or(def.layout.span(), Spanned::span);
            ctx.error(
                span,
                format!("a frame with byte escaping starts with its flag {flag:#04X} alone"),
                format!("make the first element `{{ sync = [{flag:#04X}] }}`"),
            );
        }
    }
    let last = els.last().map(|e| (&e.kind, e.def));
    let closes = matches!(last, Some((Kind::Trailer(t), _)) if trailers.get(*t).is_some_and(|t| t.bytes == [flag]));
    if !closes {
        let span = last
            .and_then(|(_, d)| d)
            .or(layout.last())
            .map_or(def.layout.span(), Spanned::span);
        ctx.error(
            span,
            format!("a frame with byte escaping ends with its flag {flag:#04X}"),
            format!("add `{{ trailer = [{flag:#04X}], name = \"end\" }}` as the last element"),
        );
    }
}
