//! The rule of a `registers` whose run is per answering device (`BULK_READ = { ..., answers =
//! { each = "servos.id", by = "id" }, registers = { address = "servos.address", length =
//! "servos.length", answer = "data" } }`): `address` and `length` name fields of the request's
//! repeated group, the same group whose elements `answers.each` reads the ids from, so that
//! the answer of each listed device is typed by the run of its own element. Lowers it to
//! [`PerDevice`]; the fields' kinds are checked where a request's own fields are
//! ([`super::registers`]).

use toml::Spanned;

use super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::{FieldKind, PerDevice, Struct};
use crate::spec::model::{SStr, SelectDef};

/// What a `registers` names its run's fields in: the request itself, or the elements of its
/// repeated group.
pub(super) enum RunFields {
    /// `address` and `length` are fields of the request.
    Request,
    /// They are fields of the group's element (`servos.address`).
    PerDevice(PerDevice),
}

/// `path` split at its dot: the group and its element's field (`servos.address`), or the
/// request's field alone (`address`).
fn split(path: &str) -> (Option<&str>, &str) {
    match path.split_once('.') {
        Some((group, member)) => (Some(group), member),
        None => (None, path),
    }
}

/// Rule: `address` and `length` name fields of the request, or both fields of one repeated
/// group of it (`servos.address`, `servos.length`); a group only where the command's
/// `answers.each` reads the answering ids from the same group (`servos.id`). `None` after an
/// error.
pub(super) fn lower_run_fields(
    ctx: &mut Ctx<'_>,
    command: &str,
    sel: &SelectDef,
    request: &Struct,
) -> Option<RunFields> {
    let (group, _) = split(sel.address.get_ref());
    if let Some(length) = &sel.length {
        let (other, _) = split(length.get_ref());
        if other != group {
            let place = |g: Option<&str>| match g {
                Some(g) => format!("a field of its group `{g}`"),
                None => "a field of the request".to_string(),
            };
            ctx.error(
                length.span(),
                format!(
                    "`length` names {}, but `address` names {}",
                    place(other),
                    place(group)
                ),
                "name both in the request (`address`, `length`) or both in one group (`servos.address`, `servos.length`)",
            );
            return None;
        }
    }
    let Some(group) = group else {
        return Some(RunFields::Request);
    };
    let element = group_element(ctx, &sel.address, group, request)?;
    let id = answering_member(ctx, command, &sel.address, group)?;
    Some(RunFields::PerDevice(PerDevice {
        group: group.to_string(),
        element,
        id,
    }))
}

/// Rule: the group a path names is a repeated struct field of the request; gives its element.
fn group_element(ctx: &mut Ctx<'_>, path: &SStr, group: &str, request: &Struct) -> Option<usize> {
    let Some(f) = request.fields.iter().find(|f| f.name == group) else {
        let help = match did_you_mean(group, request.fields.iter().map(|f| f.name.as_str())) {
            Some(b) => format!("did you mean `{b}`?"),
            None => format!("name a repeated field of `{}`", request.name),
        };
        ctx.error(
            path.span(),
            format!("the request `{}` has no field `{group}`", request.name),
            help,
        );
        return None;
    };
    if let FieldKind::Group { elem, .. } = f.kind {
        return Some(elem);
    }
    ctx.error(
        path.span(),
        format!(
            "field `{group}` of `{}` is not a repeated struct, so it lists no devices",
            request.name
        ),
        "name a field of the request itself, or a field of the elements of a group (`servos.address`)",
    );
    None
}

/// Rule: a run per device needs the command's `answers`, which reads the ids from the same
/// group: gives the element's id field (`answers.each`'s member).
fn answering_member(ctx: &mut Ctx<'_>, command: &str, path: &SStr, group: &str) -> Option<String> {
    let spec = ctx.spec;
    let answers = spec
        .commands
        .iter()
        .find(|(n, _)| n.get_ref() == command)
        .and_then(|(_, d)| d.get_ref().answers.as_ref())
        .map(Spanned::get_ref);
    let Some(each) = answers.map(|a| a.each.get_ref().as_str()) else {
        ctx.error(
            path.span(),
            format!(
                "`{}` selects a run per device, but command `{command}` lists no devices that answer it (`answers`)",
                path.get_ref()
            ),
            format!(
                "list them in the same group (`answers = {{ each = \"{group}.id\", by = \"id\" }}`), or name a field of the request"
            ),
        );
        return None;
    };
    // A request has one repeated group (its last field), so an `answers.each` that does not
    // walk this group is itself an error, which the rule of `answers` reports.
    match split(each) {
        (Some(g), member) if g == group => Some(member.to_string()),
        _ => None,
    }
}

/// The struct whose fields `address` and `length` name.
pub(super) fn run_struct<'a>(
    run: &RunFields,
    request: &'a Struct,
    structs: &'a [Struct],
) -> Option<&'a Struct> {
    match run {
        RunFields::Request => Some(request),
        RunFields::PerDevice(p) => structs.get(p.element),
    }
}

/// The field a path names in its struct, at the path's place in the spec.
pub(super) fn member(path: &SStr) -> SStr {
    Spanned::new(path.span(), split(path.get_ref()).1.to_string())
}
