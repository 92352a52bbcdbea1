//! An optional field ([`FieldKind::Optional`](crate::ir::FieldKind::Optional)): a `_present`
//! flag before the inner kind's members, set on read when bytes remain, tested on write; its
//! text is the inner kind's, or `null` for each of its keys.

use crate::ir::{Field, Struct};

use super::Kind;
use crate::c::fields::{Dir, indent, optional_flag};
use crate::c::format;
use crate::c::names::{self, Names};
use crate::c::template::fill;

/// The inner kind, present or not.
pub(super) struct Optional<'a>(pub(super) Box<dyn Kind + 'a>);

impl Kind for Optional<'_> {
    fn members(&self, n: &Names, f: &Field, out: &mut String) {
        let name = names::field(&f.name);
        out.push_str(&fill!(
            "    bool ${name}_present; /**< Whether the payload holds `${name}`. */\n",
            name
        ));
        self.0.members(n, f, out);
    }

    fn code(&self, n: &Names, s: &Struct, f: &Field, dir: Dir, here: &str) -> String {
        let inner = indent(&self.0.code(n, s, f, dir, here), 1);
        let present = optional_flag(here, f);
        match dir {
            Dir::Read => fill!(
                r"
    ${present} = r->pos < r->len;
    if (${present}) {
${inner}    }
",
                present,
                inner
            ),
            Dir::Write => fill!(
                r"
    if (${present}) {
${inner}    }
",
                present,
                inner
            ),
        }
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (lo, name) = (&n.lo, names::field(&f.name));
        let null = |key: &str| fill!("    ${lo}emit(t, \" %s.${key}=null\", path);\n", lo, key);
        let nulls: String = self.0.keys(f).iter().map(|k| null(k)).collect();
        let (present, nulls) = (format::indent(&self.0.text(n, f)), format::indent(&nulls));
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
}
