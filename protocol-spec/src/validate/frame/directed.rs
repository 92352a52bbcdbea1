//! Header fields of one direction only (`direction = "response"` on a layout element): the
//! rules that say where such a field may stand, and the lowering of the first frame format
//! once per direction that has one, so that the IR holds each direction's own layout
//! ([`Direction::frame`](crate::ir::Direction::frame)). The format itself (`Protocol::frames`)
//! is lowered without them: it is the layout of every other direction.
//!
//! Such a field needs directions the decoder is given: when a header field tells the
//! directions, the decoder reads that field before it knows the direction, so every header
//! value before it would have to sit at one place in both directions, and the layout could
//! not say which.

use toml::Spanned;

use super::super::types::{Enums, Structs};
use super::super::{Ctx, extra};
use super::lower_frame;
use crate::diag::{Diagnostics, did_you_mean};
use crate::ir::{Command, Direction, Frame};
use crate::spec::model::{ElementDef, FrameDef, SStr};

/// The elements of a frame format that belong to one direction, with the direction's name.
fn directed(def: &FrameDef) -> impl Iterator<Item = (&Spanned<ElementDef>, &SStr)> {
    def.layout
        .get_ref()
        .iter()
        .filter_map(|el| Some((el, el.get_ref().direction.as_ref()?)))
}

/// Whether element `el` belongs in the frames of direction `direction` (`None`: the format's
/// own layout, which has only the elements of every direction).
pub(super) fn in_direction(el: &ElementDef, direction: Option<&str>) -> bool {
    match &el.direction {
        None => true,
        Some(d) => Some(d.get_ref().as_str()) == direction,
    }
}

/// The rules of the fields of one direction of the first frame format, each reported; false
/// when one fails.
pub(super) fn check_directed(ctx: &mut Ctx<'_>, def: &FrameDef) -> bool {
    let mut ok = true;
    for (el, dir) in directed(def) {
        ok &= check_direction_given(ctx, dir);
        ok &= check_directed_role(ctx, def, el);
        ok &= check_not_an_end(ctx, def, el);
    }
    ok
}

/// The first frame format as each direction that has fields of its own lays it out, in the
/// order of `[directions]`: `(direction, frame)`, once [`check_directed`] has passed. The
/// second lowering reports only errors the first could not see (those of the directed fields
/// themselves): `base_ok` says whether the first lowering succeeded.
pub(super) fn lower_directed(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    structs: &Structs,
    enums: &Enums,
    base_ok: bool,
) -> Vec<(String, Frame)> {
    if !base_ok {
        return Vec::new();
    }
    let spec = ctx.spec;
    let mut out = Vec::new();
    for name in spec.directions.keys().map(|k| k.get_ref()) {
        if !directed(def).any(|(_, d)| d.get_ref() == name) {
            continue;
        }
        let mut scratch = Diagnostics::new();
        let mut inner = Ctx {
            spec,
            diags: &mut scratch,
            default_endian: ctx.default_endian,
            foreign: ctx.foreign,
        };
        let frame = lower_frame(&mut inner, fname, true, def, structs, enums, Some(name));
        for d in scratch.into_sorted() {
            ctx.diags.push(d);
        }
        if let Some(f) = frame {
            out.push((name.clone(), f));
        }
    }
    out
}

/// Rule: a layout element of one direction belongs to the first frame format (the one the
/// directions apply to).
pub(super) fn check_first_format(ctx: &mut Ctx<'_>, def: &FrameDef, first: bool) {
    if first {
        return;
    }
    for (_, dir) in directed(def) {
        ctx.error(
            dir.span(),
            "only the first frame format has fields of one direction",
            "the directions apply to the first frame format: move the field there, or drop `direction`",
        );
    }
}

/// Rule: `direction` names a direction of `[directions]` that the decoder is given (`given =
/// true`): a direction a header field tells is read before the decoder knows it, so the
/// fields before that one could not differ by direction.
fn check_direction_given(ctx: &mut Ctx<'_>, dir: &SStr) -> bool {
    let spec = ctx.spec;
    let Some((_, def)) = spec
        .directions
        .iter()
        .find(|(k, _)| k.get_ref() == dir.get_ref())
    else {
        let names = spec.directions.keys().map(|k| k.get_ref().as_str());
        let help = match did_you_mean(dir.get_ref(), names) {
            Some(b) => format!("did you mean `{b}`?"),
            None if spec.directions.is_empty() => "declare the directions under `[directions]` (`request = { given = true }`, `response = { given = true }`), or drop `direction`".to_string(),
            None => "name a direction of `[directions]`".to_string(),
        };
        ctx.error(
            dir.span(),
            format!("no direction `{}` in `[directions]`", dir.get_ref()),
            help,
        );
        return false;
    };
    let d = def.get_ref();
    if d.given.as_ref().is_some_and(|g| *g.get_ref()) && d.message.is_none() {
        return true;
    }
    let (message, help) = if d.message.is_some() {
        (
            format!(
                "direction `{}` carries one struct (`message`), so it has no fields of its own",
                dir.get_ref()
            ),
            "its struct takes the bytes after the header: make the field the struct's first field instead",
        )
    } else {
        (
            format!(
                "direction `{}` is told by a header field, so no field can belong to it alone",
                dir.get_ref()
            ),
            "a decoder reads the header before it knows the direction: give the decoder the directions (`given = true` on each) when the header differs by direction",
        )
    };
    ctx.error(dir.span(), message, help);
    false
}

/// Rule: a field of one direction is a value its sender sets or a constant: not a dispatch
/// key, the length, the sync, a wider length or a frame counter, which every direction's
/// decoder needs at one place.
fn check_directed_role(ctx: &mut Ctx<'_>, def: &FrameDef, el: &Spanned<ElementDef>) -> bool {
    let e = el.get_ref();
    let Some(name) = &e.field else {
        // Another kind's `direction` is refused as a key that does not apply to it.
        return true;
    };
    let dispatch = def
        .dispatch
        .as_ref()
        .is_some_and(|d| d.get_ref().iter().any(|k| k.get_ref() == name.get_ref()));
    let role = if dispatch {
        Some("a dispatch key")
    } else if e.length_of.is_some() {
        Some("the frame's length")
    } else if e.one_of.is_some() {
        Some("the sync")
    } else if e.extends.is_some() {
        Some("a wider length")
    } else if e.counter.is_some() {
        Some("the frame counter")
    } else {
        None
    };
    let Some(role) = role else {
        return true;
    };
    ctx.error(
        name.span(),
        format!(
            "field `{}` belongs to one direction, so it cannot be {role}",
            name.get_ref()
        ),
        "every direction's decoder reads it at one place: drop `direction`, or make the field a value its sender sets",
    );
    false
}

/// Rule: no run of another element (`length_of`, `over`) starts or ends at a field of one
/// direction: the other directions' frames do not have it, so the run would name nothing
/// there (a run that passes over it covers it where it is).
fn check_not_an_end(ctx: &mut Ctx<'_>, def: &FrameDef, el: &Spanned<ElementDef>) -> bool {
    let Some(name) = &el.get_ref().field else {
        return true;
    };
    let mut ok = true;
    for other in def.layout.get_ref() {
        let o = other.get_ref();
        for run in [&o.length_of, &o.over].into_iter().flatten() {
            if run
                .get_ref()
                .split("..")
                .any(|end| end.trim() == name.get_ref())
            {
                ctx.error(
                    run.span(),
                    format!(
                        "this run ends at `{}`, which only {} frames have",
                        name.get_ref(),
                        el.get_ref().direction.as_ref().map_or("", |d| d.get_ref().as_str())
                    ),
                    "end the run at an element every direction has: a run over it covers it in the frames that have it",
                );
                ok = false;
            }
        }
    }
    ok
}

/// Gives each direction its own layout of the first frame format, lowered by
/// [`lower_directed`], with what the format decided once the commands were known (its packet
/// kind, the commands it carries, the bytes a check folds in per command): a direction's
/// layout differs from the format's in its fields' places alone.
pub(crate) fn attach_own_layouts(
    directions: &mut [Direction],
    own: Vec<(String, Frame)>,
    frames: &[Frame],
    commands: &[Command],
) {
    let Some(first) = frames.first() else {
        return;
    };
    for (name, mut f) in own {
        let Some(d) = directions.iter_mut().find(|d| d.name == name) else {
            continue;
        };
        f.packet = first.packet;
        f.commands.clone_from(&first.commands);
        f.direction = first.direction;
        extra::lower_extra_bytes(std::slice::from_mut(&mut f), commands);
        d.frame = Some(f);
    }
}
