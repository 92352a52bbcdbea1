//! Packets carried inside a payload (`carries`): per carrying field, a function that reads
//! the packet a decoded carrying struct carries (`NAME_read_carried_<struct>_<field>()`,
//! `templates/carried.c`), as generated Rust's `<field>_<direction>()` does: one level (a
//! carrier inside it keeps its bytes), no allocation. The command is the one whose id the key
//! field holds, among all of the spec's; the packet is read into the packet type of the first
//! format that carries every command ([`carried_format`]), whose union has a member for each.

use crate::ir::{Carried, Protocol, Struct};

use super::names::{self, Fx, Names};
use super::shape::slots_of;
use super::template::fill;

/// The first frame format whose packets carry every command of the spec: the type a carried
/// packet is read into. `None` when no format does (the C printer refuses carriers then).
pub fn carried_format(p: &Protocol) -> Option<usize> {
    (0..p.frames.len()).find(|&fi| {
        let x = Fx::new(p, fi);
        let slots = slots_of(p, &x);
        (0..p.commands.len()).all(|ci| slots.iter().any(|s| s.command == Some(ci)))
    })
}

/// The name of the reader of carried packet `c` of struct `s`
/// (`NAME_read_carried_<struct>_<field>`).
pub fn carried_reader(p: &Protocol, s: &Struct, c: &Carried) -> String {
    let n = Names::new(p);
    let (snake, field) = (names::snake(&s.name), names::field(&s.fields[c.field].name));
    format!("{}read_carried_{snake}_{field}", n.lo)
}

/// The functions' parameters before the packet: the direction, for a spec with directions.
fn params(p: &Protocol, n: &Names) -> String {
    if p.directions.is_empty() {
        String::new()
    } else {
        format!("{}direction direction, ", n.lo)
    }
}

/// The prototype of every carried packet's reader.
pub fn prototypes(p: &Protocol, n: &Names) -> String {
    let Some(fi) = carried_format(p) else {
        return String::new();
    };
    let x = Fx::new(p, fi);
    let mut out = String::new();
    for s in p.structs.iter().filter(|s| !s.carries.is_empty()) {
        for c in &s.carries {
            let (lo, xlo, params) = (&n.lo, &x.lo, params(p, n));
            let (snake, field, ty) = (
                names::snake(&s.name),
                names::field(&s.fields[c.field].name),
                n.ty(&s.name),
            );
            let doc = format!(
                "`{}.{}` read as the packet it carries (`{}` names its command).",
                s.name, s.fields[c.field].name, s.fields[c.key].name
            );
            out.push_str(&fill!(
                r"
/** ${doc} */
int ${lo}read_carried_${snake}_${field}(const ${ty} *carrier, ${params}${xlo}packet *out);
",
                doc,
                lo,
                snake,
                field,
                ty,
                params,
                xlo
            ));
        }
    }
    out
}

/// The reader of every carried packet.
pub fn readers(p: &Protocol, n: &Names) -> String {
    let Some(fi) = carried_format(p) else {
        return String::new();
    };
    let x = Fx::new(p, fi);
    let mut out = String::new();
    for s in p.structs.iter().filter(|s| !s.carries.is_empty()) {
        for c in &s.carries {
            out.push_str(&reader(p, n, &x, s, c));
        }
    }
    if !out.is_empty() {
        out.insert_str(0, "/* ---- Carried packets ---- */\n");
        out.push('\n');
    }
    out
}

/// The reader of carried packet `c` of struct `s`, into a packet of format `x`.
fn reader(p: &Protocol, n: &Names, x: &Fx, s: &Struct, c: &Carried) -> String {
    let (lo, up, xlo) = (&n.lo, &n.up, &x.lo);
    let (struct_name, field_name) = (&s.name, &s.fields[c.field].name);
    let key_name = &s.fields[c.key].name;
    let (snake, field, key, ty) = (
        names::snake(&s.name),
        names::field(field_name),
        names::field(key_name),
        n.ty(&s.name),
    );
    let format = &p.frames[x.fi].name;
    let params = params(p, n);
    let (in_direction, direction) = if p.directions.is_empty() {
        (String::new(), String::new())
    } else {
        (
            " in `direction`".to_string(),
            "    out->direction = direction;\n".to_string(),
        )
    };
    // Every command, by its one id: generated Rust's `Command::from_id`.
    let mut cases = String::new();
    for cmd in &p.commands {
        let (label, name) = (names::u64_lit(cmd.id[0]), &cmd.name);
        cases.push_str(&fill!(
            "    case ${label}: out->command = ${up}${name}; break;\n",
            label,
            up,
            name
        ));
    }
    // The member of the command (and direction) with a payload, zeroed, then read.
    let mut reads = String::new();
    for slot in slots_of(p, x).iter().filter(|s| s.si.is_some()) {
        let (guard, name) = (slot.guard(p, n, "out"), &slot.name);
        let read = names::snake(&p.structs[slot.si.unwrap_or_default()].name);
        reads.push_str(&fill!(
            "    ${guard}e = (memset(&out->payload.${name}, 0, sizeof out->payload.${name}), ${lo}read_${read}(&r, &out->payload.${name}));\n",
            guard,
            name,
            lo,
            read
        ));
    }
    fill!(
        include_str!("templates/carried.c"),
        struct_name,
        field_name,
        key_name,
        in_direction,
        format,
        up,
        lo,
        snake,
        field,
        ty,
        params,
        xlo,
        key,
        cases,
        direction,
        reads
    )
}
