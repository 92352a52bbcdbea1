//! A field a mask bit announces ([`FieldKind::When`](crate::ir::FieldKind::When)): a
//! `_present` flag before the inner kind's members, read from the mask's bit, and on write
//! required to agree with it (the runtime's `field::check_mask_bit`); its text is the inner
//! kind's, or `null` for each of its keys.

use crate::ir::{Field, Struct};

use super::Kind;
use crate::c::fields::{Dir, indent, optional_flag};
use crate::c::format;
use crate::c::names::{self, Names};
use crate::c::template::fill;

/// The inner kind, present when bit `bit` of the field `mask` is set.
pub(super) struct When<'a> {
    pub(super) inner: Box<dyn Kind + 'a>,
    pub(super) mask: &'a str,
    pub(super) bit: u32,
}

impl Kind for When<'_> {
    fn members(&self, n: &Names, f: &Field, out: &mut String) {
        let (name, mask, bit) = (names::field(&f.name), self.mask, self.bit);
        out.push_str(&fill!(
            "    bool ${name}_present; /**< Whether the payload holds `${name}`: bit ${bit} of `${mask}`. */\n",
            name,
            bit,
            mask
        ));
        self.inner.members(n, f, out);
    }

    fn code(&self, n: &Names, s: &Struct, f: &Field, dir: Dir, here: &str) -> String {
        let inner = indent(&self.inner.code(n, s, f, dir, here), 1);
        let present = optional_flag(here, f);
        let this = if dir == Dir::Read { "out" } else { "v" };
        let (mask, bit, up) = (names::field(self.mask), self.bit, &n.up);
        let set = fill!(
            "(((uint64_t)${this}->${mask} >> ${bit}) & 1u) != 0",
            this,
            mask,
            bit
        );
        match dir {
            Dir::Read => fill!(
                r"
    ${present} = ${set};
    if (${present}) {
${inner}    }
",
                present,
                set,
                inner
            ),
            Dir::Write => fill!(
                r"
    if (${present} != (${set})) return ${up}ERR_OUT_OF_RANGE;
    if (${present}) {
${inner}    }
",
                present,
                set,
                up,
                inner
            ),
        }
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (lo, name) = (&n.lo, names::field(&f.name));
        let null = |key: &str| fill!("    ${lo}emit(t, \" %s.${key}=null\", path);\n", lo, key);
        let nulls: String = self.inner.keys(f).iter().map(|k| null(k)).collect();
        let present = format::indent(&self.inner.text(n, f));
        let nulls = format::indent(&nulls);
        fill!(
            r"
    if (v->${name}_present) {
${present}    } else {
${nulls}    }
",
            name,
            present,
            nulls
        )
    }

    fn keys(&self, f: &Field) -> Vec<String> {
        self.inner.keys(f)
    }
}
