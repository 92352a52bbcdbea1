//! Rules for the members of a CAN identifier (`can_id_bits`): the identifier split into named
//! header values (DroneCAN's priority, message type and source node; ODrive's node and command
//! ids), each read and written through the virtual identifier word, so that dispatch, constants
//! and the header struct treat them as any header field's members.

use toml::Spanned;

use super::super::Ctx;
use super::super::types::{Enums, MemberSite, lower_bits, mask};
use super::Draft;
use crate::ir::{HeaderValue, Pos, Role, Scalar, Transport};
use crate::spec::model::{BitDef, FrameDef};

/// The members of a CAN identifier as written.
type Members = Spanned<Vec<Spanned<BitDef>>>;

/// Rule: `can_id_bits` applies to CAN frames, and only to the first frame format: a CAN
/// format after the first finds its command by the whole identifier (`can_id` on each
/// command), so its identifier cannot also hold other header values.
pub(super) fn check_members_placement(ctx: &mut Ctx<'_>, def: &FrameDef, first: bool) {
    let Some(bits) = &def.can_id_bits else {
        return;
    };
    let on_can = def.transport.as_ref().is_some_and(|t| t.get_ref() == "can");
    if !on_can {
        ctx.error(
            bits.span(),
            "`can_id_bits` applies to CAN frames",
            "add `transport = \"can\"` or remove `can_id_bits`",
        );
    } else if !first {
        ctx.error(
            bits.span(),
            "`can_id_bits` applies to the first frame format: a CAN format after the first finds its command by the whole CAN id",
            "make this CAN format the spec's first `[frames.NAME]` table (a CAN-only link), or remove `can_id_bits` and give each command its `can_id`",
        );
    }
}

/// Rule: the members of a CAN identifier follow the bit-member rules, hold no length (the DLC
/// is the data length), and together cover exactly the identifier's `width` bits (11 or 29),
/// so that every identifier decodes to members and encodes back to itself; a member with
/// `value` is a constant the decoder verifies (DroneCAN's service flag of a message frame).
/// Gives the indices of the members' values in `values`.
pub(super) fn lower_id_members(
    ctx: &mut Ctx<'_>,
    values: &mut Vec<HeaderValue>,
    bits: &Members,
    word: Scalar,
    transport: Transport,
    enums: &Enums,
) -> Vec<usize> {
    let width: u32 = match transport {
        Transport::Can { extended: true } => 29,
        _ => 11,
    };
    let no_length = |b: &BitDef| {
        b.length_of
            .is_some()
            .then_some("a member of the CAN id cannot be the length: the DLC is the data length")
    };
    // The members are header values of a 32-bit word: signed and scaled members are refused,
    // as in any header word.
    let members = lower_bits(
        ctx,
        bits.get_ref(),
        32,
        MemberSite::Header,
        enums,
        &no_length,
    );
    let total: u32 = members.iter().map(|m| m.width).sum();
    if total != width && members.len() == bits.get_ref().len() {
        let kind = if width == 29 {
            "an extended"
        } else {
            "a standard"
        };
        let help = if total > width {
            "shrink the members, or use `can_id = \"extended\"` for a 29-bit id".to_string()
        } else {
            format!(
                "add a member for the top {} bit(s) (with `value = 0` if they are reserved)",
                width - total
            )
        };
        ctx.error(
            bits.span(),
            format!(
                "the members of the CAN id add up to {total} bits, but {kind} CAN id has {width}"
            ),
            help,
        );
    }
    let mut idx = Vec::new();
    for (m, bdef) in members.into_iter().zip(bits.get_ref()) {
        let role = match &bdef.get_ref().value {
            Some(v) if *v.get_ref() < 0 || (*v.get_ref() as u64) > mask(m.width) => {
                ctx.error(
                    v.span(),
                    format!(
                        "value {} does not fit in `{}` ({} bits)",
                        v.get_ref(),
                        m.name,
                        m.width
                    ),
                    "use a smaller value or more bits",
                );
                Role::Const(0)
            }
            Some(v) => Role::Const(*v.get_ref() as u64),
            None => Role::User { addresses: false },
        };
        idx.push(values.len());
        values.push(HeaderValue {
            name: m.name,
            doc: m.doc,
            at: Pos::Start(0),
            word,
            shift: m.shift,
            width: m.width,
            prim: m.prim,
            role,
        });
    }
    idx
}

/// Rule: a member of the CAN id is not named as another header value of the frame (a layout
/// field or one of its members, or the virtual `dlc`): both would be fields of the header
/// struct.
pub(super) fn check_member_names(ctx: &mut Ctx<'_>, def: &FrameDef, draft: &Draft<'_>) {
    let (Some(bits), Transport::Can { .. }) = (&def.can_id_bits, draft.transport) else {
        return;
    };
    let values = &draft.values;
    for b in bits.get_ref() {
        let name = &b.get_ref().name;
        let named = |n: &String| n == name.get_ref();
        // A name repeated among the members themselves is the bit-member rule's error.
        let members = bits
            .get_ref()
            .iter()
            .filter(|m| named(m.get_ref().name.get_ref()));
        let others = values
            .iter()
            .filter(|v| named(&v.name))
            .count()
            .saturating_sub(members.count().min(1));
        if name.get_ref() == "can_id" {
            ctx.error(
                name.span(),
                "a member of the CAN id cannot be named `can_id`",
                "`can_id` is the whole identifier (a decoded frame shows it under that name); name the member after what it holds",
            );
        } else if others > 0 {
            ctx.error(
                name.span(),
                format!(
                    "member `{}` of the CAN id is also a header value of the frame",
                    name.get_ref()
                ),
                "rename one: the members of the CAN id are fields of the frame's header",
            );
        }
    }
}
