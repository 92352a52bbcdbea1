//! Padding ([`FieldKind::Padding`](protocol_spec::ir::FieldKind::Padding)): skipped on read,
//! written as zeros; no key in the object.

use protocol_runtime::{Reader, Writer};
use protocol_spec::ir::{Field, Protocol};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::read::ReadFail;

/// A run of padding bytes (the field's size).
pub(super) struct Padding;

impl<'a> Kind<'a> for Padding {
    fn read(
        &self,
        _p: &Protocol,
        f: &Field,
        _fnames: &FieldNames,
        _at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        _out: &mut Fields,
    ) -> Result<(), ReadFail> {
        r.skip(f.size)?;
        Ok(())
    }

    fn write(
        &self,
        _p: &Protocol,
        f: &Field,
        _at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        w.zeros(f.size).map_err(EncodeIssue::runtime)
    }

    fn keys(&self, _f: &'a Field) -> Vec<&'a str> {
        Vec::new()
    }
}
