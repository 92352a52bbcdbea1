//! Rules for a frame format's settings outside its layout: the transport, byte stuffing,
//! trailing-zero truncation and the one message of a frame format without dispatch key.

use super::super::Ctx;
use super::super::types::Structs;
use super::elements::byte_list;
use super::length::Layout;
use crate::diag::did_you_mean;
use crate::ir::Transport;
use crate::spec::model::{FrameDef, SStr};

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

/// Rule: stuffing names a non-empty pattern of bytes and a byte to insert.
pub(super) fn lower_stuffing(ctx: &mut Ctx<'_>, def: &FrameDef) -> Option<(Vec<u8>, u8)> {
    let d = def.stuffing.as_ref()?.get_ref();
    let after = byte_list(ctx, &d.after, "the stuffing pattern");
    match u8::try_from(*d.insert.get_ref()) {
        Ok(insert) if !after.is_empty() => Some((after, insert)),
        Ok(_) => None,
        Err(_) => {
            ctx.error(
                d.insert.span(),
                format!("{} is not a byte", d.insert.get_ref()),
                "use a value from 0x00 to 0xFF",
            );
            None
        }
    }
}

/// Rule: a frame format without a dispatch key may name the struct every frame carries; it
/// must fit the payload's bounds.
pub(super) fn lower_message(
    ctx: &mut Ctx<'_>,
    fname: &SStr,
    def: &FrameDef,
    dispatch: &[usize],
    structs: &Structs,
    lay: &Layout<'_, '_>,
    ok: &mut bool,
) -> Option<usize> {
    let m = def.message.as_ref()?;
    let (payload_min, payload_max) = (lay.payload_min, lay.payload_max);
    if !dispatch.is_empty() || def.dispatch.is_some() {
        ctx.error(
            m.span(),
            "a frame format has either a dispatch key or one `message`",
            "remove `dispatch` (every frame carries this struct) or `message`",
        );
        *ok = false;
        return None;
    }
    let Some(&i) = structs.by_name.get(m.get_ref()) else {
        let help = match did_you_mean(m.get_ref(), structs.structs.iter().map(|s| s.name.as_str()))
        {
            Some(b) => format!("did you mean `{b}`?"),
            None => "declare it as `[structs.NAME]`".to_string(),
        };
        ctx.error(m.span(), format!("unknown struct `{}`", m.get_ref()), help);
        *ok = false;
        return None;
    };
    let st = &structs.structs[i];
    if st.min_size < payload_min || st.min_size > payload_max || (st.size < payload_min) {
        ctx.error(m.span(), format!("struct `{}` takes {} to {} bytes, but frame `{}` carries {payload_min} to {payload_max}", st.name, st.min_size, st.size, fname.get_ref()), "make the payload bounds and the struct agree");
        *ok = false;
    }
    Some(i)
}

/// Rule: trailing-zero truncation applies to command payloads: the first frame format, which
/// has a dispatch key and travels as a byte stream (the structs it zero-fills must have a
/// fixed size: checked with the commands).
pub(super) fn lower_truncate_zeros(
    ctx: &mut Ctx<'_>,
    def: &FrameDef,
    first: bool,
    transport: Transport,
    ok: &mut bool,
) -> bool {
    let Some(t) = def.truncate_zeros.as_ref() else {
        return false;
    };
    if !*t.get_ref() {
        return false;
    }
    let why = if !first {
        Some("only the first frame format carries commands whose payloads can be zero-filled")
    } else if def.dispatch.is_none() {
        Some("a frame format without a dispatch key carries no command payloads")
    } else if transport != Transport::Serial {
        Some("a CAN frame's data length is its DLC, which truncation would not save")
    } else if def.stuffing.is_some() {
        Some("byte stuffing and trailing-zero truncation of one payload are not supported together")
    } else {
        None
    };
    match why {
        Some(why) => {
            ctx.error(
                t.span(),
                format!("`truncate_zeros` does not apply here: {why}"),
                "remove `truncate_zeros`, or move it to the first frame format (a serial one with `dispatch`)",
            );
            *ok = false;
            false
        }
        None => true,
    }
}
