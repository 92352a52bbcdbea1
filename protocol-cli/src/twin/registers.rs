//! The twin's register file, for a spec with `[registers]`: the bytes of the device's control
//! table, at zero unless the values file gives a register's raw value (`registers = {
//! goal_position = 2048 }`). A request whose command writes registers (its `registers.data`)
//! stores its data from its address; an answer to a request that reads registers (its
//! `registers.answer`) carries the bytes at the requested address and length (for a BULK_READ,
//! those its element asks of the answering device). Which fields select the run is the spec's
//! (`ir::Select`); this module keeps the bytes and nothing else.

use std::collections::BTreeMap;

use protocol_dynamic::{Decoded, Value};
use protocol_spec::ir::{ByteOrder, Protocol, Register, ValueType};

/// The key of the values file that holds register values (a table of raw values by name).
pub const KEY: &str = "registers";

/// The bytes of the control table, by address (an address never written reads as 0).
#[derive(Debug, Clone, Default)]
pub struct RegisterFile {
    bytes: BTreeMap<u64, u8>,
}

impl RegisterFile {
    /// The file of `p`'s map with the raw values of `given` (a table by register name); `None`
    /// when the spec has no `[registers]`.
    ///
    /// # Errors
    /// A name that is no register of the map, or a value that is not an integer its type
    /// holds.
    pub fn new(p: &Protocol, given: Option<&Value>) -> Result<Option<Self>, String> {
        let Some(map) = p.registers.as_ref() else {
            return Ok(None);
        };
        let mut file = RegisterFile::default();
        let Some(given) = given else {
            return Ok(Some(file));
        };
        let Value::Struct(fields) = given else {
            return Err(format!("`{KEY}` is not a table of register values by name"));
        };
        for (name, v) in fields.iter() {
            let r = map
                .registers
                .iter()
                .find(|r| r.name == *name)
                .ok_or_else(|| format!("`{KEY}.{name}`: no register of that name"))?;
            let bytes = raw_bytes(r, v).ok_or_else(|| {
                format!(
                    "`{KEY}.{name}`: not a raw integer that {} bytes hold",
                    r.size
                )
            })?;
            file.write(u64::from(r.address), &bytes);
        }
        Ok(Some(file))
    }

    /// `data` stored from `address`.
    pub fn write(&mut self, address: u64, data: &[u8]) {
        for (a, &b) in (address..).zip(data) {
            self.bytes.insert(a, b);
        }
    }

    /// `length` bytes from `address`.
    pub fn read(&self, address: u64, length: u64) -> Vec<u8> {
        (address..address.saturating_add(length))
            .map(|a| self.bytes.get(&a).copied().unwrap_or(0))
            .collect()
    }

    /// What request `d` does to the file: its data stored, when its command writes registers.
    /// Returns what to log.
    pub fn apply_request(&mut self, p: &Protocol, d: &Decoded) -> Option<String> {
        let s = p.registers.as_ref()?.select(d.command?)?;
        let address = uint(&d.payload, &s.address)?;
        let Value::Bytes(data) = d.payload.get(s.data.as_deref()?)? else {
            return None;
        };
        self.write(address, data);
        Some(format!("wrote {} bytes at {address}", data.len()))
    }

    /// The answer `payload` to request `d`, its registers' bytes written into it, when the
    /// request reads registers: the run the request asks of every device, or, for a request
    /// that asks each listed device a run of its own, the run of `device` (its first element
    /// that names it). Returns what to log.
    pub fn fill_answer(
        &self,
        p: &Protocol,
        d: &Decoded,
        device: Option<u8>,
        payload: &mut Value,
    ) -> Option<String> {
        let s = p.registers.as_ref()?.select(d.command?)?;
        let (_, field) = s.answer.as_ref()?;
        let run = match &s.each {
            None => &d.payload,
            Some(each) => {
                let Value::Array(elements) = d.payload.get(&each.group)? else {
                    return None;
                };
                let device = u64::from(device?);
                elements
                    .iter()
                    .find(|e| uint(e, &each.id) == Some(device))?
            }
        };
        let address = uint(run, &s.address)?;
        let length = match &s.length {
            Some(l) => uint(run, l)?,
            None => 0,
        };
        let Value::Struct(fields) = payload else {
            return None;
        };
        fields.insert(field.clone(), Value::Bytes(self.read(address, length)));
        Some(format!("read {length} bytes at {address}"))
    }
}

/// An integer field of a decoded payload.
fn uint(payload: &Value, name: &str) -> Option<u64> {
    match payload.get(name)? {
        Value::UInt(v) => Some(*v),
        Value::Int(v) => u64::try_from(*v).ok(),
        _ => None,
    }
}

/// The bytes of register `r` holding the raw integer `v` (two's complement for a negative
/// one), in the register's byte order.
fn raw_bytes(r: &Register, v: &Value) -> Option<Vec<u8>> {
    let ValueType::Scalar { scalar, .. } = &r.ty else {
        return None;
    };
    let raw = match *v {
        Value::UInt(u) => u,
        Value::Int(i) => u64::from_ne_bytes(i.to_ne_bytes()),
        _ => return None,
    };
    let size = r.size.min(8);
    let bits = u32::try_from(size * 8).ok()?;
    let fits = match *v {
        Value::Int(i) if i < 0 => bits >= 64 || i >= -(1i64 << (bits - 1)),
        _ => bits >= 64 || raw < (1u64 << bits),
    };
    if !fits || scalar.prim.is_float() {
        return None;
    }
    let le = raw.to_le_bytes();
    let mut bytes = le.get(..size)?.to_vec();
    if scalar.endian == ByteOrder::Big {
        bytes.reverse();
    }
    Some(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dynamixel() -> Protocol {
        let text = include_str!("../../../specs/dynamixel.toml");
        let source = protocol_spec::source::SpecSource::new("specs/dynamixel.toml", text);
        protocol_spec::compile(&source).expect("the spec compiles")
    }

    #[test]
    fn given_values_sit_at_their_addresses_in_their_byte_order() {
        let p = dynamixel();
        let mut given = protocol_dynamic::Fields::new();
        given.insert("present_position".to_string(), Value::UInt(0x0102_0304));
        given.insert("goal_current".to_string(), Value::Int(-2));
        let file = RegisterFile::new(&p, Some(&Value::Struct(given)))
            .expect("valid")
            .expect("a map");
        assert_eq!(file.read(132, 4), [4, 3, 2, 1]);
        assert_eq!(file.read(102, 2), [0xFE, 0xFF]);
        assert_eq!(file.read(0, 2), [0, 0]);
    }

    #[test]
    fn unknown_names_and_values_too_wide_are_refused() {
        let p = dynamixel();
        for (name, v) in [("no_such", Value::UInt(1)), ("led", Value::UInt(256))] {
            let mut given = protocol_dynamic::Fields::new();
            given.insert(name.to_string(), v);
            let e = RegisterFile::new(&p, Some(&Value::Struct(given))).unwrap_err();
            assert!(e.contains(name), "{e}");
        }
    }
}
