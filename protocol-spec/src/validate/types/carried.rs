//! Rules for a packet carried inside a payload (`carries`): a `bytes` field that holds the
//! payload of the command whose id an earlier unsigned integer field of the same struct
//! holds (MSP v1's command 255 carries a v2 command id and its payload). The key is read
//! before the bytes, and it names a command of this spec, so the spec dispatches on one field.

use super::super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{Carried, Field, FieldKind, ValueType};
use crate::spec::model::{SStr, StructDef};

/// The packets struct `d` carries, from its lowered `fields`; each `carries` follows the rules
/// below, and one that breaks one is reported and left out.
pub(super) fn lower_carries(ctx: &mut Ctx<'_>, d: &StructDef, fields: &[Field]) -> Vec<Carried> {
    let mut out = Vec::new();
    for f in d.fields.get_ref() {
        let def = f.get_ref();
        let (Some(key), Some(name)) = (&def.carries, &def.name) else {
            continue;
        };
        let Some(at) = fields.iter().position(|x| &x.name == name.get_ref()) else {
            continue;
        };
        if !check_carrier_kind(ctx, key, &fields[at]) || !check_one_field_key(ctx, key) {
            continue;
        }
        if let Some(k) = lower_carried_key(ctx, key, &fields[at].name, &fields[..at], fields) {
            out.push(Carried { field: at, key: k });
        }
    }
    out
}

/// Rule: `carries` applies to `type = "bytes"` (raw bytes, not text, not optional or
/// announced by a mask): the carried payload is bytes of the carrying struct.
fn check_carrier_kind(ctx: &mut Ctx<'_>, key: &SStr, field: &Field) -> bool {
    if matches!(field.kind, FieldKind::Bytes { text: false, .. }) {
        return true;
    }
    ctx.error(
        key.span(),
        format!(
            "`carries` applies to `type = \"bytes\"` fields, not to `{}`",
            field.name
        ),
        "carry the packet in a `bytes` field (with `size`, or the last of the struct)",
    );
    false
}

/// Rule: a carried packet's key is one value, so the spec's commands are told by one dispatch
/// field, and no direction carries one struct in place of a command (`message`).
fn check_one_field_key(ctx: &mut Ctx<'_>, key: &SStr) -> bool {
    let spec = ctx.spec;
    let fields = spec
        .frames
        .values()
        .next()
        .and_then(|f| f.get_ref().dispatch.as_ref())
        .map_or(0, |d| d.get_ref().len());
    let message = spec
        .directions
        .values()
        .any(|d| d.get_ref().message.is_some());
    if fields == 1 && !message {
        return true;
    }
    let why = if message {
        "a direction carries one struct in place of a command (`message`)".to_string()
    } else {
        format!("the commands are told by {fields} dispatch fields")
    };
    ctx.error(
        key.span(),
        format!("a carried packet names a command by one id, but {why}"),
        "`carries` needs a first frame format with `dispatch = [\"field\"]` and no direction `message`",
    );
    false
}

/// Rule: the key of a carried packet is an earlier field of the same struct, a whole
/// unsigned integer (not scaled, not an array, not split into `bits`). Gives its index.
fn lower_carried_key(
    ctx: &mut Ctx<'_>,
    key: &SStr,
    what: &str,
    before: &[Field],
    all: &[Field],
) -> Option<usize> {
    let name = key.get_ref();
    if let Some(k) = before.iter().position(|x| &x.name == name) {
        let unsigned = matches!(
            &before[k].kind,
            FieldKind::Value {
                ty: ValueType::Scalar { scalar, scale: None },
                count: None,
            } if scalar.prim.is_unsigned()
        );
        if unsigned {
            return Some(k);
        }
        ctx.error(
            key.span(),
            format!("`{name}` is not an unsigned integer field, so it cannot hold the id of the command `{what}` carries"),
            "name an earlier `u8`/`u16`/`u32` field without `scale`, `count` or `bits`",
        );
        return None;
    }
    if all.iter().any(|x| &x.name == name) {
        ctx.error(
            key.span(),
            format!("the key `{name}` comes after `{what}`, which it names the command of"),
            format!("move `{name}` before `{what}`: a decoder reads the key first"),
        );
        return None;
    }
    let help = match did_you_mean(name, before.iter().map(|x| x.name.as_str())) {
        Some(b) => format!("did you mean `{b}`?"),
        None => "name an earlier unsigned integer field of this struct".to_string(),
    };
    ctx.error(
        key.span(),
        format!("no field `{name}` before `{what}`"),
        help,
    );
    None
}
