//! The frame-format tables of the dissector, printed from the plans the other backends
//! execute: the frame rules ([`lower_layout`]) and the packet rules ([`lower_rules`]), with
//! the header values, checks and commands of each format as filterable fields.

use super::fields::Fields;
use super::lua;
use crate::ir::{Frame, Length, Prim, Protocol, Role, Transport};
use crate::layout::{LayoutPlan, lower_layout, word_field};
use crate::rules::{Carries, lower_rules};
use protocol_runtime::layout::LengthRule;
use protocol_runtime::rules::DirectionTest;

/// `v` cut to the bits of `prim`, as a key value of that type reads.
fn truncate(prim: Prim, v: u64) -> u64 {
    match prim.size() {
        8.. => v,
        n => v & ((1u64 << (8 * n)) - 1),
    }
}

fn length(plan: &LayoutPlan<'_>) -> String {
    match plan.length {
        LengthRule::Fixed(n) => format!("{{ fixed = {n} }}"),
        LengthRule::Field { field, adjust } => {
            format!("{{ field = {}, adjust = {adjust} }}", lua::word(field))
        }
        LengthRule::FieldOrBare {
            field,
            adjust,
            bare,
        } => format!(
            "{{ field = {}, adjust = {adjust}, bare = {bare} }}",
            lua::word(field)
        ),
        LengthRule::Conditional {
            field,
            adjust,
            extension,
            trailer,
        } => {
            let mut out = format!("{{ field = {}, adjust = {adjust}", lua::word(field));
            if let Some(e) = extension {
                out.push_str(&format!(
                    ", extension = {{ marker = {}, wide = {}, len = {} }}",
                    e.marker,
                    lua::word(e.wide),
                    e.len
                ));
            }
            if let Some(t) = trailer {
                out.push_str(&format!(
                    ", trailer = {{ flag = {}, len = {} }}",
                    lua::word(t.flag),
                    t.len
                ));
            }
            out + " }"
        }
    }
}

/// The commands a format carries, by their key as the dissector joins it (`"3"`, `"1,2"`).
fn commands(p: &Protocol, f: &Frame, carries: Carries) -> String {
    let mut items = Vec::new();
    for (ci, c) in p.commands.iter().enumerate() {
        let key = match carries {
            Carries::CanCommand => match c.can_id {
                Some(id) => id.to_string(),
                None => continue,
            },
            Carries::Command if f.commands.contains(&ci) => {
                c.id.iter()
                    .zip(&f.dispatch)
                    .map(|(v, &vi)| truncate(f.values[vi].prim, *v).to_string())
                    .collect::<Vec<_>>()
                    .join(",")
            }
            _ => continue,
        };
        items.push(format!("[{}] = {}", lua::string(&key), ci + 1));
    }
    format!("{{ {} }}", items.join(", "))
}

/// The filterable fields of a format's header values, and their table.
fn values(p: &Protocol, f: &Frame, fields: &mut Fields) -> String {
    let mut items = Vec::new();
    for v in &f.values {
        let abbrev = format!("{}.{}.{}", p.name, f.name, v.name);
        let role = match v.role {
            Role::User { .. } => "",
            Role::Length | Role::WideLength => " (length)",
            Role::Dispatch => " (command id)",
            Role::Const(_) => " (constant)",
            Role::Ack(_) => " (acknowledgement flag)",
            Role::Flag => " (trailer flag)",
        };
        let pf = fields.prim(v.prim, &abbrev, &format!("{}{role}", v.name), None);
        items.push(format!(
            "{{ field = {}, bool = {}, pf = {pf} }}",
            lua::word(word_field(v)),
            v.prim == Prim::Bool
        ));
    }
    format!("{{\n      {}\n    }}", items.join(",\n      "))
}

/// The checks of a format with their fields; a check the dissector cannot compute is refused.
fn checks(p: &Protocol, f: &Frame, fields: &mut Fields, refused: &mut Vec<String>) -> String {
    let mut items = Vec::new();
    for c in &f.checks {
        let abbrev = format!("{}.{}.{}", p.name, f.name, c.name);
        let pf = fields.declare(
            "uint32",
            &abbrev,
            &format!("{} ({})", c.name, c.naming.display),
            ", base.HEX",
        );
        let algorithm = lua::algorithm(&c.algorithm).unwrap_or_else(|| {
            refused.push(format!(
                "{abbrev}: a CRC of more than 32 bits (Lua's bit32 computes 32)"
            ));
            String::from("{}")
        });
        let extra = c.extra.as_ref().map_or(String::new(), |e| {
            let bytes: Vec<String> = e
                .bytes
                .iter()
                .map(|(k, b)| format!("[{k}] = {b}"))
                .collect();
            format!(
                ", extra = {{ key = {}, bytes = {{ {} }} }}",
                lua::word(e.key),
                bytes.join(", ")
            )
        });
        items.push(format!(
            "{{ name = {}, algorithm = {algorithm}, from = {}, to = {}, at = {}, size = {}, \
             order = {}, header = {}{extra}, pf = {pf} }}",
            lua::string(&c.name),
            lua::pos(c.from),
            lua::pos(c.to),
            lua::pos(c.at),
            c.size,
            lua::order(c.endian),
            c.header
        ));
    }
    format!("{{\n      {}\n    }}", items.join(",\n      "))
}

/// The packet rules of a format: what it carries, its key, acknowledgements, directions,
/// stuffing and zero-fill.
fn packet_rules(p: &Protocol, f: &Frame) -> String {
    let r = lower_rules(p, f);
    let carries = match r.carries {
        Carries::Command => "\"command\"".to_string(),
        Carries::CanCommand => "\"can\"".to_string(),
        Carries::Struct(si) => format!("\"struct\", struct = {}", si + 1),
        Carries::Bytes => "\"bytes\"".to_string(),
    };
    let key: Vec<String> = r.key.iter().map(|k| lua::word(k.field)).collect();
    let ack = r.ack.map_or("nil".to_string(), |(_, a)| {
        format!(
            "{{ flag = {}, equals = {}, header_len = {}, bare = {} }}",
            lua::word(a.flag),
            a.equals,
            a.header_len,
            a.bare
        )
    });
    let directions: Vec<String> = r
        .direction_tests()
        .iter()
        .map(|t| match t {
            DirectionTest::InRange { field, first, last } => {
                format!(
                    "{{ field = {}, first = {first}, last = {last} }}",
                    lua::word(*field)
                )
            }
            DirectionTest::Equals { field, value } => {
                format!("{{ field = {}, equals = {value} }}", lua::word(*field))
            }
        })
        .collect();
    let stuffing = r.stuffing.map_or("nil".to_string(), |s| {
        format!(
            "{{ after = {}, insert = {} }}",
            lua::bytes(s.after),
            s.insert
        )
    });
    format!(
        "carries = {carries}, header_len = {}, trailer_len = {}, key = {{ {} }}, ack = {ack},\n    \
         directions = {{ {} }}, stuffing = {stuffing}, truncate_zeros = {}, extensions = {},\n    \
         commands = {}",
        r.header_len,
        r.trailer_len,
        key.join(", "),
        directions.join(", "),
        r.truncate_zeros,
        f.extensions,
        commands(p, f, r.carries)
    )
}

/// The table of frame format `f`.
pub fn format(p: &Protocol, f: &Frame, fields: &mut Fields, refused: &mut Vec<String>) -> String {
    let plan = lower_layout(f);
    let constants: Vec<String> = plan
        .constants
        .iter()
        .map(|(_, c)| format!("{{ field = {}, value = {} }}", lua::word(c.field), c.value))
        .collect();
    let indices = |v: &[usize]| -> String {
        let items: Vec<String> = v.iter().map(|i| (i + 1).to_string()).collect();
        format!("{{ {} }}", items.join(", "))
    };
    let markers: Vec<String> = plan
        .markers
        .iter()
        .map(|m| {
            format!(
                "{{ at = {}, bytes = {} }}",
                lua::pos(m.at),
                lua::bytes(m.bytes)
            )
        })
        .collect();
    let lookup: Vec<String> = plan
        .sync_set
        .iter()
        .map(|b| format!("[{b}] = true"))
        .collect();
    let extended = match f.transport {
        Transport::Can { extended } => extended,
        Transport::Serial => false,
    };
    let flag_trailer = f.flag_trailer.as_ref().map_or(String::new(), |t| {
        let abbrev = format!("{}.{}.{}", p.name, f.name, t.name);
        let pf = fields.declare("bytes", &abbrev, &t.name, "");
        format!(
            ",\n    flag_trailer = {{ flag = {}, len = {}, pf = {pf} }}",
            lua::word(word_field(&f.values[t.flag])),
            t.len
        )
    });
    // An escaped frame is cut at its flags and unescaped before the rules above read it.
    let escape = f.escape.as_ref().map_or(String::new(), |e| {
        let original: Vec<String> = e
            .pairs
            .iter()
            .map(|[reserved, sub]| format!("[0x{sub:02X}] = 0x{reserved:02X}"))
            .collect();
        format!(
            ",\n    escape = {{ flag = 0x{:02X}, escape = 0x{:02X}, original = {{ {} }} }}",
            e.flag,
            e.escape,
            original.join(", ")
        )
    });
    if let Length::Field { value, .. } = f.length {
        if f.values[value].word.prim.size() > 6 {
            refused.push(format!(
                "{}.{}: a length word of more than 6 bytes",
                p.name, f.name
            ));
        }
    }
    format!(
        "  {{ name = {}, extended = {extended}, sync = {}, sync_set = {}, sync_lookup = {{ {} }},\n    \
         decide_len = {}, min_len = {}, max_len = {}, length = {},\n    \
         constants = {{ {} }}, header_checks = {}, frame_checks = {}, markers = {{ {} }},\n    \
         values = {},\n    checks = {},\n    {}{flag_trailer}{escape} }},",
        lua::string(&f.name),
        lua::bytes(plan.sync),
        lua::bytes(plan.sync_set),
        lookup.join(", "),
        plan.header_len,
        plan.min_len,
        plan.max_len,
        length(&plan),
        constants.join(", "),
        indices(&plan.header_checks),
        indices(&plan.frame_checks),
        markers.join(", "),
        values(p, f, fields),
        checks(p, f, fields, refused),
        packet_rules(p, f)
    )
}
