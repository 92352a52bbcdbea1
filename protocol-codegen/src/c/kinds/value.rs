//! A value ([`FieldKind::Value`](crate::ir::FieldKind::Value)), or a fixed array of them: a
//! scalar (scaled or not), an enum, a nested struct or fixed text, one value's statements
//! being `values`'.

use crate::ir::{Field, Protocol, Struct, ValueType};

use super::{Kind, member_head};
use crate::c::fields::{Dir, indent};
use crate::c::format::{self, Label, each};
use crate::c::names::{self, Names, value_type};
use crate::c::template::fill;
use crate::c::values::{read_elem, write_elem};

/// A value of type `ty`, or `count` of them.
pub(super) struct Value<'a> {
    pub(super) p: &'a Protocol,
    pub(super) ty: &'a ValueType,
    pub(super) count: Option<usize>,
}

impl Kind for Value<'_> {
    fn members(&self, n: &Names, f: &Field, out: &mut String) {
        let (name, doc) = member_head(f);
        let count = self.count.map(|c| format!("[{c}]")).unwrap_or_default();
        let text = match self.ty {
            ValueType::Text(len) => format!("[{len}]"),
            _ => String::new(),
        };
        let ty = value_type(self.p, n, self.ty);
        out.push_str(&fill!(
            "    ${ty} ${name}${count}${text};${doc}\n",
            ty,
            name,
            count,
            text,
            doc
        ));
    }

    fn code(&self, n: &Names, _s: &Struct, _f: &Field, dir: Dir, here: &str) -> String {
        value(self.p, n, self.ty, self.count, dir, here)
    }

    fn text(&self, n: &Names, f: &Field) -> String {
        let (key, name) = (&f.name, names::field(&f.name));
        match self.count {
            None => format::value(self.p, n, self.ty, &Label::of(key), &format!("v->{name}")),
            Some(c) => each(
                &format!("{c}u"),
                format::value(
                    self.p,
                    n,
                    self.ty,
                    &Label::item(key),
                    &format!("v->{name}[i]"),
                ),
            ),
        }
    }
}

/// A value, or a fixed count of them.
fn value(
    p: &Protocol,
    n: &Names,
    ty: &ValueType,
    count: Option<usize>,
    dir: Dir,
    here: &str,
) -> String {
    let Some(count) = count else {
        return match dir {
            Dir::Read => read_elem(p, n, ty, here),
            Dir::Write => write_elem(p, n, ty, here),
        };
    };
    let each = format!("{here}[i]");
    let elem = match dir {
        Dir::Read => read_elem(p, n, ty, &each),
        Dir::Write => write_elem(p, n, ty, &each),
    };
    let elem = indent(&elem, 1);
    fill!(
        r"
    for (i = 0; i < ${count}u; i++) {
${elem}    }
",
        count,
        elem
    )
}
