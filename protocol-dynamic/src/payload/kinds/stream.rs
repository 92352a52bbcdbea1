//! A bit stream ([`FieldKind::BitStream`](protocol_spec::ir::FieldKind::BitStream)): bytes read
//! most significant bit first, whose members are keys of the struct's object, each got and set
//! by the runtime's `bitstream::get_stream` and `bitstream::set_stream`.

use protocol_runtime::{Reader, Writer, bitstream};
use protocol_spec::ir::{BitMember, Field, Protocol};

use super::{Kind, ReadAt, WriteAt};
use crate::error::EncodeIssue;
use crate::model::Fields;
use crate::names::FieldNames;
use crate::payload::join;
use crate::payload::read::{Path, ReadFail, read_member_bits};
use crate::payload::write::member_raw;

/// The stream's members.
pub(super) struct Stream<'a> {
    pub(super) members: &'a [BitMember],
}

impl<'a> Kind<'a> for Stream<'a> {
    fn read(
        &self,
        p: &Protocol,
        f: &Field,
        fnames: &FieldNames,
        at: &ReadAt<'_>,
        r: &mut Reader<'_>,
        out: &mut Fields,
    ) -> Result<(), ReadFail> {
        let bytes = r.take(f.size)?;
        for (m, key) in self.members.iter().zip(&fnames.keys) {
            let bits = bitstream::get_stream(bytes, m.shift as usize, m.width);
            let v = read_member_bits(p, m, bits, &Path::Field(at.path, &m.name))?;
            out.push(key, v);
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
        // Zeroed: the bits after the last member are written as 0.
        let mut bytes = vec![0u8; f.size];
        for m in self.members {
            let mpath = join(at.path, &m.name);
            let v = at
                .obj
                .get(&m.name)
                .ok_or_else(|| EncodeIssue::missing(&mpath))?;
            let raw = member_raw(p, m, v, &mpath)?;
            bitstream::set_stream(&mut bytes, m.shift as usize, m.width, raw).map_err(|_| {
                EncodeIssue::new(&mpath, format!("{raw} does not fit {} bits", m.width))
            })?;
        }
        w.put_bytes(&bytes).map_err(EncodeIssue::runtime)
    }

    fn keys(&self, _f: &'a Field) -> Vec<&'a str> {
        self.members.iter().map(|m| m.name.as_str()).collect()
    }
}
