//! A value a mask bit announces ([`FieldKind::When`](protocol_spec::ir::FieldKind::When)):
//! read when bit `bit` of the earlier field `mask` is set, else `Null` for each of its keys;
//! written when one of its keys holds a value that is not `Null`, which must agree with the
//! bit (the runtime's `field::check_mask_bit`), as generated code refuses a mismatch.

use protocol_runtime::{Reader, Writer, field};
use protocol_spec::ir::{Field, Protocol};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::{Fields, Value};
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::ReadFail;

/// The inner kind, present when the mask's bit is set.
pub(super) struct When<'a> {
    pub(super) inner: Box<dyn Kind<'a> + 'a>,
    pub(super) mask: &'a str,
    pub(super) bit: u32,
}

impl<'a> Kind<'a> for When<'a> {
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        // The mask is a field of the struct being read, read before this one.
        let mask = out.get(self.mask).and_then(Value::as_u64).unwrap_or(0);
        if field::mask_bit(mask, self.bit) {
            return self.inner.read(p, f, fnames, at, r, out);
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
        let mask = at.obj.get(self.mask).and_then(Value::as_u64).unwrap_or(0);
        if field::check_mask_bit(present, mask, self.bit).is_err() {
            let (bit, name) = (self.bit, self.mask);
            let what = if present {
                format!("present, but bit {bit} of `{name}` is clear")
            } else {
                format!("absent, but bit {bit} of `{name}` is set")
            };
            return Err(EncodeIssue::new(join(at.path, &f.name), what));
        }
        if present {
            self.inner.write(p, f, at, w)
        } else {
            Ok(())
        }
    }

    fn keys(&self, f: &'a Field) -> Vec<&'a str> {
        self.inner.keys(f)
    }
}
