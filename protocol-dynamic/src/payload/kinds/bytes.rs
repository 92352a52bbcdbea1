//! Bytes ([`FieldKind::Bytes`](protocol_spec::ir::FieldKind::Bytes)): every byte left (but
//! the checks after them) or as many as an earlier field states, at most `max`; raw bytes, or
//! text without a terminator (a string when it is UTF-8, else its bytes).

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{Field, Protocol, Struct};

use super::{Kind, ReadAt, WriteAt, value_of};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value};
use crate::names::FieldNames;
use crate::payload::check::{text_bytes, text_value};
use crate::payload::join;
use crate::payload::read::{ReadFail, read_rest_bytes};
use crate::payload::write::{check_len, value_bytes};

/// Bytes of at most `max`, sized by the field `size_from` or by the end of the payload.
pub(super) struct Bytes<'a> {
    pub(super) max: usize,
    pub(super) size_from: &'a Option<String>,
    pub(super) text: bool,
}

impl Bytes<'_> {
    /// The value of the bytes read.
    fn value(&self, bytes: Vec<u8>) -> Value {
        if self.text {
            text_value(&bytes)
        } else {
            Value::Bytes(bytes)
        }
    }
}

impl Kind<'_> for Bytes<'_> {
    fn read(
        &self,
        _p: &Protocol,
        _f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let v = match self.size_from {
            // `Bytes::<max>::read_rest`.
            None => read_rest_bytes(r, self.max, 0)?,
            Some(n) => {
                let count = at
                    .owner
                    .unwrap_or(out)
                    .get(n)
                    .and_then(Value::as_u64)
                    .unwrap_or(0);
                field::take_sized(r, count, self.max)?.to_vec()
            }
        };
        out.push(&fnames.name, self.value(v));
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
        let bytes = if self.text {
            text_bytes(v, &fpath)?
        } else {
            value_bytes(v).ok_or_else(|| {
                EncodeIssue::new(
                    &fpath,
                    "expected bytes: a hex string or an array of numbers 0..=255",
                )
            })?
        };
        check_len(
            bytes.len(),
            "bytes",
            self.max,
            self.size_from.as_deref(),
            at.owner,
            &fpath,
        )?;
        w.put_bytes(&bytes).map_err(EncodeIssue::runtime)
    }

    // Every byte left but the checks after it (`Bytes::read_rest_but`).
    fn read_in<'b>(
        &self,
        p: &Protocol,
        s: &Struct,
        i: usize,
        fnames: &FieldNames,
        _spans: &[(Reader<'b>, usize)],
        r: &mut Reader<'b>,
        at: &ReadAt<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let f = &s.fields[i];
        if self.size_from.is_some() || s.bytes_after(i) == 0 {
            return self.read(p, f, fnames, at, r, out);
        }
        let v = read_rest_bytes(r, self.max, s.bytes_after(i))?;
        out.push(&fnames.name, self.value(v));
        Ok(())
    }
}
