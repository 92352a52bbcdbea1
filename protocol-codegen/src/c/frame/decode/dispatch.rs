//! Which command and direction a checked frame is, as the decoder of one frame reads them:
//! the direction the caller gives (and a direction's one struct, read where the dispatch key
//! would be), the direction from the header's tests, the command of a dispatch key, and the
//! command of a CAN id. The reading of the rest of the frame is the parent module's.

use protocol_runtime::rules::DirectionTest;

use crate::ir::Protocol;

use super::super::wire::{field_word, truncate, truncated};
use super::body_len;
use crate::c::names::{self, Fx, Names};
use crate::c::template::fill;

/// The direction the decoder is given: none is an unknown direction; a direction whose frames
/// carry one struct reads it from where the dispatch key would be.
pub(super) fn given_direction(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    out.push_str(&fill!(
        r"
    if ((int)direction < 0 || direction >= ${up}DIRECTION_COUNT) return ${up}ERR_UNKNOWN_DIRECTION;
    out->direction = direction;
",
        up
    ));
    for d in &p.directions {
        let Some((si, start)) = d.message else {
            continue;
        };
        let (direction, name) = (d.name.to_uppercase(), &d.name);
        let snake = names::snake(&p.structs[si].name);
        out.push_str(&fill!(
            r"
    if (direction == ${up}${direction}) {
        out->command = ${up}COMMAND_COUNT; /* none */
        if (end < ${start}u) return ${up}ERR_FRAME;
        r.p = bytes + ${start}u;
        r.len = end - ${start}u;
        r.pos = 0;
        memset(&out->payload.${name}, 0, sizeof out->payload.${name});
        if ((e = ${lo}read_${snake}(&r, &out->payload.${name})) != 0) return e;
        return r.pos != r.len ? ${up}ERR_PAYLOAD_LENGTH : 0;
    }
",
            up,
            direction,
            start,
            name,
            lo,
            snake
        ));
    }
}

/// The direction from the header of format `x`, its rules' tests in order (on a link, each
/// command format names its own direction field). The bounds are in the header value's type;
/// the value read is truncated to it.
pub(super) fn directions(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
    if x.rules.directions.is_empty() {
        return;
    }
    let len = body_len(p, x);
    out.push_str("    ");
    for (d, &(value, test)) in p.directions.iter().zip(&x.rules.directions) {
        let bits = truncated(&f.values[value], "raw");
        let cond = match test {
            // A range from 0 has no lower test: an unsigned value is never below it (and C
            // compilers warn of a comparison that is always true).
            DirectionTest::InRange {
                field,
                first: 0,
                last,
            } => {
                let (word, last) = (field_word(field), names::u64_lit(last));
                fill!(
                    "${lo}field(bytes, ${len}, ${word}, &raw) && ${bits} <= ${last}",
                    lo,
                    len,
                    word,
                    bits,
                    last
                )
            }
            DirectionTest::InRange { field, first, last } => {
                let (word, first, last) = (
                    field_word(field),
                    names::u64_lit(first),
                    names::u64_lit(last),
                );
                fill!(
                    "${lo}field(bytes, ${len}, ${word}, &raw) && ${bits} >= ${first} && ${bits} <= ${last}",
                    lo,
                    len,
                    word,
                    bits,
                    first,
                    last
                )
            }
            DirectionTest::Equals { field, value } => {
                let (word, equals) = (field_word(field), names::u64_lit(value));
                fill!(
                    "${lo}field(bytes, ${len}, ${word}, &raw) && ${bits} == ${equals}",
                    lo,
                    len,
                    word,
                    bits,
                    equals
                )
            }
        };
        let direction = d.name.to_uppercase();
        out.push_str(&fill!(
            "if (${cond}) out->direction = ${up}${direction};\n    else ",
            cond,
            up,
            direction
        ));
    }
    out.push_str(&fill!("return ${up}ERR_UNKNOWN_DIRECTION;\n", up));
}

/// The dispatch key, one variable per field of the rules' key (each truncated to its header
/// value's type), then the command it names among those the format carries.
pub(super) fn dispatch_key(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
    let key = &x.rules.key;
    let fields = key.len();
    out.push_str(&fill!(
        r"
    {
        uint64_t key[${fields}];
",
        fields
    ));
    for (k, field) in key.iter().enumerate() {
        let (word, bits) = (
            field_word(field.field),
            truncated(&f.values[field.value], "raw"),
        );
        out.push_str(&fill!(
            r"
        if (!${lo}field(bytes, len, ${word}, &raw)) return ${up}ERR_FRAME;
        key[${k}] = ${bits};
",
            lo,
            word,
            up,
            k,
            bits
        ));
    }
    let carried = |ci: usize| f.commands.contains(&ci);
    if let [field] = key[..] {
        // One key field: a switch (a jump table where the ids are dense).
        let vi = field.value;
        let narrow = f.values[vi].prim.size() <= 4;
        let cast = if narrow { "(uint32_t)" } else { "" };
        out.push_str(&fill!("        switch (${cast}key[0]) {\n", cast));
        for (ci, c) in p.commands.iter().enumerate() {
            if !carried(ci) || c.id.len() != 1 {
                continue;
            }
            let id = truncate(f.values[vi].prim, c.id[0]);
            let label = if narrow {
                format!("{id:#x}u")
            } else {
                names::u64_lit(id)
            };
            let name = &c.name;
            out.push_str(&fill!(
                "        case ${label}: out->command = ${up}${name}; break;\n",
                label,
                up,
                name
            ));
        }
        out.push_str(&fill!(
            r"
        default: return ${up}ERR_UNKNOWN_COMMAND;
        }
    }
",
            up
        ));
        return;
    }
    out.push_str("        ");
    for (ci, c) in p.commands.iter().enumerate() {
        if !carried(ci) || c.id.len() != fields {
            continue;
        }
        let conds: Vec<String> = key
            .iter()
            .zip(&c.id)
            .enumerate()
            .map(|(k, (field, id))| {
                let v = &f.values[field.value];
                format!("key[{k}] == {}", names::u64_lit(truncate(v.prim, *id)))
            })
            .collect();
        let (conds, name) = (conds.join(" && "), &c.name);
        out.push_str(&fill!(
            "if (${conds}) out->command = ${up}${name};\n        else ",
            conds,
            up,
            name
        ));
    }
    out.push_str(&fill!(
        r"
return ${up}ERR_UNKNOWN_COMMAND;
    }
",
        up
    ));
}

/// The command of a CAN frame: the one whose CAN id is the rules' key, the frame's whole
/// identifier word (bits above the id's width, which no bus delivers, name no command).
pub(super) fn can_command(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let [id] = x.rules.key[..] else {
        return;
    };
    let word = field_word(id.field);
    out.push_str(&fill!(
        "    if (!${lo}field(bytes, len, ${word}, &raw)) return ${up}ERR_FRAME;\n    ",
        lo,
        word,
        up
    ));
    for c in &p.commands {
        if let Some(id) = c.can_id {
            let (id, name) = (names::u64_lit(id), &c.name);
            out.push_str(&fill!(
                "if (raw == ${id}) out->command = ${up}${name};\n    else ",
                id,
                up,
                name
            ));
        }
    }
    out.push_str(&fill!("return ${up}ERR_UNKNOWN_COMMAND;\n", up));
}
