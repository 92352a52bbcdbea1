//! NUL-terminated text ([`FieldKind::NulText`](protocol_spec::ir::FieldKind::NulText)): a
//! string of at most `max` bytes, as `text::read_nul_text` and `text::nul_text_fits` read and
//! write it.

use protocol_runtime::{Reader, Writer};
use protocol_spec::ir::{Field, Protocol};

use super::{Kind, ReadAt, WriteAt, value_of};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::check::{read_nul_text, write_nul_text};
use crate::payload::join;
use crate::payload::read::ReadFail;

/// Text of at most `max` bytes and its NUL.
pub(super) struct NulText {
    pub(super) max: usize,
}

impl Kind<'_> for NulText {
    fn read(
        &self,
        _p: &Protocol,
        _f: &Field,
        fnames: &FieldNames,
        _at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let v = read_nul_text(r, self.max)?;
        out.push(&fnames.name, v);
        Ok(())
    }

    fn write(
        &self,
        _p: &Protocol,
        f: &Field,
        at: &WriteAt<'_>,
        w: &mut Writer<'_>,
    ) -> Result<(), EncodeIssue> {
        let fpath = join(at.path, &f.name);
        let v = value_of(f, at, &fpath)?;
        write_nul_text(v, self.max, w, &fpath)
    }
}
