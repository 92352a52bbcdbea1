//! A check inside the payload ([`FieldKind::Check`](crate::ir::FieldKind::Check)): verified
//! on read and computed on write over the bytes of the fields it covers, whose positions the
//! struct's walk marks; no member of the C struct, no text.

use crate::ir::{ByteOrder, Field, PayloadCheck, Struct};

use super::Kind;
use crate::c::fields::Dir;
use crate::c::names::Names;
use crate::c::prelude::{put_call, take_call};
use crate::c::template::fill;
use crate::c::values::try_call;

/// The check.
pub(super) struct Check<'a>(pub(super) &'a PayloadCheck);

impl Kind for Check<'_> {
    fn members(&self, _n: &Names, _f: &Field, _out: &mut String) {}

    // Printed as a field of its struct (`walk`), which knows the covered fields.
    fn code(&self, _n: &Names, _s: &Struct, _f: &Field, _dir: Dir, _here: &str) -> String {
        unreachable!("a check is printed by walk")
    }

    fn walk(&self, n: &Names, s: &Struct, i: usize, dir: Dir, _here: &str) -> String {
        payload_check(n, s, &s.fields[i], self.0, dir)
    }

    fn text(&self, _n: &Names, _f: &Field) -> String {
        String::new()
    }
}

/// A check inside the payload over the bytes `from<first>..to<last>` (the runtime's
/// `field::verify_check`: the stored value, then the check; `field::put_check`).
fn payload_check(n: &Names, s: &Struct, f: &Field, c: &PayloadCheck, dir: Dir) -> String {
    let up = &n.up;
    let name = crate::c::checks::payload_check_name(n, s, f);
    let (width, big) = (c.algorithm.width(), u8::from(c.endian == ByteOrder::Big));
    let (from, to) = (format!("from{}", c.first), format!("to{}", c.last));
    match dir {
        Dir::Read => {
            try_call(&take_call(n, width, big, "raw"))
                + &fill!(
                    r"
    if (!${name}(r->p + ${from}, ${to} - ${from}, &word) || word != raw) return ${up}ERR_PAYLOAD_CHECK;
",
                    name,
                    from,
                    to,
                    up
                )
        }
        Dir::Write => {
            fill!(
                "    (void)${name}(w->p + ${from}, ${to} - ${from}, &word);\n",
                name,
                from,
                to
            ) + &try_call(&put_call(n, width, big, "word"))
        }
    }
}
