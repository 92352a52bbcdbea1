//! Payload structs between the wire and [`Value`](crate::Value)s: the dynamic counterpart of the `impl Payload`
//! that `emit_payload_impl` (`protocol-codegen/src/codegen/payload/`) generates, field for
//! field and in the same order, with the same errors; the field rules themselves (scaling,
//! rounding, clamping, bit members, enum policy, sized bytes, groups) are the runtime's
//! (`protocol_runtime::field`), which generated code calls too.
//!
//! A struct is a [`Value::Struct`](crate::Value::Struct) with its fields in spec order:
//! nested structs are structs, arrays and repeated groups are arrays, bytes are bytes, an
//! optional field that is absent is `Null`, enums are their spec name (the number when unknown
//! and kept), scaled fields their physical value, bitfield members their own fields; padding
//! does not appear. Reading lives in [`read`], writing in [`write`].

mod check;
mod read;
mod write;

pub use read::{ReadFail, read_payload};
pub(crate) use write::value_bytes;
pub use write::write_payload;

use protocol_spec::ir::{Enum, Field, FieldKind, Prim};

use crate::value::truncate;

fn join(path: &str, name: &str) -> String {
    if path.is_empty() {
        name.to_string()
    } else {
        format!("{path}.{name}")
    }
}

/// The value of raw bits of a signed type, `None` for unsigned types.
fn signed_value(prim: Prim, raw: u64) -> Option<i64> {
    match prim {
        Prim::I8 => Some(i64::from(raw as u8 as i8)),
        Prim::I16 => Some(i64::from(raw as u16 as i16)),
        Prim::I24 => Some(i64::from(((raw as u32) << 8) as i32 >> 8)),
        Prim::I32 => Some(i64::from(raw as u32 as i32)),
        Prim::I64 => Some(raw as i64),
        _ => None,
    }
}

/// The variant of an enum with raw value `raw` (bits truncated to the enum's type).
fn variant(e: &Enum, raw: u64) -> Option<&protocol_spec::ir::EnumVariant> {
    e.variants.iter().find(|v| truncate(e.prim, v.value) == raw)
}

/// The names a field takes in its struct's object: its name, or its bit members' names.
pub(crate) fn keys(f: &Field) -> Vec<&str> {
    fn of<'a>(name: &'a str, kind: &'a FieldKind) -> Vec<&'a str> {
        match kind {
            FieldKind::Padding | FieldKind::Check(_) => Vec::new(),
            FieldKind::Bits { members, .. } => members.iter().map(|m| m.name.as_str()).collect(),
            FieldKind::Optional(inner) => of(name, inner),
            FieldKind::Value { .. }
            | FieldKind::Bytes { .. }
            | FieldKind::Group { .. }
            | FieldKind::Packed { .. }
            | FieldKind::NulText { .. }
            | FieldKind::Array { .. } => {
                vec![name]
            }
        }
    }
    of(&f.name, &f.kind)
}
