//! Comparing payload structs field by field: types, sizes, byte orders, scales, enums,
//! variable-size fields; names, units and docs are compatible changes.

use protocol_spec::ir::{
    BitMember, Enum, Field, FieldKind, Protocol, Scale, Struct, UnknownPolicy, ValueType,
};

use super::words::{field_type, unknown};
use super::{Class, Report};

/// Compares two structs field by field. After the first breaking change the later fields'
/// offsets may have moved, so comparing them would only repeat it: the walk stops there.
pub(super) fn diff_struct(
    op: &Protocol,
    os: &Struct,
    np: &Protocol,
    ns: &Struct,
    path: &str,
    r: &mut Report<'_>,
) {
    for (of, nf) in os.fields.iter().zip(&ns.fields) {
        let at = format!("{path}: field `{}` (offset {})", nf.name, nf.offset);
        if !diff_field(op, of, np, nf, &at, r) {
            return;
        }
    }
    if os.fields.len() != ns.fields.len() || os.size != ns.size {
        let extra = if ns.fields.len() > os.fields.len() {
            "fields added"
        } else {
            "fields removed"
        };
        r.breaking(format!(
            "{path}: {extra}, {} → {} bytes (payload sizes are exact)",
            os.size, ns.size
        ));
    }
    if os.doc != ns.doc {
        r.compatible(format!("{path}: struct doc changed"));
    }
}

/// Compares one field; returns false after a breaking change.
fn diff_field(
    op: &Protocol,
    of: &Field,
    np: &Protocol,
    nf: &Field,
    at: &str,
    r: &mut Report<'_>,
) -> bool {
    let same_shape = match (&of.kind, &nf.kind) {
        (FieldKind::Padding, FieldKind::Padding) => of.size == nf.size,
        (
            FieldKind::Bits {
                word: a,
                members: ma,
            },
            FieldKind::Bits {
                word: b,
                members: mb,
            },
        ) => a == b && diff_members(op, ma, np, mb, at, r),
        (FieldKind::BitStream { members: ma }, FieldKind::BitStream { members: mb }) => {
            of.size == nf.size && diff_members(op, ma, np, mb, at, r)
        }
        // A packed array's wire form is all of its parameters but the Rust type.
        (
            FieldKind::Packed {
                count: ca,
                bits: ba,
                order: oa,
                scale: sa,
                ..
            },
            FieldKind::Packed {
                count: cb,
                bits: bb,
                order: ob,
                scale: sb,
                ..
            },
        ) => ca == cb && ba == bb && oa == ob && sa == sb,
        (FieldKind::Value { ty: ta, count: ca }, FieldKind::Value { ty: tb, count: cb }) => {
            ca == cb && diff_value(op, ta, np, tb, at, r)
        }
        (
            a @ (FieldKind::Bytes { .. }
            | FieldKind::Group { .. }
            | FieldKind::Optional(_)
            | FieldKind::When { .. }),
            b,
        ) => same_kind(op, a, np, b, at, r),
        // Their wire form is all their description says.
        (
            FieldKind::NulText { .. } | FieldKind::Array { .. } | FieldKind::Check(_),
            FieldKind::NulText { .. } | FieldKind::Array { .. } | FieldKind::Check(_),
        ) => field_type(op, of) == field_type(np, nf),
        _ => false,
    };
    if !same_shape {
        r.breaking(format!(
            "{at}: {} → {}",
            field_type(op, of),
            field_type(np, nf)
        ));
        return false;
    }
    if of.name != nf.name {
        r.source(format!("{at}: renamed from `{}`", of.name));
    }
    if of.unit != nf.unit {
        r.compatible(format!("{at}: unit `{}` → `{}`", of.unit, nf.unit));
    }
    if of.doc != nf.doc {
        r.compatible(format!("{at}: doc changed"));
    }
    true
}

/// Whether two variable-size field kinds are the same on the wire (nested differences are
/// reported).
fn same_kind(
    op: &Protocol,
    a: &FieldKind,
    np: &Protocol,
    b: &FieldKind,
    at: &str,
    r: &mut Report<'_>,
) -> bool {
    match (a, b) {
        (
            FieldKind::Bytes {
                max: ma,
                size_from: sa,
                text: ta,
            },
            FieldKind::Bytes {
                max: mb,
                size_from: sb,
                text: tb,
            },
        ) => ma == mb && sa == sb && ta == tb,
        (FieldKind::Group { elem: ea, max: ma }, FieldKind::Group { elem: eb, max: mb }) => {
            let before = r.out.len();
            diff_struct(op, &op.structs[*ea], np, &np.structs[*eb], at, r);
            ma == mb && !r.out[before..].iter().any(|c| c.class == Class::Breaking)
        }
        (FieldKind::Optional(x), FieldKind::Optional(y)) => match (&**x, &**y) {
            (FieldKind::Value { ty: ta, count: ca }, FieldKind::Value { ty: tb, count: cb }) => {
                ca == cb && diff_value(op, ta, np, tb, at, r)
            }
            (x, y) => same_kind(op, x, np, y, at, r),
        },
        // The same bit of the same mask announces the same value.
        (
            FieldKind::When {
                kind: x,
                mask: ma,
                bit: ba,
            },
            FieldKind::When {
                kind: y,
                mask: mb,
                bit: bb,
            },
        ) => {
            ma == mb
                && ba == bb
                && match (&**x, &**y) {
                    (
                        FieldKind::Value { ty: ta, count: ca },
                        FieldKind::Value { ty: tb, count: cb },
                    ) => ca == cb && diff_value(op, ta, np, tb, at, r),
                    (x, y) => x == y,
                }
        }
        _ => false,
    }
}

/// Whether two element types are the same on the wire (nested differences are reported).
fn diff_value(
    op: &Protocol,
    a: &ValueType,
    np: &Protocol,
    b: &ValueType,
    at: &str,
    r: &mut Report<'_>,
) -> bool {
    match (a, b) {
        (
            ValueType::Scalar {
                scalar: sa,
                scale: ka,
            },
            ValueType::Scalar {
                scalar: sb,
                scale: kb,
            },
        ) => sa == sb && diff_scale(ka.as_ref(), kb.as_ref(), at, r),
        (ValueType::Struct(x), ValueType::Struct(y)) => {
            let (sx, sy) = (&op.structs[*x], &np.structs[*y]);
            if sx.size != sy.size {
                return false;
            }
            let before = r.out.len();
            diff_struct(op, sx, np, sy, at, r);
            !r.out[before..].iter().any(|c| c.class == Class::Breaking)
        }
        (ValueType::Enum(x, sa), ValueType::Enum(y, sb)) => {
            sa == sb && diff_enum(&op.enums[*x], &np.enums[*y], at, r)
        }
        (ValueType::Text(x), ValueType::Text(y)) => x == y,
        _ => false,
    }
}

fn diff_scale(a: Option<&Scale>, b: Option<&Scale>, at: &str, r: &mut Report<'_>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => {
            if (x.factor, x.offset) != (y.factor, y.offset) {
                return false;
            }
            if x.physical != y.physical {
                r.source(format!(
                    "{at}: physical type {} → {}",
                    x.physical.rust_name(),
                    y.physical.rust_name()
                ));
            }
            true
        }
        _ => false,
    }
}

fn diff_members(
    op: &Protocol,
    a: &[BitMember],
    np: &Protocol,
    b: &[BitMember],
    at: &str,
    r: &mut Report<'_>,
) -> bool {
    if a.len() != b.len() {
        return false;
    }
    for (x, y) in a.iter().zip(b) {
        // Signedness and scaling change what the same bits mean.
        if (x.shift, x.width, x.is_signed(), x.scale) != (y.shift, y.width, y.is_signed(), y.scale)
        {
            return false;
        }
        match (x.enum_index, y.enum_index) {
            (Some(i), Some(j)) => {
                if !diff_enum(
                    &op.enums[i],
                    &np.enums[j],
                    &format!("{at}, bits `{}`", y.name),
                    r,
                ) {
                    return false;
                }
            }
            (None, None) => {}
            _ => return false,
        }
        if x.name != y.name {
            r.source(format!(
                "{at}: bits {}..{} renamed `{}` → `{}`",
                y.shift,
                y.shift + y.width,
                x.name,
                y.name
            ));
        }
    }
    true
}

/// Compares enum variants by value: a removed or renumbered variant breaks; an added one keeps
/// the wire only when old decoders keep unknown values, and breaks exhaustive matches. Returns whether the wire type is the
/// same.
fn diff_enum(a: &Enum, b: &Enum, at: &str, r: &mut Report<'_>) -> bool {
    if a.prim != b.prim {
        return false;
    }
    for v in &a.variants {
        match b.variants.iter().find(|w| w.value == v.value) {
            None => {
                r.breaking(format!(
                    "{at}: enum `{}` lost the value {} ({})",
                    b.name, v.value, v.name
                ));
            }
            Some(w) if w.name != v.name => {
                r.source(format!(
                    "{at}: enum `{}` value {} renamed {} → {}",
                    b.name, v.value, v.name, w.name
                ));
            }
            Some(_) => {}
        }
    }
    for w in &b.variants {
        if !a.variants.iter().any(|v| v.value == w.value) {
            match a.unknown {
                // The wire keeps, the source does not: see `ADDED_VARIANT`.
                UnknownPolicy::Keep => r.source(format!(
                    "{at}: enum `{}` gained {} = {} (old decoders keep it as an unknown value; {})",
                    b.name,
                    w.name,
                    w.value,
                    super::ADDED_VARIANT
                )),
                UnknownPolicy::Reject => r.breaking(format!(
                    "{at}: enum `{}` gained {} = {}, which old decoders reject (`unknown = \"reject\"`)",
                    b.name, w.name, w.value
                )),
            }
        }
    }
    if a.unknown != b.unknown {
        // `keep` adds the generated enum's `Unknown(raw)` variant.
        r.source(format!(
            "{at}: enum `{}`: {} → {}",
            b.name,
            unknown(a.unknown),
            unknown(b.unknown)
        ));
    }
    // Variant changes are reported above; the field keeps its wire shape.
    true
}
