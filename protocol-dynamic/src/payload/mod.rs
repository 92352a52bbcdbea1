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
//! does not appear; a carrying field (`carries`) read with a frame is the packet it carries
//! ([`carried`]). Each field kind is read and written by its module in `kinds`; a struct's
//! walk is in [`read`] and [`write`].

mod carried;
mod check;
mod kinds;
mod read;
mod write;

pub(crate) use carried::{carried_packets, carry_of};
pub(crate) use read::read_register;
pub use read::{ReadFail, read_payload};
pub(crate) use write::value_bytes;
pub use write::write_payload;

use protocol_spec::ir::{Enum, Prim};

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
    crate::value::sign_extended(prim, raw)
}

/// The variant of an enum with raw value `raw` (bits truncated to the enum's type).
fn variant(e: &Enum, raw: u64) -> Option<&protocol_spec::ir::EnumVariant> {
    e.variants.iter().find(|v| truncate(e.prim, v.value) == raw)
}

pub(crate) use kinds::keys;
