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
        let mut items = Vec::new();
        match self.size_from {
            None => {
                while field::more(r) {
                    let v = read_elem(p, at.names, self.ty, r, &Path::Index(&fpath, items.len()))?;
                    if items.len() == self.max {
                        return Err(ReadFail::Runtime(field::group_full(r, at.size)));
                    }
                    items.push(v);
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
                    items.push(read_elem(p, at.names, self.ty, r, &Path::Index(&fpath, i))?);
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
        check_len(
            items.len(),
            "elements",
            self.max,
            self.size_from.as_deref(),
            at.owner,
            &fpath,
        )?;
        for (i, item) in items.iter().enumerate() {
            write_elem(p, self.ty, item, w, &format!("{fpath}[{i}]"))?;
        }
        Ok(())
    }
}
