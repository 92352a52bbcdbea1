//! Rules for a link of several command formats: a serial frame format after the first that
//! carries the commands too (`commands = true`, MAVLink 1 beside MAVLink 2), which commands
//! each carries, whether a format carries extension fields (`extensions`), the syncs that
//! tell the formats apart for the link's one decoder, and the field that tells the direction
//! in each format (MSP v1 and v2 both have `direction`).

use toml::Spanned;

use super::super::Ctx;
use super::super::types::Structs;
use crate::ir::{
    AddressSet, Command, Direction, DirectionRule, Frame, PacketKind, Role, Transport,
};
use crate::spec::model::FrameDef;

/// The most command formats of a link: what the run-time codec's stream holds.
const MAX_LINK_FORMATS: usize = 8;

/// The largest value of a field of `width` bits.
fn mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// Rules: `commands = true` is for a serial frame format after the first, with a dispatch key
/// of as many fields as the first format's, in a spec whose first format has one and which
/// has no directions given to the decoder, no acknowledgements and no byte stuffing on it;
/// its sync tells it apart from the other formats of the link; directions told by a header
/// field find that field, by its name, in every format; `extensions = false` is for a format
/// that carries commands, in a spec without directions. Sets the packet kind, the direction
/// field and the commands of each such format (those whose id fits its dispatch fields, and
/// whose payload fits its bounds), and gives the link's formats.
pub(crate) fn lower_link(
    ctx: &mut Ctx<'_>,
    frames: &mut [Frame],
    commands: &[Command],
    directions: &[Direction],
    addresses: &[AddressSet],
    structs: &Structs,
) -> Vec<usize> {
    let spec = ctx.spec;
    let mut link = Vec::new();
    for (name, def) in &spec.frames {
        let def: &FrameDef = def.get_ref();
        let Some(fi) = frames.iter().position(|f| &f.name == name.get_ref()) else {
            continue;
        };
        if let Some(e) = def.extensions.as_ref().filter(|e| !*e.get_ref()) {
            let carries = def.commands.as_ref().is_some_and(|c| *c.get_ref())
                || frames[fi].packet == PacketKind::Command;
            if !carries {
                ctx.error(
                    e.span(),
                    format!("`extensions = false` on frame `{}`, which carries no commands", name.get_ref()),
                    "remove it: it says which fields of a command's payload a command format carries",
                );
            }
        }
        let Some(flag) = def.commands.as_ref().filter(|c| *c.get_ref()) else {
            continue;
        };
        let given = directions.iter().any(|d| d.rule == DirectionRule::Given);
        if let Some(why) = refusal(frames, fi, def, given, !directions.is_empty()) {
            ctx.error(
                flag.span(),
                format!("frame `{}` cannot carry the commands: {why}", name.get_ref()),
                "remove `commands = true`, or make the format a serial one with a `dispatch` key like the first format's",
            );
            continue;
        }
        if let Some(other) = sync_clash(frames, fi, &link) {
            ctx.error(
                flag.span(),
                format!(
                    "frame `{}` starts like frame `{other}`: the link's decoder could not tell their frames apart",
                    name.get_ref()
                ),
                "give the formats syncs that differ in a byte both have (MAVLink: `FE` and `FD`)",
            );
            continue;
        }
        let direction = match direction_field(&frames[fi], &frames[0], directions, addresses) {
            Ok(d) => d,
            Err(why) => {
                ctx.error(
                    flag.span(),
                    format!("frame `{}` cannot carry the commands: {why}", name.get_ref()),
                    "give every command format the field that tells the direction, under the same name and wide enough for the directions' values",
                );
                continue;
            }
        };
        if link.len() >= MAX_LINK_FORMATS {
            ctx.error(
                flag.span(),
                format!("frame `{}` would be command format number {} of the link, at most {MAX_LINK_FORMATS} are supported", name.get_ref(), link.len() + 1),
                "carry the commands in fewer frame formats",
            );
            continue;
        }
        if link.is_empty() {
            link.push(0);
        }
        link.push(fi);
        let carried = carried_commands(ctx, flag, &frames[fi], commands, structs);
        let f = &mut frames[fi];
        f.packet = PacketKind::Commands;
        f.direction = direction;
        f.commands = carried;
    }
    // The first format carries the commands whose id fits its own dispatch fields: on a link,
    // an id may fit a wider format's only.
    if let Some(first) = frames
        .first_mut()
        .filter(|f| f.packet == PacketKind::Command)
    {
        let fits = |c: &Command| {
            c.id.iter()
                .zip(&first.dispatch)
                .all(|(&v, &vi)| v <= mask(first.values[vi].width))
        };
        let carried: Vec<usize> = first
            .commands
            .iter()
            .copied()
            .filter(|&ci| commands.get(ci).is_some_and(fits))
            .collect();
        first.commands = carried;
    }
    link
}

/// Why frame `fi` cannot carry the commands, if it cannot.
fn refusal(
    frames: &[Frame],
    fi: usize,
    def: &FrameDef,
    given: bool,
    directions: bool,
) -> Option<String> {
    let (first, f) = (&frames[0], &frames[fi]);
    let why = if fi == 0 {
        "the first frame format carries them already".to_string()
    } else if first.packet != PacketKind::Command {
        format!(
            "the first frame format `{}` has no dispatch key",
            first.name
        )
    } else if f.transport != Transport::Serial {
        "a CAN frame format finds its command by the CAN id (`can_id` on each command)".to_string()
    } else if f.dispatch.len() != first.dispatch.len() {
        format!(
            "its dispatch key has {} field(s), the first format's {}",
            f.dispatch.len(),
            first.dispatch.len()
        )
    } else if def.message.is_some() {
        "it carries one `message`".to_string()
    } else if given {
        "directions given to the decoder (`given = true`) are not supported on a link of several command formats: tell them by a header field".to_string()
    } else if first.ack.is_some() || f.ack.is_some() {
        "acknowledgements are not supported on a link of several command formats".to_string()
    } else if directions && !(f.extensions && first.extensions) {
        "a format without extension fields (`extensions = false`) is not supported in a spec with directions".to_string()
    } else if f.stuffing.is_some() || first.stuffing.is_some() {
        "byte stuffing is not supported on a link of several command formats".to_string()
    } else {
        return None;
    };
    Some(why)
}

/// The header value of frame `f` that tells the directions: the user field named as the
/// first format's direction field, able to hold every direction's value; `None` in a spec
/// whose header does not tell its directions.
fn direction_field(
    f: &Frame,
    first: &Frame,
    directions: &[Direction],
    addresses: &[AddressSet],
) -> Result<Option<usize>, String> {
    let Some(name) = first.direction.map(|vi| first.values[vi].name.as_str()) else {
        return Ok(None);
    };
    let Some(vi) = f.values.iter().position(|v| v.name == name) else {
        return Err(format!(
            "it has no header field `{name}`, which tells the directions"
        ));
    };
    let v = &f.values[vi];
    if !matches!(v.role, Role::User { .. }) {
        return Err(format!(
            "its `{name}` is computed by the codec, so it cannot tell the direction"
        ));
    }
    for d in directions {
        let largest = match &d.rule {
            DirectionRule::Equals { equals, .. } => *equals,
            DirectionRule::InSet { set, .. } => addresses.get(*set).map_or(0, |a| a.last),
            DirectionRule::Given => 0,
        };
        if largest > mask(v.width) {
            return Err(format!(
                "its field `{name}` cannot hold {largest}, a value of direction `{}`",
                d.name
            ));
        }
    }
    Ok(Some(vi))
}

/// The bytes a format's frames start with, as sets of values: the sync set (if any), then
/// the sync bytes.
fn sync_pattern(f: &Frame) -> Vec<Vec<u8>> {
    let mut pattern = Vec::new();
    if !f.sync_set.is_empty() {
        pattern.push(f.sync_set.clone());
    }
    pattern.extend(f.sync.iter().map(|&b| vec![b]));
    pattern
}

/// A format of the link (the first, or one of `link`) whose sync does not differ from frame
/// `fi`'s in a byte both have.
fn sync_clash(frames: &[Frame], fi: usize, link: &[usize]) -> Option<String> {
    let mine = sync_pattern(&frames[fi]);
    let others = std::iter::once(0).chain(link.iter().copied().filter(|&i| i != 0));
    for oi in others {
        let theirs = sync_pattern(&frames[oi]);
        let differ = mine
            .iter()
            .zip(&theirs)
            .any(|(a, b)| !a.iter().any(|x| b.contains(x)));
        if !differ {
            return Some(frames[oi].name.clone());
        }
    }
    None
}

/// The commands frame `f` carries: those whose id fits its dispatch fields. A carried
/// command's payload (without extension fields, for a format without them) must fit the
/// format's payload bounds.
fn carried_commands(
    ctx: &mut Ctx<'_>,
    flag: &Spanned<bool>,
    f: &Frame,
    commands: &[Command],
    structs: &Structs,
) -> Vec<usize> {
    let mut carried = Vec::new();
    for (ci, c) in commands.iter().enumerate() {
        let fits =
            c.id.iter()
                .zip(&f.dispatch)
                .all(|(&v, &vi)| v <= mask(f.values[vi].width));
        if !fits {
            continue;
        }
        for si in c.payloads.iter().flatten() {
            let s = &structs.structs[*si];
            let size = match (f.extensions, s.base_size) {
                (false, Some(base)) => base,
                _ => s.size,
            };
            if size > f.payload_max || s.min_size.min(size) < f.payload_min {
                ctx.error(
                    flag.span(),
                    format!(
                        "command `{}` carries {size} payload bytes in frame `{}`, which carries {} to {}",
                        c.name, f.name, f.payload_min, f.payload_max
                    ),
                    "make the payload bounds of the formats and the struct agree",
                );
            }
        }
        carried.push(ci);
    }
    carried
}
