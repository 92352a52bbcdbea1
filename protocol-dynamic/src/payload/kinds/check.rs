//! A check inside a payload ([`FieldKind::Check`](protocol_spec::ir::FieldKind::Check)):
//! verified on read and computed on write over the bytes of the fields it covers, as
//! `field::verify_check` and `field::put_check` do; no key in the object.

use protocol_runtime::{Reader, Writer};
use protocol_spec::ir::{Field, PayloadCheck, Protocol, Struct};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::read::ReadFail;

/// The check.
pub(super) struct Check<'a>(pub(super) &'a PayloadCheck);

impl<'a> Kind<'a> for Check<'a> {
    // Read as a field of its struct (`read_in`), which knows the covered fields; validation
    // keeps checks out of repeated elements.
    fn read(
        &self,
        _p: &Protocol,
        _f: &Field,
        _fnames: &FieldNames,
        _at: &ReadAt<'_>,
        _r: &mut Reader<'_>,
        _out: &mut Fields,
    ) -> Result<(), ReadFail> {
        Ok(())
    }

    // Written as a field of its struct (`write_in`), which knows the covered fields.
    fn write(
        &self,
        _p: &Protocol,
        _f: &Field,
        _at: &WriteAt<'_>,
        _w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        Ok(())
    }

    fn keys(&self, _f: &'a Field) -> Vec<&'a str> {
        Vec::new()
    }

    fn read_in<'b>(
        &self,
        _p: &Protocol,
        _s: &Struct,
        _i: usize,
        _fnames: &FieldNames,
        spans: &[(Reader<'b>, usize)],
        r: &mut Reader<'b>,
        _at: &ReadAt<'_>,
        _out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let c = self.0;
        let (from, end) = (&spans[c.first].0, spans[c.last].1);
        crate::payload::check::verify(c, r, from, end)?;
        Ok(())
    }

    fn write_in(
        &self,
        _p: &Protocol,
        _s: &Struct,
        _i: usize,
        spans: &[(usize, usize)],
        _at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let c = self.0;
        crate::payload::check::put(c, w, spans[c.first].0, spans[c.last].1)
            .map_err(EncodeIssue::runtime)
    }
}
