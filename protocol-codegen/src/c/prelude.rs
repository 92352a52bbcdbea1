//! The start of the source file: its includes and attributes, and the byte-order helpers every
//! spec's readers and writers call (`templates/bytes.c`: whole-integer readers and writers of
//! each size and byte order, positions and header fields; `templates/packed.c`, for the specs
//! with bit-packed arrays; `templates/stream.c`, for those with bit streams). [`take_call`] and [`put_call`] name the helper of one integer.

use crate::ir::{FieldKind, Protocol};

use super::names::Names;
use super::shape::any_field;
use super::template::fill;

/// The start of the source file, up to the spec's names.
pub fn source_prelude(p: &Protocol, n: &Names) -> String {
    let (lo, up, name) = (&n.lo, &n.up, &p.name);
    let mut out = fill!(include_str!("templates/source_open.c"), name, up);
    out.push('\n');
    out.push_str(&fill!(include_str!("templates/bytes.c"), lo, up));
    out.push('\n');
    if any_field(p, |k| matches!(k, FieldKind::Packed { .. })) {
        out.push_str(&fill!(include_str!("templates/packed.c"), lo, up));
        out.push('\n');
    }
    if any_field(p, |k| matches!(k, FieldKind::BitStream { .. })) {
        out.push_str(&fill!(include_str!("templates/stream.c"), lo, up));
        out.push('\n');
    }
    out
}

/// The suffix of a sized reader or writer: `u8`, `u16le`, `u32be`.
fn sized_name(size: usize, big: bool) -> String {
    let order = match (size, big) {
        (1, _) => "",
        (_, true) => "be",
        (_, false) => "le",
    };
    format!("u{}{order}", 8 * size)
}

/// The C call that reads an unsigned integer of `size` bytes (`big`: big-endian) from the
/// payload reader `r` into `raw`: a sized reader where there is one, else `take_uint`.
pub fn take_call(n: &Names, size: usize, big: u8, raw: &str) -> String {
    let lo = &n.lo;
    if matches!(size, 1 | 2 | 4 | 8) {
        format!("{lo}take_{}(r, &{raw})", sized_name(size, big != 0))
    } else {
        format!("{lo}take_uint(r, {size}u, {big}, &{raw})")
    }
}

/// The C call that writes `value` as an unsigned integer of `size` bytes to the frame writer
/// `w`, as [`take_call`] reads it.
pub fn put_call(n: &Names, size: usize, big: u8, value: &str) -> String {
    let lo = &n.lo;
    if matches!(size, 1 | 2 | 4 | 8) {
        format!("{lo}put_{}(w, {value})", sized_name(size, big != 0))
    } else {
        format!("{lo}put_uint(w, {size}u, {big}, {value})")
    }
}
