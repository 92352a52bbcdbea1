//! Rules for the per-command byte a check folds in (`extra = "command"` on a check,
//! `check_extra` on each command): every command of such a spec declares its byte, no other
//! spec has one, and the frame's table of bytes is built from the commands.

use super::Ctx;
use crate::ir::{Command, DIRECT_KEYS, Frame};
use crate::spec::model::{CommandDef, SStr, SpecFile};

/// Whether any check of the spec declares a per-command extra byte (as written: a check whose
/// `extra` is wrong has its own error, and its commands are checked as if it were right).
fn has_extra(spec: &SpecFile) -> bool {
    spec.frames.values().any(|f| {
        f.get_ref()
            .layout
            .get_ref()
            .iter()
            .any(|e| e.get_ref().extra.is_some())
    })
}

/// Rule: when a check folds in a per-command byte, every command declares `check_extra`, a
/// byte (0 to 255); otherwise no command declares one.
pub(crate) fn lower_check_extra(ctx: &mut Ctx<'_>, name: &SStr, d: &CommandDef) -> Option<u8> {
    let wanted = has_extra(ctx.spec);
    match &d.check_extra {
        None if wanted => {
            ctx.error(
                name.span(),
                format!("command `{}` has no `check_extra`", name.get_ref()),
                "a check of this spec folds in a byte per command (`extra = \"command\"`): add `check_extra = N` (0 to 255) to the command",
            );
            None
        }
        None => None,
        Some(v) if !wanted => {
            ctx.error(
                v.span(),
                format!(
                    "command `{}` declares `check_extra`, but no check folds it in",
                    name.get_ref()
                ),
                "add `extra = \"command\"` to the check that folds it in, or remove `check_extra`",
            );
            None
        }
        Some(v) => match u8::try_from(*v.get_ref()) {
            Ok(b) => Some(b),
            Err(_) => {
                ctx.error(
                    v.span(),
                    format!("`check_extra` {} is not a byte", v.get_ref()),
                    "use a value from 0 to 255",
                );
                None
            }
        },
    }
}

/// Each per-command extra byte table: `(id, byte)` of every command the frame format carries
/// (every command, for a format that carries none: its key then finds no byte), sorted by id,
/// and the ids below the largest one under [`DIRECT_KEYS`] read from a table indexed by id.
pub(crate) fn lower_extra_bytes(frames: &mut [Frame], commands: &[Command]) {
    for f in frames {
        let mut bytes: Vec<(u32, u8)> = commands
            .iter()
            .enumerate()
            .filter(|(ci, _)| f.commands.is_empty() || f.commands.contains(ci))
            .filter_map(|(_, c)| {
                let id = u32::try_from(*c.id.first()?).ok()?;
                Some((id, c.check_extra?))
            })
            .collect();
        bytes.sort_unstable();
        let direct = bytes
            .iter()
            .map(|&(id, _)| id)
            .take_while(|&id| id < DIRECT_KEYS)
            .last()
            .map_or(0, |id| id as usize + 1);
        for c in &mut f.checks {
            if let Some(extra) = &mut c.extra {
                extra.bytes.clone_from(&bytes);
                extra.direct = direct;
            }
        }
    }
}
