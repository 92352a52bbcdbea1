//! Rules for addresses, directions and the command table: ids against the dispatch key,
//! duplicate ids and names, payload references and their sizes against the frame.

use std::collections::HashMap;

use toml::Spanned;

use super::names::{check_screaming_name, check_snake_name, pascal_case};
use super::types::{Structs, mask};
use super::{Ctx, directions as given, directions_empty as empty, text};
use crate::diag::did_you_mean;
use crate::ir::{AddressSet, Command, Direction, DirectionRule, Frame, Role, Transport};
use crate::spec::model::{DirectionDef, IdDef, SStr};

/// Rule: an address set is `{ range = [first, last] }` with first <= last, or `{ value = v }`;
/// addresses are not negative.
pub(crate) fn lower_addresses(ctx: &mut Ctx<'_>) -> Vec<AddressSet> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    for (name, def) in &spec.addresses {
        check_snake_name(ctx, name, "address name");
        let d = def.get_ref();
        let (first, last) = match (&d.range, &d.value) {
            (Some(r), None) => {
                match r.get_ref().as_slice() {
                    [a, b] if *a.get_ref() >= 0 && a.get_ref() <= b.get_ref() => {
                        (*a.get_ref() as u64, *b.get_ref() as u64)
                    }
                    _ => {
                        ctx.error(r.span(), format!("address range of `{}` is not `[first, last]` with 0 <= first <= last", name.get_ref()), "write `range = [0x01, 0x10]`");
                        continue;
                    }
                }
            }
            (None, Some(v)) if *v.get_ref() >= 0 => (*v.get_ref() as u64, *v.get_ref() as u64),
            (None, Some(v)) => {
                ctx.error(v.span(), "an address cannot be negative", "use 0 or more");
                continue;
            }
            _ => {
                ctx.error(
                    def.span(),
                    format!(
                        "address `{}` needs exactly one of `range` and `value`",
                        name.get_ref()
                    ),
                    "write `{ range = [0x01, 0x10] }` or `{ value = 0xFF }`",
                );
                continue;
            }
        };
        out.push(AddressSet {
            name: name.get_ref().clone(),
            first,
            last,
            doc: text(&d.doc),
        });
    }
    out
}

/// Rule: directions are `request` and `response` (both, or none), and any number of empty
/// directions besides them (`empty = true`, `directions_empty::check_empty`); each names a
/// header field of the first frame and either an address set (`in`) or a value (`equals`).
pub(crate) fn lower_directions(
    ctx: &mut Ctx<'_>,
    frame: &Frame,
    addresses: &[AddressSet],
    structs: &Structs,
) -> Vec<Direction> {
    let spec = ctx.spec;
    let mut out = Vec::new();
    for (name, def) in &spec.directions {
        let n = name.get_ref();
        let Some(is_empty) = empty::check_empty(ctx, name, def) else {
            continue;
        };
        let d = def.get_ref();
        if d.given.is_some() || d.message.is_some() {
            if let Some((rule, message)) = given::lower_given(ctx, n, def, frame, structs) {
                out.push(Direction {
                    name: n.clone(),
                    rust_name: pascal_case(n),
                    doc: text(&d.doc),
                    rule,
                    message,
                    empty: false,
                    frame: None,
                });
            }
            continue;
        }
        let Some(field) = &d.field else {
            ctx.error(
                def.span(),
                format!("direction `{n}` needs `field` or `given`"),
                "write `{ field = \"sender\", in = \"master\" }` when a header field tells the direction, or `{ given = true }` when the decoder is given it",
            );
            continue;
        };
        let Some(vi) = frame.values.iter().position(|v| &v.name == field.get_ref()) else {
            let help = match did_you_mean(
                field.get_ref(),
                frame.values.iter().map(|v| v.name.as_str()),
            ) {
                Some(b) => format!("did you mean `{b}`?"),
                None => "name a header field of the first frame".to_string(),
            };
            ctx.error(
                field.span(),
                format!(
                    "frame `{}` has no header field `{}`",
                    frame.name,
                    field.get_ref()
                ),
                help,
            );
            continue;
        };
        if !matches!(frame.values[vi].role, Role::User { .. }) {
            ctx.error(
                field.span(),
                format!(
                    "`{}` is computed by the codec, so it cannot tell the direction",
                    field.get_ref()
                ),
                "use a field the sender sets, such as an address or a flag",
            );
            continue;
        }
        let Some(rule) = lower_direction_rule(ctx, n, def, frame, vi, addresses) else {
            continue;
        };
        out.push(Direction {
            name: n.clone(),
            rust_name: pascal_case(n),
            doc: text(&d.doc),
            rule,
            message: None,
            empty: is_empty,
            frame: None,
        });
    }
    given::check_given_agree(ctx);
    // Rule: both directions, or neither. Report a lone direction only when the spec declares
    // one; when a declared direction failed to lower, its own error says why.
    let paired = |n: &str| n == "request" || n == "response";
    let declared =
        (spec.directions.iter()).filter(|(k, d)| paired(k.get_ref()) || !empty::is_empty(d));
    if declared.count() == 1 {
        let span = spec
            .directions
            .keys()
            .next()
            .map(Spanned::span)
            .unwrap_or_default();
        ctx.error(
            span,
            "only one direction is declared",
            "declare both `request` and `response`, or neither",
        );
    }
    if out.iter().filter(|d| paired(&d.name)).count() != 2 {
        out.clear();
    }
    // Request first, then response, then the empty directions, whatever the spec's order.
    out.sort_by_key(|d| match d.name.as_str() {
        "request" => 0,
        "response" => 1,
        _ => 2,
    });
    out
}

/// Rule: a direction tells its frames by the header value lying in a declared address set
/// (`in`), or equalling a value the field can hold (`equals`), exactly one of the two.
fn lower_direction_rule(
    ctx: &mut Ctx<'_>,
    n: &str,
    def: &Spanned<DirectionDef>,
    frame: &Frame,
    vi: usize,
    addresses: &[AddressSet],
) -> Option<DirectionRule> {
    let d = def.get_ref();
    Some(match (&d.in_set, &d.equals) {
        (Some(set), None) => match addresses.iter().position(|a| &a.name == set.get_ref()) {
            Some(si) => DirectionRule::InSet { value: vi, set: si },
            None => {
                let help =
                    match did_you_mean(set.get_ref(), addresses.iter().map(|a| a.name.as_str())) {
                        Some(b) => format!("did you mean `{b}`?"),
                        None => "declare the set under `[addresses]`".to_string(),
                    };
                ctx.error(
                    set.span(),
                    format!("unknown address set `{}`", set.get_ref()),
                    help,
                );
                return None;
            }
        },
        (None, Some(v))
            if *v.get_ref() >= 0 && (*v.get_ref() as u64) <= mask(frame.values[vi].width) =>
        {
            DirectionRule::Equals {
                value: vi,
                equals: *v.get_ref() as u64,
            }
        }
        (None, Some(v)) => {
            ctx.error(
                v.span(),
                format!(
                    "{} does not fit in field `{}`",
                    v.get_ref(),
                    frame.values[vi].name
                ),
                "use a value the field can hold",
            );
            return None;
        }
        _ => {
            ctx.error(def.span(), format!("direction `{n}` needs exactly one of `in` and `equals`"), "write `{ field = \"sender\", in = \"master\" }` or `{ field = \"is_ack\", equals = 1 }`");
            return None;
        }
    })
}

/// Rule: every command has a SCREAMING_SNAKE_CASE name whose Rust form is unique, an id with
/// one value per dispatch field that fits the field and is not used by another command, and
/// payload references (`payload` without directions, `request`/`response` with them) that
/// name structs whose size fits the frame's payload bounds.
pub(crate) fn lower_commands(
    ctx: &mut Ctx<'_>,
    frames: &[Frame],
    directions: &[Direction],
    structs: &Structs,
) -> Vec<Command> {
    let spec = ctx.spec;
    let mut out: Vec<Command> = Vec::new();
    // The first frame format holds the dispatch key. When it failed to lower, its own errors
    // say why, and the commands are still checked for everything that does not need it.
    let frame = frames.first().filter(|f| {
        spec.frames
            .keys()
            .next()
            .is_some_and(|k| k.get_ref() == &f.name)
    });
    if let Some(frame) = frame {
        if !spec.commands.is_empty() && frame.dispatch.is_empty() {
            let span = spec
                .commands
                .keys()
                .next()
                .map(Spanned::span)
                .unwrap_or_default();
            ctx.error(span, format!("commands are declared, but frame `{}` has no dispatch key", frame.name), "add `dispatch = [\"command\"]` to the frame, naming the field that holds the command id");
            return out;
        }
    }
    let key_fields = frame
        .map(|f| key_fields(ctx, f, frames))
        .unwrap_or_default();
    let mut ids: HashMap<Vec<u64>, String> = HashMap::new();
    let mut can_ids: HashMap<u64, String> = HashMap::new();
    let can_frame = frames
        .iter()
        .skip(1)
        .find(|f| matches!(f.transport, Transport::Can { .. }));
    let mut rust_names: HashMap<String, String> = HashMap::new();
    for (name, def) in &spec.commands {
        if !check_screaming_name(ctx, name, "command") {
            continue;
        }
        let d = def.get_ref();
        let rust_name = pascal_case(name.get_ref());
        let mut valid = true;
        if let Some(prev) = rust_names.get(&rust_name) {
            ctx.error(
                name.span(),
                format!(
                    "commands `{prev}` and `{}` both become the Rust name `{rust_name}`",
                    name.get_ref()
                ),
                "rename one so their PascalCase forms differ",
            );
            valid = false;
        } else {
            rust_names.insert(rust_name.clone(), name.get_ref().clone());
        }
        let id = frame.and_then(|frame| lower_id(ctx, name, d, frame, &key_fields, &mut ids));
        let payloads = lower_payload_refs(ctx, name, d, frame, directions, structs);
        let can_id = lower_can_id(ctx, name, d.can_id.as_ref(), can_frame, &mut can_ids);
        let check_extra = super::extra::lower_check_extra(ctx, name, d);
        if let (true, Some(id)) = (valid, id) {
            out.push(Command {
                can_id,
                check_extra,
                name: name.get_ref().clone(),
                rust_name,
                id,
                doc: text(&d.doc),
                payloads,
            });
        }
    }
    out
}

/// The dispatch fields an id's values must fit, as (width, name): the first frame's, each
/// widened to the widest field at its place among the formats that carry the commands too
/// (`commands = true` with a dispatch key of as many fields): a command may be carried by a
/// wider format only (MSP v2's ids above 255); which formats carry it is the link's rule.
fn key_fields(ctx: &Ctx<'_>, first: &Frame, frames: &[Frame]) -> Vec<(u32, String)> {
    let mut out: Vec<(u32, String)> = first
        .dispatch
        .iter()
        .map(|&vi| (first.values[vi].width, first.values[vi].name.clone()))
        .collect();
    for (name, def) in ctx.spec.frames.iter().skip(1) {
        if !def
            .get_ref()
            .commands
            .as_ref()
            .is_some_and(|c| *c.get_ref())
        {
            continue;
        }
        let Some(f) = frames.iter().find(|f| &f.name == name.get_ref()) else {
            continue;
        };
        if f.dispatch.len() != out.len() {
            continue;
        }
        for ((width, field), &vi) in out.iter_mut().zip(&f.dispatch) {
            if f.values[vi].width > *width {
                *width = f.values[vi].width;
                *field = f.values[vi].name.clone();
            }
        }
    }
    out
}

/// Rule: an id has one value per dispatch field of the frame, each fitting its field (the
/// widest of the link's command formats, `key_fields`), and no other command has the same id.
fn lower_id(
    ctx: &mut Ctx<'_>,
    name: &SStr,
    d: &crate::spec::model::CommandDef,
    frame: &Frame,
    key_fields: &[(u32, String)],
    ids: &mut HashMap<Vec<u64>, String>,
) -> Option<Vec<u64>> {
    let raw: Vec<i64> = match d.id.get_ref() {
        IdDef::One(v) => vec![*v],
        IdDef::Many(v) => v.clone(),
    };
    if raw.len() != frame.dispatch.len() {
        let keys: Vec<&str> = frame
            .dispatch
            .iter()
            .map(|&i| frame.values[i].name.as_str())
            .collect();
        ctx.error(
            d.id.span(),
            format!(
                "id has {} value(s), but the dispatch key has {} field(s) ({})",
                raw.len(),
                keys.len(),
                keys.join(", ")
            ),
            if keys.len() == 1 {
                "write one integer, e.g. `id = 0x01`".to_string()
            } else {
                format!(
                    "write one integer per field, in the order {}",
                    keys.join(", ")
                )
            },
        );
        return None;
    }
    let mut id = Vec::new();
    let mut fits = true;
    for (v, (width, field)) in raw.iter().zip(key_fields) {
        if *v < 0 || (*v as u64) > mask(*width) {
            ctx.error(
                d.id.span(),
                format!("id {v} does not fit in the {width}-bit field `{field}`"),
                format!("ids of `{field}` range from 0 to {}", mask(*width)),
            );
            fits = false;
        }
        id.push(*v as u64);
    }
    if !fits {
        return None;
    }
    if let Some(prev) = ids.get(&id) {
        ctx.error(d.id.span(), format!("command `{}` reuses the id of `{prev}`", name.get_ref()), "every command needs its own id; ids are explicit so that adding a command never renumbers the others");
        return None;
    }
    ids.insert(id.clone(), name.get_ref().clone());
    Some(id)
}

fn lower_payload_refs(
    ctx: &mut Ctx<'_>,
    name: &SStr,
    d: &crate::spec::model::CommandDef,
    frame: Option<&Frame>,
    directions: &[Direction],
    structs: &Structs,
) -> Vec<Option<usize>> {
    let resolve = |ctx: &mut Ctx<'_>, r: &Option<SStr>| -> Option<usize> {
        let r = r.as_ref()?;
        let Some(&i) = structs.by_name.get(r.get_ref()) else {
            if !ctx.spec.structs.keys().any(|k| k.get_ref() == r.get_ref()) {
                let help = match did_you_mean(
                    r.get_ref(),
                    structs.structs.iter().map(|s| s.name.as_str()),
                ) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => "declare it as `[structs.NAME]`".to_string(),
                };
                ctx.error(r.span(), format!("unknown struct `{}`", r.get_ref()), help);
            }
            return None;
        };
        let size = structs.structs[i].size;
        let min_size = structs.structs[i].min_size;
        if !structs.structs[i].context.is_empty() {
            // Sized bytes whose size field is not in the struct: as a payload, nothing else can
            // hold it, so the `size` names a missing field.
            for (need, span, earlier) in structs.size_refs.get(r.get_ref()).into_iter().flatten() {
                let help = match did_you_mean(need, earlier.iter().map(String::as_str)) {
                    Some(b) => format!("did you mean `{b}`?"),
                    None => {
                        "name an earlier integer field that holds the number of bytes".to_string()
                    }
                };
                ctx.error(
                    span.clone(),
                    format!(
                        "struct `{}` has no integer field `{need}` before its sized bytes",
                        r.get_ref()
                    ),
                    help,
                );
            }
            return Some(i);
        }
        let Some(frame) = frame else { return Some(i) };
        if frame.truncate_zeros && min_size != size {
            ctx.error(r.span(), format!("struct `{}` ends with variable bytes, but frame `{}` zero-fills truncated payloads to their struct's size", r.get_ref(), frame.name), "give the struct a fixed size, or remove the frame's `truncate_zeros`");
        }
        if min_size > frame.payload_max && min_size != size {
            ctx.error(r.span(), format!("struct `{}` takes at least {min_size} bytes, but frame `{}` carries at most {} payload bytes", r.get_ref(), frame.name, frame.payload_max), "raise the payload's `max` or shrink the struct");
        } else if size > frame.payload_max && min_size == size {
            ctx.error(
                r.span(),
                format!(
                    "struct `{}` is {size} bytes, but frame `{}` carries at most {} payload bytes",
                    r.get_ref(),
                    frame.name,
                    frame.payload_max
                ),
                "raise the payload's `max` or shrink the struct",
            );
        } else if min_size < frame.payload_min {
            ctx.error(
                r.span(),
                format!(
                    "struct `{}` is {size} bytes, but frame `{}` carries at least {} payload bytes",
                    r.get_ref(),
                    frame.name,
                    frame.payload_min
                ),
                "lower the payload's `min` or pad the struct",
            );
        }
        Some(i)
    };
    if directions.is_empty() {
        // Directions declared but broken: their own errors say why; skip these checks.
        let declared = !ctx.spec.directions.is_empty();
        for (key, v) in [("request", &d.request), ("response", &d.response)]
            .into_iter()
            .filter(|_| !declared)
        {
            if let Some(v) = v {
                ctx.error(v.span(), format!("`{key}` needs `[directions]`, which this spec does not declare"), "write `payload = \"...\"`, or declare `[directions]` to give requests and responses their own payloads");
            }
        }
        vec![resolve(ctx, &d.payload)]
    } else {
        if let Some(p) = &d.payload {
            ctx.error(p.span(), format!("command `{}` uses `payload`, but this spec has directions", name.get_ref()), "write `request = \"...\"` and/or `response = \"...\"`; a missing one means an empty payload");
        }
        directions
            .iter()
            .map(|dir| {
                let r = match dir.name.as_str() {
                    "request" => &d.request,
                    "response" => &d.response,
                    // An empty direction carries no payload of any command.
                    _ => return None,
                };
                match (dir.message, r) {
                    (Some((si, _)), Some(r)) => {
                        ctx.error(r.span(), format!("direction `{}` carries `{}` in every frame, so command `{}` has no {} payload of its own", dir.name, structs.structs[si].name, name.get_ref(), dir.name), format!("remove `{}` from the command", dir.name));
                        None
                    }
                    _ => resolve(ctx, r),
                }
            })
            .collect()
    }
}

/// Rule: a command's `can_id` is given when the spec has a CAN frame besides its first frame,
/// fits the frame's id width (11 or 29 bits), and is not another command's.
fn lower_can_id(
    ctx: &mut Ctx<'_>,
    name: &SStr,
    id: Option<&Spanned<i64>>,
    can_frame: Option<&Frame>,
    seen: &mut HashMap<u64, String>,
) -> Option<u64> {
    let id = id?;
    let declared = ctx.spec.frames.values().skip(1).any(|f| {
        f.get_ref()
            .transport
            .as_ref()
            .is_some_and(|t| t.get_ref() == "can")
    });
    let Some(frame) = can_frame else {
        if declared {
            // The CAN frame failed to lower; its own errors say why.
            return None;
        }
        ctx.error(
            id.span(),
            "`can_id` needs a CAN frame besides the first frame",
            "add a `[frames.NAME]` with `transport = \"can\"`, or remove `can_id`",
        );
        return None;
    };
    let width = frame.values.first().map_or(11, |v| v.width);
    let v = *id.get_ref();
    if v < 0 || (v as u64) > mask(width) {
        ctx.error(id.span(), format!("CAN id {v:#x} does not fit in {width} bits"), if width == 11 { "standard CAN ids go up to 0x7FF; use `can_id = \"extended\"` on the frame for 29-bit ids".to_string() } else { "extended CAN ids go up to 0x1FFFFFFF".to_string() });
        return None;
    }
    if let Some(prev) = seen.get(&(v as u64)) {
        ctx.error(
            id.span(),
            format!("command `{}` reuses the CAN id of `{prev}`", name.get_ref()),
            "every command needs its own CAN id",
        );
        return None;
    }
    seen.insert(v as u64, name.get_ref().clone());
    Some(v as u64)
}
