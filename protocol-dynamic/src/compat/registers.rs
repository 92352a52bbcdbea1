//! How a change of the register map (`[registers]`) is classified: a register removed, moved
//! to another address, resized or retyped changes what a host reads at an address (breaking);
//! a register added, or a changed unit, access or doc, does not (compatible). Registers are
//! matched by name.

use protocol_spec::ir::{Protocol, Register, ValueType};

use super::{Change, Report};

/// The changes of the register map from `old` to `new`.
pub(super) fn diff_registers(old: &Protocol, new: &Protocol, out: &mut Vec<Change>) {
    let mut r = Report {
        out,
        subject: "registers".into(),
    };
    let (o, n) = match (&old.registers, &new.registers) {
        (None, None) => return,
        (None, Some(_)) => return r.compatible("register map added"),
        (Some(_), None) => {
            return r.breaking("register map removed (reads and writes are no longer typed)");
        }
        (Some(o), Some(n)) => (o, n),
    };
    for or in &o.registers {
        r.subject = format!("register {}", or.name);
        let Some(nr) = n.registers.iter().find(|x| x.name == or.name) else {
            r.breaking(format!("removed ({} bytes at {})", or.size, or.address));
            continue;
        };
        diff_register(or, nr, &mut r);
    }
    for nr in n
        .registers
        .iter()
        .filter(|x| !o.registers.iter().any(|y| y.name == x.name))
    {
        r.subject = format!("register {}", nr.name);
        r.compatible(format!("added ({} bytes at {})", nr.size, nr.address));
    }
}

/// Rule: where a register lies and how its bytes read are the wire; its unit, access and doc
/// are not.
fn diff_register(o: &Register, n: &Register, r: &mut Report<'_>) {
    if o.address != n.address {
        r.breaking(format!("moved from address {} to {}", o.address, n.address));
    }
    if o.size != n.size {
        r.breaking(format!("resized from {} to {} bytes", o.size, n.size));
    }
    if o.ty != n.ty {
        r.breaking(format!(
            "retyped from {} to {}",
            type_text(&o.ty),
            type_text(&n.ty)
        ));
    }
    if o.unit != n.unit {
        r.compatible(format!("unit `{}` → `{}`", o.unit, n.unit));
    }
    if o.access != n.access {
        r.compatible(format!(
            "access `{}` → `{}`",
            o.access.as_str(),
            n.access.as_str()
        ));
    }
    if o.doc != n.doc {
        r.compatible("doc changed");
    }
}

/// A register's type in words: its primitive, byte order and scale.
fn type_text(t: &ValueType) -> String {
    match t {
        ValueType::Scalar { scalar, scale } => {
            let mut s = format!("`{}` ({:?})", scalar.prim.rust_name(), scalar.endian);
            if let Some(sc) = scale {
                s.push_str(&format!(" scaled {sc:?}"));
            }
            s
        }
        other => format!("{other:?}"),
    }
}
