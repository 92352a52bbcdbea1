//! A repeated group ([`FieldKind::Group`](protocol_spec::ir::FieldKind::Group)): objects of
//! the element struct to the payload's end, at most `max`, read and written inline as
//! generated code does, so that an element's sized bytes use the repeating struct's fields.

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{Field, Protocol};

use super::{Kind, ReadAt, WriteAt, of, value_of};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value};
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{Path, ReadFail};
use crate::payload::write::{check_keys, check_len};

/// Up to `max` elements of the struct `elem`.
pub(super) struct Group {
    pub(super) elem: usize,
    pub(super) max: usize,
}

impl Kind<'_> for Group {
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let sizes = at.owner.unwrap_or(out);
        let mut items = Vec::new();
        let fpath = Path::Field(at.path, &f.name);
        let enames = at.names.fields(self.elem);
        while field::more(r) {
            let mut item = Fields::new();
            let epath = Path::Index(&fpath, items.len());
            let eat = ReadAt {
                names: at.names,
                size: at.size,
                path: &epath,
                owner: Some(sizes),
                carry: at.carry,
            };
            for (ef, en) in p.structs[self.elem].fields.iter().zip(enames) {
                of(&ef.kind).read(p, ef, en, &eat, r, &mut item)?;
            }
            if items.len() == self.max {
                return Err(ReadFail::Runtime(field::group_full(r, at.size)));
            }
            items.push(Value::Struct(item));
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
        check_len(items.len(), "elements", self.max, None, at.owner, &fpath)?;
        let es = &p.structs[self.elem];
        for (i, item) in items.iter().enumerate() {
            let ipath = format!("{fpath}[{i}]");
            let iobj = item.as_struct().ok_or_else(|| {
                EncodeIssue::new(&ipath, format!("expected an object (struct `{}`)", es.name))
            })?;
            check_keys(es, iobj, &ipath)?;
            let eat = WriteAt {
                obj: iobj,
                path: &ipath,
                owner: at.owner,
                carry: at.carry,
            };
            for ef in &es.fields {
                of(&ef.kind).write(p, ef, &eat, w)?;
            }
        }
        Ok(())
    }
}
