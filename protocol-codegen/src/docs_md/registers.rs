//! The register map section of the Markdown reference (`[registers]`): the table of registers
//! in address order (address, size, name, type and scaling, unit, access, description) and the
//! commands whose requests select runs of it (one run for every device a request lists, or one
//! per device).

use std::fmt::Write as _;

use super::cell;
use crate::ir::{Access, Protocol, Register, Select, ValueType};

/// The `## Registers` section, for a spec with `[registers]`.
pub(super) fn registers(p: &Protocol, out: &mut String) {
    let Some(map) = &p.registers else {
        return;
    };
    let _ = writeln!(out, "## Registers\n");
    if !map.doc.is_empty() {
        let _ = writeln!(out, "{}\n", map.doc);
    }
    let _ = writeln!(
        out,
        "| Address | Size | Register | Type | Unit | Access | Description |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|");
    for r in &map.registers {
        let _ = writeln!(
            out,
            "| {} | {} | `{}` | {} | {} | {} | {} |",
            r.address,
            r.size,
            r.name,
            type_text(r),
            cell(&r.unit),
            access_text(r.access),
            cell(&r.doc)
        );
    }
    out.push('\n');
    if !map.selects.is_empty() {
        let _ = writeln!(out, "Commands that select registers:\n");
        for s in &map.selects {
            let _ = writeln!(out, "- {}", select_text(p, s));
        }
        out.push('\n');
    }
}

/// The wire type, with its scaling to the physical value.
fn type_text(r: &Register) -> String {
    match &r.ty {
        ValueType::Scalar {
            scalar,
            scale: Some(sc),
        } => {
            let offset = if sc.offset == 0.0 {
                String::new()
            } else {
                format!(" + {}", sc.offset)
            };
            format!(
                "`{}` × {}{offset} (`{}`)",
                scalar.prim.spec_name(),
                sc.factor,
                sc.physical.rust_name()
            )
        }
        ValueType::Scalar { scalar, .. } => format!("`{}`", scalar.prim.spec_name()),
        _ => String::new(),
    }
}

fn access_text(a: Access) -> &'static str {
    match a {
        Access::Read => "read",
        Access::Write => "write",
        Access::ReadWrite => "read, write",
    }
}

/// What a command's request selects, in words.
fn select_text(p: &Protocol, s: &Select) -> String {
    let name = p.commands.get(s.command).map_or("", |c| c.name.as_str());
    let mut parts = Vec::new();
    if let Some(d) = &s.data {
        parts.push(format!(
            "its `{d}` writes the registers from its `{}`",
            s.address
        ));
    }
    if let (Some((_, field)), Some(each)) = (&s.answer, &s.each) {
        let asked = s
            .length
            .as_ref()
            .map(|l| format!(" as many bytes as the element's `{l}` asks,"))
            .unwrap_or_default();
        parts.push(format!(
            "it reads from each device its `{}` lists the registers from the `{}` of that \
             device's element (the first whose `{}` is the device's id),{asked} and each \
             device's answer's `{field}` holds their values",
            each.group, s.address, each.id
        ));
    } else if let Some((_, field)) = &s.answer {
        let fanout = p
            .session
            .as_ref()
            .is_some_and(|ss| ss.fanouts.iter().any(|f| f.command == s.command));
        let asked = s
            .length
            .as_ref()
            .map(|l| format!(" as many bytes as its `{l}` asks,"))
            .unwrap_or_default();
        let (from, whose) = if fanout {
            (" of each device it lists", "each device's answer")
        } else {
            ("", "its answer")
        };
        parts.push(format!(
            "it reads the registers{from} from its `{}`,{asked} and {whose}'s `{field}` holds their values",
            s.address
        ));
    }
    format!("`{name}`: {}.", parts.join("; "))
}
