//! Rules for a frame format's settings outside its layout: the transport.

use super::super::Ctx;
use crate::diag::did_you_mean;
use crate::ir::Transport;
use crate::spec::model::FrameDef;

/// Rule: `transport` is `"serial"` (default) or `"can"`; `can_id` (`"standard"` or
/// `"extended"`) applies to CAN frames only.
pub(super) fn lower_transport(ctx: &mut Ctx<'_>, def: &FrameDef) -> Transport {
    let extended = match def.can_id.as_ref().map(|c| (c, c.get_ref().as_str())) {
        None | Some((_, "standard")) => false,
        Some((_, "extended")) => true,
        Some((c, other)) => {
            ctx.error(
                c.span(),
                format!("unknown CAN id kind `{other}`"),
                "write `\"standard\"` (11-bit ids) or `\"extended\"` (29-bit ids)",
            );
            false
        }
    };
    match def.transport.as_ref().map(|t| (t, t.get_ref().as_str())) {
        None | Some((_, "serial")) => {
            if let Some(c) = &def.can_id {
                ctx.error(
                    c.span(),
                    "`can_id` applies to CAN frames",
                    "add `transport = \"can\"` or remove `can_id`",
                );
            }
            Transport::Serial
        }
        Some((_, "can")) => Transport::Can { extended },
        Some((t, other)) => {
            let help = match did_you_mean(other, ["serial", "can"]) {
                Some(b) => format!("did you mean `{b}`?"),
                None => "write `\"serial\"` (a byte stream) or `\"can\"`".to_string(),
            };
            ctx.error(t.span(), format!("unknown transport `{other}`"), help);
            Transport::Serial
        }
    }
}
