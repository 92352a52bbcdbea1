//! Rules for the shape of one layout element: its kind key and the keys that apply to it, and
//! lists of bytes (sync, trailers, stuffing patterns).

use toml::Spanned;

use super::super::Ctx;
use crate::spec::model::ElementDef;

/// The keys an element may carry besides its kind key, per kind.
const FIELD_KEYS: &[&str] = &[
    "field",
    "type",
    "addresses",
    "length_of",
    "value",
    "bits",
    "doc",
];
const SYNC_KEYS: &[&str] = &["sync", "doc"];
const PAYLOAD_KEYS: &[&str] = &["payload", "doc"];
const CHECK_KEYS: &[&str] = &["check", "over", "byte_order", "name", "doc"];
const TRAILER_KEYS: &[&str] = &["trailer", "name", "doc"];

fn present_keys(e: &ElementDef) -> Vec<(&'static str, std::ops::Range<usize>)> {
    let mut v = Vec::new();
    macro_rules! k {
        ($($f:ident => $n:literal),*) => {$(
            if let Some(x) = &e.$f { v.push(($n, x.span())); }
        )*};
    }
    k!(sync => "sync", field => "field", payload => "payload", check => "check", trailer => "trailer",
       ty => "type", addresses => "addresses", length_of => "length_of", value => "value",
       bits => "bits", over => "over", byte_order => "byte_order", name => "name", doc => "doc");
    v
}

/// Rule: each element has exactly one kind key (`sync`, `field`, `payload`, `check`,
/// `trailer`) and only the keys that apply to that kind.
pub(super) fn check_element_keys(
    ctx: &mut Ctx<'_>,
    el: &Spanned<ElementDef>,
) -> Option<&'static str> {
    let keys = present_keys(el.get_ref());
    let kinds: Vec<_> = keys
        .iter()
        .filter(|(k, _)| ["sync", "field", "payload", "check", "trailer"].contains(k))
        .collect();
    let kind = match kinds.as_slice() {
        [one] => one.0,
        [] => {
            ctx.error(el.span(), "layout element has no kind", "start it with one of `sync = [...]`, `field = \"name\"`, `payload = { max = N }`, `check = \"algorithm\"` or `trailer = [...]`");
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
