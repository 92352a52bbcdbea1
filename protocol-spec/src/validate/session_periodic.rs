//! Rules of `[session] periodic` (`periodic = [{ command = "HEARTBEAT", period_ms = 1000 }]`):
//! each entry names a command, once, with a period in range and the side that sends it; the
//! list fits the runtime's table. Lowers them to [`ir::Periodic`]s.

use toml::Spanned;

use super::Ctx;
use super::session::{command, ms};
use crate::diag::did_you_mean;
use crate::ir::{self, Periodic};
use crate::spec::model::{PeriodicDef, SStr};
use protocol_runtime::session::Sender;

/// The most periodic commands a spec lists.
const MAX_PERIODIC: usize = 16;

/// The `periodic` list, lowered, in spec order; `None` after an error.
pub(super) fn lower_periodic(
    ctx: &mut Ctx<'_>,
    list: Option<&Spanned<Vec<Spanned<PeriodicDef>>>>,
    commands: &[ir::Command],
) -> Option<Vec<Periodic>> {
    let Some(list) = list else {
        return Some(Vec::new());
    };
    // Rule: at most `MAX_PERIODIC` commands.
    if list.get_ref().len() > MAX_PERIODIC {
        ctx.error(
            list.span(),
            format!(
                "`periodic` lists {} commands; a side sends at most {MAX_PERIODIC} at a rate",
                list.get_ref().len()
            ),
            "keep the commands the link needs at a fixed rate",
        );
        return None;
    }
    let mut out: Vec<Periodic> = Vec::new();
    let mut ok = true;
    for entry in list.get_ref() {
        let e = entry.get_ref();
        let ci = command(ctx, &e.command, commands, "name a command of `[commands]`");
        let period = ms(ctx, &e.period_ms, "period_ms");
        let sender = e
            .sender
            .as_ref()
            .map_or(Some(Sender::Both), |s| sender(ctx, s));
        let (Some(ci), Some(period_ms), Some(sender)) = (ci, period, sender) else {
            ok = false;
            continue;
        };
        // Rule: a command is listed once (one rate per command).
        if out.iter().any(|p| p.command == ci) {
            ctx.error(
                e.command.span(),
                format!("`{}` is listed twice in `periodic`", e.command.get_ref()),
                "give each command one rate: remove one of the entries",
            );
            ok = false;
            continue;
        }
        out.push(Periodic {
            command: ci,
            period_ms,
            sender,
            doc: super::text(&e.doc),
        });
    }
    ok.then_some(out)
}

/// Rule: `sender` is `"requester"`, `"responder"` or `"both"`.
fn sender(ctx: &mut Ctx<'_>, s: &SStr) -> Option<Sender> {
    const NAMES: [&str; 3] = ["requester", "responder", "both"];
    match s.get_ref().as_str() {
        "requester" => Some(Sender::Requester),
        "responder" => Some(Sender::Responder),
        "both" => Some(Sender::Both),
        other => {
            let help = match did_you_mean(other, NAMES.iter().copied()) {
                Some(b) => format!("did you mean `{b}`?"),
                None => "write `requester`, `responder` or `both`".to_string(),
            };
            ctx.error(s.span(), format!("unknown sender `{other}`"), help);
            None
        }
    }
}
