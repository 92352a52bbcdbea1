//! Rules for one layout element at a time: its kind key and the keys that apply to it, the
//! sync, the payload bounds, checks and trailers (header fields are in `header`), and the
//! rules over the element list (unique names, the sync first).

use toml::Spanned;

use super::super::checksum::{resolve_algorithm, set_crc_table};
use super::super::names::{check_snake_name, parse_byte_order};
use super::super::types::Enums;
use super::super::{Ctx, text};
use super::{Draft, El, Kind, header};
use crate::ir::{Algorithm, ByteOrder, Check, CheckExtra, Pos, Trailer, Transport, WordField};

use crate::spec::model::{ElementDef, FrameDef, SStr};

/// Lower element `i` of the layout into the draft, by its kind. `None` when the element's kind
/// key has no value to read.
pub(super) fn lower_element<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    i: usize,
    el: &'s Spanned<ElementDef>,
    enums: &Enums,
) -> Option<()> {
    let Some(kind) = check_element_keys(ctx, el) else {
        draft.broken = true;
        return Some(());
    };
    match kind {
        "sync" => lower_sync(ctx, draft, i, el),
        "field" => header::lower_field_element(ctx, draft, el, enums),
        "payload" => lower_payload(ctx, draft, el),
        "check" => lower_check(ctx, draft, el),
        "optional" => {
            super::conditional::lower_optional(ctx, draft, el);
            Some(())
        }
        _ => lower_trailer(ctx, draft, el),
    }
}

/// The keys an element may carry besides its kind key, per kind.
const FIELD_KEYS: &[&str] = &[
    "field",
    "type",
    "addresses",
    "length_of",
    "value",
    "one_of",
    "bits",
    "extends",
    "marker",
    "counter",
    "direction",
    "doc",
];
const SYNC_KEYS: &[&str] = &["sync", "doc"];
const PAYLOAD_KEYS: &[&str] = &["payload", "doc"];
const CHECK_KEYS: &[&str] = &[
    "check",
    "over",
    "byte_order",
    "extra",
    "table",
    "name",
    "doc",
];
const TRAILER_KEYS: &[&str] = &["trailer", "name", "doc"];
const OPTIONAL_KEYS: &[&str] = &["optional", "size", "when", "doc"];

fn present_keys(e: &ElementDef) -> Vec<(&'static str, std::ops::Range<usize>)> {
    let mut v = Vec::new();
    macro_rules! k {
        ($($f:ident => $n:literal),*) => {$(
            if let Some(x) = &e.$f { v.push(($n, x.span())); }
        )*};
    }
    k!(sync => "sync", field => "field", payload => "payload", check => "check", trailer => "trailer",
       ty => "type", addresses => "addresses", length_of => "length_of", value => "value",
       one_of => "one_of", bits => "bits", over => "over", byte_order => "byte_order", extra => "extra",
       table => "table", name => "name", optional => "optional", size => "size", when => "when",
       extends => "extends", marker => "marker", counter => "counter", direction => "direction",
       doc => "doc");
    v
}

/// Rule: each element has exactly one kind key (`sync`, `field`, `payload`, `check`,
/// `trailer`, `optional`) and only the keys that apply to that kind.
pub(super) fn check_element_keys(
    ctx: &mut Ctx<'_>,
    el: &Spanned<ElementDef>,
) -> Option<&'static str> {
    let keys = present_keys(el.get_ref());
    let kinds: Vec<_> = keys
        .iter()
        .filter(|(k, _)| ["sync", "field", "payload", "check", "trailer", "optional"].contains(k))
        .collect();
    let kind = match kinds.as_slice() {
        [one] => one.0,
        [] => {
            ctx.error(el.span(), "layout element has no kind", "start it with one of `sync = [...]`, `field = \"name\"`, `payload = { max = N }`, `check = \"algorithm\"`, `trailer = [...]` or `optional = \"name\"`");
            return None;
        }
        [_, second, ..] => {
            ctx.error(
                second.1.clone(),
                format!(
                    "layout element has two kinds (`{}` and `{}`)",
                    kinds[0].0, second.0
                ),
                "split it into two elements",
            );
            return None;
        }
    };
    let allowed = match kind {
        "sync" => SYNC_KEYS,
        "field" => FIELD_KEYS,
        "payload" => PAYLOAD_KEYS,
        "check" => CHECK_KEYS,
        "optional" => OPTIONAL_KEYS,
        _ => TRAILER_KEYS,
    };
    for (k, span) in &keys {
        if !allowed.contains(k) {
            ctx.error(
                span.clone(),
                format!("key `{k}` does not apply to a `{kind}` element"),
                format!(
                    "a `{kind}` element takes {}",
                    allowed
                        .iter()
                        .map(|a| format!("`{a}`"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            );
        }
    }
    Some(kind)
}

pub(super) fn byte_list(
    ctx: &mut Ctx<'_>,
    list: &Spanned<Vec<Spanned<i64>>>,
    what: &str,
) -> Vec<u8> {
    if list.get_ref().is_empty() {
        ctx.error(
            list.span(),
            format!("{what} is empty"),
            "list at least one byte, e.g. `[0xFF, 0xFF]`",
        );
    }
    let mut out = Vec::new();
    for b in list.get_ref() {
        match u8::try_from(*b.get_ref()) {
            Ok(v) => out.push(v),
            Err(_) => ctx.error(
                b.span(),
                format!("{} is not a byte", b.get_ref()),
                "use a value from 0x00 to 0xFF",
            ),
        }
    }
    out
}

/// Rule: sync bytes are a non-empty list of bytes, the first element of a serial frame's
/// layout; a CAN frame has none.
fn lower_sync<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    i: usize,
    el: &'s Spanned<ElementDef>,
) -> Option<()> {
    let bytes = byte_list(ctx, el.get_ref().sync.as_ref()?, "sync");
    if matches!(draft.transport, Transport::Can { .. }) {
        ctx.error(
            el.span(),
            "a CAN frame has no sync bytes",
            "remove the `sync` element: CAN delivers whole frames",
        );
    } else if i != 0 {
        ctx.error(el.span(), "sync bytes must be the first element of the layout", "move the `sync` element to the start; constant bytes after the payload are a `trailer`");
        draft.broken = true;
    }
    draft.els.push(El {
        name: "sync".into(),
        def: Some(el),
        size: bytes.len(),
        kind: Kind::Sync(bytes),
    });
    Some(())
}

/// Rule: a frame has one payload, with a `max` size and bounds 0 <= min <= max.
fn lower_payload<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
) -> Option<()> {
    let p = el.get_ref().payload.as_ref()?;
    if draft.payload.is_some() {
        ctx.error(
            el.span(),
            "a frame has one payload",
            "remove the second `payload` element",
        );
        return Some(());
    }
    let min = p.get_ref().min.as_ref().map_or(0, |m| *m.get_ref());
    let max = match &p.get_ref().max {
        Some(m) => *m.get_ref(),
        None => {
            ctx.error(
                p.span(),
                "the payload needs a `max` size",
                "write `payload = { max = N }`: decoders size their buffer from it",
            );
            draft.broken = true;
            min.max(0)
        }
    };
    if min < 0 || max < min {
        ctx.error(
            p.span(),
            format!("payload bounds {min}..={max} are not valid"),
            "use 0 <= min <= max",
        );
        draft.broken = true;
    }
    draft.payload = Some((draft.els.len(), min.max(0) as usize, max.max(0) as usize));
    draft.els.push(El {
        name: "payload".into(),
        def: Some(el),
        size: 0,
        kind: Kind::Payload,
    });
    Some(())
}

/// Rule: a check names a known algorithm, an optional byte order and an optional snake_case
/// name (default `checksum`); a check before the payload is a header check.
fn lower_check<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
) -> Option<()> {
    let d = el.get_ref();
    let alg_name = d.check.as_ref()?;
    let algorithm = resolve_algorithm(ctx, alg_name);
    let endian = match &d.byte_order {
        Some(o) => parse_byte_order(ctx, o).unwrap_or(ctx.default_endian),
        None => ctx.default_endian,
    };
    let name = d
        .name
        .as_ref()
        .map_or_else(|| "checksum".to_string(), |n| n.get_ref().clone());
    if let Some(n) = &d.name {
        check_snake_name(ctx, n, "check name");
    }
    let Some((mut algorithm, naming)) = algorithm else {
        draft.broken = true;
        return Some(());
    };
    if let Some(t) = &d.table {
        if !set_crc_table(ctx, t, &mut algorithm) {
            draft.broken = true;
            return Some(());
        }
    }
    let extra = match &d.extra {
        None => None,
        Some(e) => {
            let Some(extra) = lower_extra(ctx, e, &algorithm) else {
                draft.broken = true;
                return Some(());
            };
            Some(extra)
        }
    };
    let size = algorithm.width();
    let ci = draft.checks.len();
    draft.checks.push((
        Check {
            name: name.clone(),
            doc: text(&d.doc),
            algorithm,
            naming,
            extra,
            at: Pos::Start(0),
            size,
            endian,
            from: Pos::Start(0),
            to: Pos::Start(0),
            header: draft.payload.is_none(),
        },
        draft.els.len(),
    ));
    draft.els.push(El {
        name,
        def: Some(el),
        size,
        kind: Kind::Check(ci),
    });
    Some(())
}

/// Rule: a check's `extra` is `"command"` (each command's `check_extra` byte, folded in after
/// the covered bytes), on a CRC. The CRC keeps its table: the covered bytes take its fast
/// path and the byte one more table step.
fn lower_extra(ctx: &mut Ctx<'_>, e: &SStr, algorithm: &Algorithm) -> Option<CheckExtra> {
    if e.get_ref() != "command" {
        ctx.error(
            e.span(),
            format!("unknown check extra `{}`", e.get_ref()),
            "use `extra = \"command\"`: each command's `check_extra` byte is folded in after the covered bytes",
        );
        return None;
    }
    if !matches!(
        algorithm,
        Algorithm::Crc8(_) | Algorithm::Crc16(_) | Algorithm::Crc32(_) | Algorithm::Crc64(_)
    ) {
        ctx.error(
            e.span(),
            "a per-command extra byte is folded into CRCs only",
            "use a CRC for this check, or remove `extra`",
        );
        return None;
    }
    Some(CheckExtra {
        value: 0,
        key: WordField {
            at: Pos::Start(0),
            size: 1,
            order: ByteOrder::Little,
            shift: 0,
            width: 8,
        },
        bytes: Vec::new(),
        direct: 0,
    })
}

/// Rule: a trailer is a non-empty list of bytes after the payload, named `trailer` unless it
/// says otherwise.
fn lower_trailer<'s>(
    ctx: &mut Ctx<'_>,
    draft: &mut Draft<'s>,
    el: &'s Spanned<ElementDef>,
) -> Option<()> {
    let d = el.get_ref();
    let bytes = byte_list(ctx, d.trailer.as_ref()?, "trailer");
    if draft.payload.is_none() {
        ctx.error(
            el.span(),
            "a trailer comes after the payload",
            "constant bytes before the payload are a field with `value = ...`, or the sync",
        );
    }
    let name = d
        .name
        .as_ref()
        .map_or_else(|| "trailer".to_string(), |n| n.get_ref().clone());
    let ti = draft.trailers.len();
    draft.trailers.push(Trailer {
        name: name.clone(),
        doc: text(&d.doc),
        at: Pos::Start(0),
        bytes: bytes.clone(),
    });
    draft.els.push(El {
        name,
        def: Some(el),
        size: bytes.len(),
        kind: Kind::Trailer(ti),
    });
    Some(())
}

/// Rule: element names are unique within a frame (they are what `over` and `length_of` name).
pub(super) fn check_unique_names(ctx: &mut Ctx<'_>, fname: &SStr, els: &[El<'_>]) {
    for (i, e) in els.iter().enumerate() {
        let Some(edef) = e.def else { continue };
        if els[..i].iter().any(|p| p.name == e.name) {
            let span = edef
                .get_ref()
                .field
                .as_ref()
                .or(edef.get_ref().name.as_ref())
                .map_or(edef.span(), Spanned::span);
            ctx.error(span, format!("two elements of frame `{}` are named `{}`", fname.get_ref(), e.name), "give every field, check and trailer its own name (checks and trailers take `name = \"...\"`)");
        }
    }
}

/// Rule: the first element of a serial frame is the sync, or a field that is the sync (`one_of`)
/// (checked only when every element lowered: a broken element may be the sync).
pub(super) fn check_serial_sync(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    draft: &mut Draft<'_>,
) {
    if draft.transport == Transport::Serial
        && !matches!(draft.els.first().map(|e| &e.kind), Some(Kind::Sync(_)))
        && draft.sync_set.is_none()
        && !draft.broken
    {
        ctx.error(def.layout.span(), format!("frame `{}` has no sync bytes", fname.get_ref()), "start the layout with `{ sync = [0xFF, 0xFF] }` (or a `u8` field with `one_of = [...]`): a stream decoder finds frames by their sync");
        draft.broken = true;
    }
}
