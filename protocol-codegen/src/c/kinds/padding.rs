//! Padding ([`FieldKind::Padding`](crate::ir::FieldKind::Padding)): its bytes skipped on read,
//! written as zeros; no member of the C struct, no text.

use crate::ir::{Field, Struct};

use super::Kind;
use crate::c::fields::Dir;
use crate::c::names::Names;
use crate::c::template::fill;
use crate::c::values::try_call;

/// A run of padding bytes (the field's size).
pub(super) struct Padding;

impl Kind for Padding {
    fn members(&self, _n: &Names, _f: &Field, _out: &mut String) {}

    fn code(&self, n: &Names, _s: &Struct, f: &Field, dir: Dir, _here: &str) -> String {
        padding(n, f.size, dir)
    }

    fn text(&self, _n: &Names, _f: &Field) -> String {
        String::new()
    }
}

/// Padding: its bytes skipped, or written as zeros.
fn padding(n: &Names, size: usize, dir: Dir) -> String {
    let lo = &n.lo;
    match dir {
        Dir::Read => try_call(&fill!("${lo}skip(r, ${size}u)", lo, size)),
        Dir::Write => try_call(&fill!("${lo}zero(w, ${size}u)", lo, size)),
    }
}
