//! A bit-packed array ([`FieldKind::Packed`](protocol_spec::ir::FieldKind::Packed)): `count`
//! elements of `bits` bits back to back (the runtime's `packed`), numbers or scaled values.

use protocol_runtime::{Reader, Writer, packed};
use protocol_spec::ir::{BitOrder, ByteOrder, Field, Prim, Protocol, Scalar, Scale};

use super::{Kind, ReadAt, WriteAt, value_of};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{ReadFail, read_packed};
use crate::payload::write::{issue, scaled_raw};
use crate::value::value_bits;

/// `count` elements of `bits` bits.
pub(super) struct Packed {
    pub(super) count: usize,
    pub(super) bits: u32,
    pub(super) order: BitOrder,
    pub(super) prim: Prim,
    pub(super) scale: Option<Scale>,
}

impl Kind<'_> for Packed {
    fn read(
        &self,
        _p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        _at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let v = read_packed(
            r,
            f.size,
            self.count,
            self.bits,
            self.order,
            self.scale.as_ref(),
        )?;
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
        let (count, bits) = (self.count, self.bits);
        let fpath = join(at.path, &f.name);
        let v = value_of(f, at, &fpath)?;
        let items = v
            .as_array()
            .filter(|items| items.len() == count)
            .ok_or_else(|| {
                EncodeIssue::new(&fpath, format!("expected an array of {count} elements"))
            })?;
        let mut bytes = vec![0u8; f.size];
        let raw_type = Scalar {
            prim: self.prim,
            endian: ByteOrder::Little,
        };
        for (i, item) in items.iter().enumerate() {
            let ipath = format!("{fpath}[{i}]");
            let raw = match &self.scale {
                None => value_bits(item, self.prim).map_err(|e| issue(&ipath, e))?,
                Some(sc) => scaled_raw(raw_type, sc, item, &ipath)?,
            };
            packed::set_packed(&mut bytes, i, bits, self.order, raw)
                .map_err(|_| EncodeIssue::new(&ipath, format!("{raw} does not fit {bits} bits")))?;
        }
        w.put_bytes(&bytes).map_err(EncodeIssue::runtime)
    }
}
