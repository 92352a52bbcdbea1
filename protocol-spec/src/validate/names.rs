//! Rules about names and primitive type spellings: identifier case, Rust keywords, collisions
//! with the names the expansion itself defines, byte orders and wire type names.

use super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{ByteOrder, Prim, Scalar};
use crate::spec::model::SStr;

/// Type names the expansion defines in every generated module; specs cannot reuse them.
pub const RESERVED_TYPE_NAMES: &[&str] = &[
    "Header",
    "Message",
    "Request",
    "Response",
    "Packet",
    "Command",
    "Decoder",
    "Layout",
    "Frame",
    "Payload",
    "Direction",
    "Session",
    "Requester",
    "Responder",
];

/// Rust keywords that cannot be raw identifiers (`self`, `Self`, `super`, `crate`).
const NOT_RAW: &[&str] = &["self", "Self", "super", "crate", "_"];

/// The primitive type names a spec may write (before an optional `le`/`be` suffix).
pub const PRIM_NAMES: &[&str] = &[
    "u8", "i8", "u16", "i16", "u24", "i24", "u32", "i32", "u40", "i40", "u48", "i48", "u56", "i56",
    "u64", "i64", "f16", "f32", "f64", "bool",
];

/// `SHAKING_HANDS` -> `ShakingHands`, `chassis_coord` -> `ChassisCoord`.
pub fn pascal_case(name: &str) -> String {
    name.split('_')
        .filter(|w| !w.is_empty())
        .map(|w| {
            let mut chars = w.chars();
            match chars.next() {
                Some(first) => {
                    first.to_ascii_uppercase().to_string() + &chars.as_str().to_ascii_lowercase()
                }
                None => String::new(),
            }
        })
        .collect()
}

fn is_snake(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some('a'..='z'))
        && chars.all(|c| matches!(c, 'a'..='z' | '0'..='9' | '_'))
}

fn is_pascal(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some('A'..='Z')) && chars.all(|c| c.is_ascii_alphanumeric())
}

fn is_screaming(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some('A'..='Z'))
        && chars.all(|c| matches!(c, 'A'..='Z' | '0'..='9' | '_'))
}

/// Rule: field, frame, address and module names are snake_case identifiers (lowercase ASCII
/// letters, digits and `_`, starting with a letter), and not `self`/`super`/`crate`. Other
/// Rust keywords are fine: they become raw identifiers.
pub(crate) fn check_snake_name(ctx: &mut Ctx<'_>, name: &SStr, what: &str) -> bool {
    let n = name.get_ref();
    if NOT_RAW.contains(&n.as_str()) {
        ctx.error(
            name.span(),
            format!("{what} `{n}` cannot be used"),
            format!("`self`, `super` and `crate` cannot be names in Rust, even as raw identifiers; e.g. `{n}_`"),
        );
        return false;
    }
    if !is_snake(n) {
        ctx.error(
            name.span(),
            format!("{what} `{n}` is not a snake_case identifier"),
            format!(
                "use lowercase letters, digits and `_`, starting with a letter, e.g. `{}`",
                to_snake(n)
            ),
        );
        return false;
    }
    true
}

/// Rule: struct and enum names are PascalCase identifiers.
pub(crate) fn check_pascal_name(ctx: &mut Ctx<'_>, name: &SStr, what: &str) -> bool {
    let n = name.get_ref();
    if !is_pascal(n) {
        ctx.error(
            name.span(),
            format!("{what} name `{n}` is not a PascalCase identifier"),
            format!(
                "use letters and digits, starting with a capital, e.g. `{}`",
                pascal_case(&to_snake(n))
            ),
        );
        return false;
    }
    true
}

/// Rule: command and enum variant names are SCREAMING_SNAKE_CASE (as in the C originals); the
/// Rust name is their PascalCase form.
pub(crate) fn check_screaming_name(ctx: &mut Ctx<'_>, name: &SStr, what: &str) -> bool {
    let n = name.get_ref();
    if !is_screaming(n) {
        ctx.error(
            name.span(),
            format!("{what} name `{n}` is not SCREAMING_SNAKE_CASE"),
            format!(
                "use capitals, digits and `_`, e.g. `{}`",
                to_snake(n).to_ascii_uppercase()
            ),
        );
        return false;
    }
    true
}

pub(crate) fn to_snake(name: &str) -> String {
    let chars: Vec<char> = name.chars().collect();
    let mut out = String::new();
    for (i, &c) in chars.iter().enumerate() {
        // A capital starts a word after a lowercase letter or digit, or before a lowercase
        // letter inside a run of capitals (`CRCValue` -> `crc_value`).
        let prev = i.checked_sub(1).and_then(|p| chars.get(p)).copied();
        let next = chars.get(i + 1).copied();
        let boundary = c.is_ascii_uppercase()
            && match prev {
                Some(p) if p.is_ascii_lowercase() || p.is_ascii_digit() => true,
                Some(p) if p.is_ascii_uppercase() => next.is_some_and(|n| n.is_ascii_lowercase()),
                _ => false,
            };
        if boundary && !out.ends_with('_') {
            out.push('_');
        }
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let out = out.trim_matches('_').to_string();
    if out.starts_with(|c: char| c.is_ascii_digit()) || out.is_empty() {
        format!("x_{out}")
    } else {
        out
    }
}

/// Rule: struct and enum names are unique across both kinds, and none is a name the expansion
/// defines itself (`Header`, `Message`, ...).
pub(crate) fn check_type_names(ctx: &mut Ctx<'_>) {
    let spec = ctx.spec;
    let mut seen: Vec<(String, &'static str)> = Vec::new();
    let all = spec
        .structs
        .keys()
        .map(|k| (k, "struct"))
        .chain(spec.enums.keys().map(|k| (k, "enum")));
    for (name, kind) in all {
        let n = name.get_ref();
        if RESERVED_TYPE_NAMES.contains(&n.as_str()) {
            ctx.error(
                name.span(),
                format!("{kind} name `{n}` is reserved: the generated module defines `{n}` itself"),
                format!("rename it, e.g. `{n}Data`"),
            );
        }
        if let Some((_, other)) = seen.iter().find(|(s, _)| s == n) {
            ctx.error(
                name.span(),
                format!("{kind} `{n}` has the same name as a {other}"),
                "structs and enums share one namespace; rename one of them",
            );
        }
        seen.push((n.clone(), kind));
    }
}

/// Rule: a byte order is `"little"` or `"big"`.
pub(crate) fn parse_byte_order(ctx: &mut Ctx<'_>, s: &SStr) -> Option<ByteOrder> {
    match s.get_ref().as_str() {
        "little" | "le" => Some(ByteOrder::Little),
        "big" | "be" => Some(ByteOrder::Big),
        other => {
            ctx.error(
                s.span(),
                format!("unknown byte order `{other}`"),
                "write `\"little\"` or `\"big\"`",
            );
            None
        }
    }
}

/// Parse a primitive type spelling: `u16`, `u16le`, `u16be`, `f32`, `bool`, ... The byte order
/// defaults to `default`. `None` when the name is not a primitive (it may be a struct or enum).
pub fn parse_prim(name: &str, default: ByteOrder) -> Option<Scalar> {
    let (base, endian) = if let Some(b) = name.strip_suffix("le") {
        (b, ByteOrder::Little)
    } else if let Some(b) = name.strip_suffix("be") {
        (b, ByteOrder::Big)
    } else {
        (name, default)
    };
    let prim = match base {
        "bool" if base.len() == name.len() => Prim::Bool,
        "bool" => return None,
        other => Prim::from_spec_name(other)?,
    };
    Some(Scalar { prim, endian })
}

/// Every spelling of a primitive type, for "did you mean" suggestions.
pub fn prim_spellings() -> Vec<String> {
    let mut out = Vec::new();
    for p in PRIM_NAMES {
        out.push((*p).to_string());
        if *p != "bool" && *p != "u8" && *p != "i8" {
            out.push(format!("{p}le"));
            out.push(format!("{p}be"));
        }
    }
    out
}

/// Report an unknown type name, suggesting the closest known one. A primitive's spelling with a
/// width the wire does not have (`u36`, `f24`) is answered with the widths there are and the
/// narrowest that holds it, not with the nearest spelling (`u8`, `u16`), which means something
/// else.
pub(crate) fn unknown_type(ctx: &mut Ctx<'_>, ty: &SStr, known: &[String], what: &str) {
    let n = ty.get_ref();
    let nearest = did_you_mean(n, known.iter().map(String::as_str));
    // Transposed letters (`i61`, `u42be`) are a typo of that name, whatever the width says.
    let transposed = nearest.filter(|b| same_letters(b, n));
    let help = match transposed
        .map(|b| format!("did you mean `{b}`?"))
        .or_else(|| width_help(n))
        .or_else(|| nearest.map(|b| format!("did you mean `{b}`?")))
    {
        Some(help) => help,
        None => format!(
            "{what} is a primitive (`u8`, `u16be`, `f32`, `bool`, ...), or the name of a struct or enum of this spec"
        ),
    };
    ctx.error(ty.span(), format!("unknown type `{n}`"), help);
}

/// Whether `a` and `b` are spelled with the same letters, in some order.
fn same_letters(a: &str, b: &str) -> bool {
    let sorted = |s: &str| {
        let mut c: Vec<char> = s.chars().collect();
        c.sort_unstable();
        c
    };
    sorted(a) == sorted(b)
}

/// For `u36`, `i12be`, `f24`: the widths of that kind of number, and the narrowest that holds
/// the one written. `None` when the name is not a number's spelling.
fn width_help(name: &str) -> Option<String> {
    let (base, order) = match (name.strip_suffix("le"), name.strip_suffix("be")) {
        (Some(b), _) => (b, "le"),
        (_, Some(b)) => (b, "be"),
        _ => (name, ""),
    };
    let mut chars = base.chars();
    let kind = chars.next()?;
    let bits: u32 = chars.as_str().parse().ok()?;
    let (what, widths): (&str, &[u32]) = match kind {
        'u' => ("unsigned integers", &[8, 16, 24, 32, 40, 48, 56, 64]),
        'i' => ("signed integers", &[8, 16, 24, 32, 40, 48, 56, 64]),
        'f' => ("floats", &[16, 32, 64]),
        _ => return None,
    };
    let list = widths
        .iter()
        .map(|w| format!("`{kind}{w}`"))
        .collect::<Vec<_>>()
        .join(", ");
    Some(match widths.iter().find(|w| **w >= bits) {
        Some(_) if kind == 'f' && [8, 24].contains(&bits) => {
            format!("{what} are {list}; declare a {bits}-bit float's raw bits as `u{bits}{order}`")
        }
        Some(_) if kind == 'f' => format!("{what} are {list}"),
        Some(w) => {
            format!("{what} are {list} (with `le` or `be`); `{kind}{w}{order}` holds {bits} bits")
        }
        None => format!("{what} are {list}: none is wider than 64 bits"),
    })
}
