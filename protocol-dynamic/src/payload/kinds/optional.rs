//! An optional value ([`FieldKind::Optional`](protocol_spec::ir::FieldKind::Optional)): read
//! when bytes remain, else `Null` for each of its keys; written when one of its keys holds a
//! value that is not `Null`.

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{Field, Protocol};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value};
use crate::names::FieldNames;
use crate::payload::read::ReadFail;

/// The inner kind, present or not.
pub(super) struct Optional<'a>(pub(super) Box<dyn Kind<'a> + 'a>);

impl<'a> Kind<'a> for Optional<'a> {
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        if field::more(r) {
            return self.0.read(p, f, fnames, at, r, out);
        }
        for key in &fnames.keys {
            out.push(key, Value::Null);
        }
        Ok(())
    }

    fn write(
        &self,
        p: &Protocol,
        f: &Field,
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let present = crate::payload::keys(f)
            .iter()
            .any(|k| at.obj.get(k).is_some_and(|v| !v.is_null()));
        if present {
            self.0.write(p, f, at, w)
        } else {
            Ok(())
        }
    }

    fn keys(&self, f: &'a Field) -> Vec<&'a str> {
        self.0.keys(f)
    }
}
