//! The frame counter of a frame format (`counter = true` on a header field, a sequence
//! number): which header value counts frames. It is decode-side statistics only (lost and reordered frames);
//! no codec checks it, so it is a plain value the sender sets in every backend.

use super::Ctx;
use crate::ir::{HeaderValue, Role};
use crate::spec::model::FrameDef;

/// Rule: `counter = true` marks at most one header field of a frame format, a whole field
/// (not one with `bits`) whose value the sender sets: not a constant, the length, a dispatch
/// key, the acknowledgement flag or the flag of an optional trailer.
pub(super) fn lower_counter(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    values: &[HeaderValue],
    ok: &mut bool,
) -> Option<usize> {
    let mut found: Option<usize> = None;
    for el in def.layout.get_ref() {
        let d = el.get_ref();
        let (Some(name), Some(flag)) = (&d.field, &d.counter) else {
            continue;
        };
        if !*flag.get_ref() {
            continue;
        }
        let mut refuse = |why: String, help: &str| {
            ctx.error(flag.span(), why, help);
            *ok = false;
        };
        if d.bits.is_some() {
            refuse(
                format!(
                    "`{}` has `bits`: a frame counter is a whole field",
                    name.get_ref()
                ),
                "put the counter in a field of its own",
            );
            continue;
        }
        let Some(vi) = values.iter().position(|v| v.name == *name.get_ref()) else {
            continue;
        };
        if !matches!(values[vi].role, Role::User { .. }) {
            refuse(
                format!(
                    "`{}` is {}: a frame counter is a value the sender sets",
                    name.get_ref(),
                    role_name(&values[vi].role)
                ),
                "mark the field that counts frames",
            );
            continue;
        }
        if found.is_some() {
            refuse(
                "a frame format has one frame counter".to_string(),
                "remove `counter` from all but one field",
            );
            continue;
        }
        found = Some(vi);
    }
    found
}

fn role_name(role: &Role) -> &'static str {
    match role {
        Role::Length | Role::WideLength => "the frame's length",
        Role::Dispatch => "a dispatch key",
        Role::Const(_) => "a constant (`value`)",
        Role::Ack(_) => "the acknowledgement flag",
        Role::Flag => "the flag of an optional trailer",
        Role::User { .. } => "a value the sender sets",
    }
}
