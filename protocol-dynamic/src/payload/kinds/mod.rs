//! One module per field kind of the IR ([`FieldKind`]), each owning how the run-time codec
//! reads that kind into [`Value`](crate::Value)s and writes it back, and the keys it takes in
//! its struct's object. [`of`] is the one place that matches on the kind.

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

use protocol_runtime::{Reader, Writer};
use protocol_spec::ir::{Field, FieldKind, Protocol, Struct};

use super::read::{Path, ReadFail};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::{FieldNames, Names};

/// Where a field is read: the protocol's interned names, the wire size of the struct whose
/// read code runs (a repeated group reports it when full), the path of the struct, and the
/// fields sized bytes take their size from: the struct being read (`None`: the fields read so
/// far), or for a group's elements, which generated code reads inline, the struct that
/// repeats them; and the message a carried packet is read in (`carried`'s `carry`).
pub(super) struct ReadAt<'a> {
    pub(super) names: &'a Names,
    pub(super) size: usize,
    pub(super) path: &'a Path<'a>,
    pub(super) owner: Option<&'a Fields>,
    pub(super) carry: Option<usize>,
}

/// Where a field is written from: the object holding its value, the path of that object, and
/// the fields sized bytes take their size from (the struct, or for a group's elements the
/// struct that repeats them), and the message a carried packet is written in (`carried`'s
/// `carry`).
pub(super) struct WriteAt<'a> {
    pub(super) obj: &'a Fields,
    pub(super) path: &'a str,
    pub(super) owner: &'a Fields,
    pub(super) carry: Option<usize>,
}

/// What the run-time codec does with one field kind, as generated code does it.
pub(super) trait Kind<'a> {
    /// Reads the field `f` (or the optional field holding this kind) into `out`, under its
    /// names `fnames`.
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail>;

    /// Writes the field `f` from `at.obj`.
    fn write(
        &self,
        p: &Protocol,
        f: &Field,
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue>;

    /// The names the field takes in its struct's object.
    fn keys(&self, f: &'a Field) -> Vec<&'a str> {
        vec![f.name.as_str()]
    }

    /// Reads field `i` of struct `s` (names `fnames`, read at `at`), where a kind may need
    /// the fields around it (`spans`: a copy of the reader at each earlier field's start, and
    /// the position after it).
    #[allow(clippy::too_many_arguments)]
    fn read_in<'b>(
        &self,
        p: &Protocol,
        s: &Struct,
        i: usize,
        fnames: &FieldNames,
        spans: &[(Reader<'b>, usize)],
        r: &mut Reader<'b>,
        at: &ReadAt<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let _ = spans;
        self.read(p, &s.fields[i], fnames, at, r, out)
    }

    /// Writes field `i` of struct `s` from `at.obj`, where a kind may need the fields around
    /// it (`spans`: where each earlier field starts and ends).
    fn write_in(
        &self,
        p: &Protocol,
        s: &Struct,
        i: usize,
        spans: &[(usize, usize)],
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let _ = spans;
        self.write(p, &s.fields[i], at, w)
    }
}

/// The one match on the IR's field kind: the codec of `kind`.
pub(super) fn of(kind: &FieldKind) -> Box<dyn Kind<'_> + '_> {
    match kind {
        FieldKind::Padding => Box::new(padding::Padding),
        FieldKind::Value { ty, count } => Box::new(value::Value { ty, count: *count }),
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
        FieldKind::Optional(inner) => Box::new(optional::Optional(of(inner))),
        FieldKind::When { kind, mask, bit } => Box::new(when::When {
            inner: of(kind),
            mask,
            bit: *bit,
        }),
        FieldKind::BitStream { members } => Box::new(stream::Stream { members }),
        FieldKind::Bits { word, members } => Box::new(bits::Bits {
            word: *word,
            members,
        }),
        FieldKind::Array {
            ty,
            max,
            size_from,
            by_mask,
        } => Box::new(array::Array {
            ty,
            max: *max,
            size_from,
            by_mask: *by_mask,
        }),
        FieldKind::NulText { max } => Box::new(nul_text::NulText { max: *max }),
        FieldKind::Check(c) => Box::new(check::Check(c)),
    }
}

/// The names a field takes in its struct's object: its name, or its bit members' names.
pub(crate) fn keys(f: &Field) -> Vec<&str> {
    of(&f.kind).keys(f)
}

/// The value of field `f` in `at.obj`, or the error naming it missing.
fn value_of<'v>(f: &Field, at: &WriteAt<'v>, fpath: &str) -> Result<&'v crate::Value, EncodeIssue> {
    at.obj
        .get(&f.name)
        .ok_or_else(|| EncodeIssue::missing(fpath))
}
