//! An array of values ([`FieldKind::Array`](protocol_spec::ir::FieldKind::Array)): numbers or
//! enums to the payload's end, or as many as an earlier field states, at most `max`.

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{Field, Protocol, ValueType};

use super::{Kind, ReadAt, WriteAt, value_of};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value};
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{Path, ReadFail, read_elem};
use crate::payload::write::{check_len, write_elem};

/// Up to `max` elements of `ty`, counted by the field `size_from` or by the payload's end.
pub(super) struct Array<'a> {
    pub(super) ty: &'a ValueType,
    pub(super) max: usize,
    pub(super) size_from: &'a Option<String>,
    /// `size_from` is a mask of this struct: one element per set bit.
    pub(super) by_mask: bool,
}

impl Kind<'_> for Array<'_> {
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let fpath = Path::Field(at.path, &f.name);
        let ctx = (at.names, at.carry);
        let mut items = Vec::new();
        match self.size_from {
            None => {
                while field::more(r) {
                    let v = read_elem(p, ctx, self.ty, r, &Path::Index(&fpath, items.len()))?;
                    if items.len() == self.max {
                        return Err(ReadFail::Runtime(field::group_full(r, at.size)));
                    }
                    items.push(v);
                }
            }
            Some(n) if self.by_mask => {
                let mask = out.get(n).and_then(Value::as_u64).unwrap_or(0);
                for i in 0..field::array_len(field::mask_count(mask), self.max)? {
                    items.push(read_elem(p, ctx, self.ty, r, &Path::Index(&fpath, i))?);
                }
            }
            Some(n) => {
                let stated = at
                    .owner
                    .unwrap_or(out)
                    .get(n)
                    .and_then(Value::as_u64)
                    .unwrap_or(0);
                for i in 0..field::array_len(stated, self.max)? {
                    items.push(read_elem(p, ctx, self.ty, r, &Path::Index(&fpath, i))?);
                }
            }
        }
        out.push(&fnames.name, Value::Array(items));
        Ok(())
    }

    fn write(
        &self,
        p: &Protocol,
        f: &Field,
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let fpath = join(at.path, &f.name);
        let v = value_of(f, at, &fpath)?;
        let items = v
            .as_array()
            .ok_or_else(|| EncodeIssue::new(&fpath, "expected an array of elements"))?;
        match self.size_from {
            Some(n) if self.by_mask => check_mask_len(items.len(), self.max, n, at.obj, &fpath)?,
            _ => check_len(
                items.len(),
                "elements",
                self.max,
                self.size_from.as_deref(),
                at.owner,
                &fpath,
            )?,
        }
        for (i, item) in items.iter().enumerate() {
            write_elem(p, self.ty, item, w, &format!("{fpath}[{i}]"), at.carry)?;
        }
        Ok(())
    }
}

/// Refuses `len` elements above `max`, or other than the set bits of the mask `mask` (a field
/// of `obj`), as generated code does.
fn check_mask_len(
    len: usize,
    max: usize,
    mask: &str,
    obj: &Fields,
    path: &str,
) -> Result<(), EncodeIssue> {
    check_len(len, "elements", max, None, obj, path)?;
    let bits = obj.get(mask).and_then(Value::as_u64);
    match bits.map(field::mask_count) {
        Some(n) if field::check_stated_len(len, n).is_ok() => Ok(()),
        Some(n) => Err(EncodeIssue::new(
            path,
            format!("{len} elements, but `{mask}` has {n} bits set"),
        )),
        None => Err(EncodeIssue::new(
            path,
            format!("{len} elements, but `{mask}` holds no number"),
        )),
    }
}
