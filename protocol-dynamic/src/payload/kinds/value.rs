//! A value ([`FieldKind::Value`](protocol_spec::ir::FieldKind::Value)), or a fixed array of
//! them: a number (scaled or not), an enum's name, a nested struct's object, or fixed text.

use protocol_runtime::{Reader, Writer};
use protocol_spec::ir::{Field, Protocol, ValueType};

use super::{Kind, ReadAt, WriteAt, value_of};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value as V};
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{Path, ReadFail, read_elem};
use crate::payload::write::write_elem;

/// A value of type `ty`, or `count` of them.
pub(super) struct Value<'a> {
    pub(super) ty: &'a ValueType,
    pub(super) count: Option<usize>,
}

impl Kind<'_> for Value<'_> {
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
        let v = match self.count {
            None => read_elem(p, ctx, self.ty, r, &fpath)?,
            Some(n) => {
                let mut items = Vec::with_capacity(n);
                for i in 0..n {
                    items.push(read_elem(p, ctx, self.ty, r, &Path::Index(&fpath, i))?);
                }
                V::Array(items)
            }
        };
        out.push(&fnames.name, v);
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
        let Some(n) = self.count else {
            return write_elem(p, self.ty, v, w, &fpath, at.carry);
        };
        let items = v.as_array().ok_or_else(|| {
            EncodeIssue::new(&fpath, format!("expected an array of {n} elements"))
        })?;
        if items.len() != n {
            return Err(EncodeIssue::new(
                &fpath,
                format!("expected {n} elements, got {}", items.len()),
            ));
        }
        for (i, item) in items.iter().enumerate() {
            write_elem(p, self.ty, item, w, &format!("{fpath}[{i}]"), at.carry)?;
        }
        Ok(())
    }
}
