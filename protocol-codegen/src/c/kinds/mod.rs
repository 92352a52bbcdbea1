//! One module per field kind of the IR ([`FieldKind`]), each owning everything the C printer
//! prints of that kind: its members in the payload's C struct (the header), its statements in
//! the struct's reader and writer (with the runtime's field rules), and its text form. [`of`]
//! is the one place that matches on the kind.

mod array;
mod bits;
mod bytes;
mod check;
mod group;
mod nul_text;
mod optional;
mod packed;
mod padding;
mod stream;
mod value;
mod when;

use crate::ir::{Field, FieldKind, Protocol, Struct};

use super::fields::Dir;
use super::names::{self, Names, doc_comment};
use super::template::fill;

/// What the C printer prints of one field kind.
pub(super) trait Kind {
    /// Its declarations in the payload's C struct.
    fn members(&self, n: &Names, f: &Field, out: &mut String);

    /// The statements that read or write it in a reader or writer of struct `s`, its C value
    /// `here` (`f` is the field, or the optional field that holds this kind).
    fn code(&self, n: &Names, s: &Struct, f: &Field, dir: Dir, here: &str) -> String;

    /// Its statements as field `i` of struct `s`, where a kind may need the fields around it.
    fn walk(&self, n: &Names, s: &Struct, i: usize, dir: Dir, here: &str) -> String {
        self.code(n, s, &s.fields[i], dir, here)
    }

    /// Its text form's statements (`<prefix>_format`).
    fn text(&self, n: &Names, f: &Field) -> String;

    /// The keys its text names: `null` each when an optional field is absent.
    fn keys(&self, f: &Field) -> Vec<String> {
        vec![f.name.clone()]
    }
}

/// The one match on the IR's field kind: the printer of `kind`.
pub(super) fn of<'a>(p: &'a Protocol, kind: &'a FieldKind) -> Box<dyn Kind + 'a> {
    match kind {
        FieldKind::Padding => Box::new(padding::Padding),
        FieldKind::Value { ty, count } => Box::new(value::Value {
            p,
            ty,
            count: *count,
        }),
        FieldKind::Bytes {
            max,
            size_from,
            text,
        } => Box::new(bytes::Bytes {
            max: *max,
            size_from,
            text: *text,
        }),
        FieldKind::Group { elem, max } => Box::new(group::Group {
            p,
            elem: *elem,
            max: *max,
        }),
        FieldKind::Packed {
            count,
            bits,
            order,
            prim,
            scale,
        } => Box::new(packed::Packed {
            count: *count,
            bits: *bits,
            order: *order,
            prim: *prim,
            scale: *scale,
        }),
        FieldKind::Optional(inner) => Box::new(optional::Optional(of(p, inner))),
        FieldKind::When { kind, mask, bit } => Box::new(when::When {
            inner: of(p, kind),
            mask,
            bit: *bit,
        }),
        FieldKind::Bits { word, members } => Box::new(bits::Bits {
            p,
            word: *word,
            members,
        }),
        FieldKind::BitStream { members } => Box::new(stream::Stream { p, members }),
        FieldKind::Array {
            ty,
            max,
            size_from,
            by_mask,
        } => Box::new(array::Array {
            p,
            ty,
            max: *max,
            size_from,
            by_mask: *by_mask,
        }),
        FieldKind::NulText { max } => Box::new(nul_text::NulText { max: *max }),
        FieldKind::Check(c) => Box::new(check::Check(c)),
    }
}

/// A field's C name and its doc comment, as its members are declared.
fn member_head(f: &Field) -> (String, String) {
    (names::field(&f.name), doc_comment(&f.doc, &f.unit))
}

/// The member that counts the elements or bytes of `name` used.
fn used(name: &str, what: &str, max: usize) -> String {
    fill!(
        "    size_t ${name}_len; /**< ${what} of `${name}` used (at most ${max}). */\n",
        name,
        what,
        max
    )
}
