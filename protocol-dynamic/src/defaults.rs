//! The payload a device answers with when it is told no values: the value of a struct's
//! all-zero bytes, read as any payload is ([`read_payload`]), so that every number, enum and
//! text it holds is one the struct can carry (a scaled field reads as its offset, a group as
//! empty).

use crate::Codec;
use crate::model::Value;
use crate::payload::read_payload;

impl Codec<'_> {
    /// The value of payload struct `si` (an index into the protocol's structs) whose bytes, at
    /// its smallest size, are all zero; `None` for an index out of range or when zero bytes
    /// are no payload of it (an enum without a variant 0, a payload check).
    ///
    /// ```
    /// use protocol_dynamic::{Interpreter, Value};
    ///
    /// let interpreter =
    ///     Interpreter::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml"))?;
    /// let codec = interpreter.codec();
    /// let p = codec.protocol();
    /// let coord = p.structs.iter().position(|s| s.name == "ChassisCoord").unwrap();
    /// let Some(Value::Struct(fields)) = codec.zero_payload(coord) else { panic!() };
    /// assert_eq!(fields.get("x"), Some(&Value::F32(0.0)));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    #[must_use]
    pub fn zero_payload(&self, si: usize) -> Option<Value> {
        let size = self.protocol.structs.get(si)?.min_size;
        read_payload(self.protocol, self.names, si, &vec![0; size], None)
            .ok()
            .map(Value::Struct)
    }
}
