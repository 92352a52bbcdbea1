//! Checks inside a payload and the values of text (NUL-terminated or not), as generated code
//! reads and writes them:
//! the runtime's `field::verify_check` and `field::put_check` over the covered fields'
//! bytes, and `text::read_nul_text` / `text::nul_text_fits`.

use protocol_runtime::checksum::{Bitwise, Checksum};
use protocol_runtime::{DecodeError, EncodeError, Reader, Writer, field, text};
use protocol_spec::ir::{Algorithm, PayloadCheck, Prim};

use crate::error::EncodeIssue;
use crate::model::Value;
use crate::value::value_bits;

/// Runs `f` with the [`Checksum`] of `a`: a CRC computed bit by bit from the parameters the
/// codec owns ([`Bitwise`]: the value is the same with any table, and building none costs
/// nothing per payload).
fn with_checksum<T>(a: &Algorithm, f: impl FnOnce(&Checksum<'_>) -> T) -> T {
    let width = a.width() as u8;
    match a {
        Algorithm::Crc8(s) => f(&Checksum::Object {
            width,
            check: &Bitwise::<u8>::new(&s.params),
        }),
        Algorithm::Crc16(s) => f(&Checksum::Object {
            width,
            check: &Bitwise::<u16>::new(&s.params),
        }),
        Algorithm::Crc32(s) => f(&Checksum::Object {
            width,
            check: &Bitwise::<u32>::new(&s.params),
        }),
        Algorithm::Crc64(s) => f(&Checksum::Object {
            width,
            check: &Bitwise::<u64>::new(&s.params),
        }),
        // Every other algorithm needs no table.
        other => f(&other.tableless().unwrap_or(Checksum::Sum8)),
    }
}

/// Reads and verifies check `c` at the reader's position; `start` is a copy of the reader
/// where its first covered field began, `end` the position after its last.
pub(super) fn verify(
    c: &PayloadCheck,
    r: &mut Reader<'_>,
    start: &Reader<'_>,
    end: usize,
) -> Result<(), DecodeError> {
    with_checksum(&c.algorithm, |k| {
        field::verify_check(r, start, end, k, c.endian)
    })
}

/// Writes check `c` over the bytes written from `start` to `end`.
pub(super) fn put(
    c: &PayloadCheck,
    w: &mut Writer<'_>,
    start: usize,
    end: usize,
) -> Result<(), EncodeError> {
    with_checksum(&c.algorithm, |k| {
        field::put_check(w, start, end, k, c.endian)
    })
}

/// A NUL-terminated text of at most `max` bytes, read: a string when it is UTF-8, else the
/// array of its bytes (without the NUL), so that encoding gives them back.
pub(super) fn read_nul_text(r: &mut Reader<'_>, max: usize) -> Result<Value, DecodeError> {
    Ok(text_value(text::read_nul_text(r, max)?))
}

/// A text's value: a string when its bytes are UTF-8, else the array of its bytes, so that
/// encoding gives them back (NUL-terminated text, and text without a terminator).
pub(super) fn text_value(bytes: &[u8]) -> Value {
    match core::str::from_utf8(bytes) {
        Ok(s) => Value::from(s.to_string()),
        Err(_) => Value::Array(bytes.iter().map(|&b| Value::UInt(u64::from(b))).collect()),
    }
}

/// A text's bytes from its value: a string, or an array of byte values.
pub(super) fn text_bytes(v: &Value, path: &str) -> Result<Vec<u8>, EncodeIssue> {
    let wrong = || EncodeIssue::new(path, "expected a string or an array of bytes");
    match v {
        Value::String(s) => Ok(s.as_bytes().to_vec()),
        Value::Array(items) => items
            .iter()
            .map(|item| value_bits(item, Prim::U8).map(|b| b as u8))
            .collect::<Result<Vec<u8>, _>>()
            .map_err(|_| wrong()),
        _ => Err(wrong()),
    }
}

/// Writes a NUL-terminated text of at most `max` bytes from a string or an array of byte
/// values: its bytes, then the NUL. A text longer than `max` or holding a NUL is refused,
/// never cut.
pub(super) fn write_nul_text(
    v: &Value,
    max: usize,
    w: &mut Writer<'_>,
    path: &str,
) -> Result<(), EncodeIssue> {
    let bytes = text_bytes(v, path)?;
    if !text::nul_text_fits(&bytes, max) {
        return Err(EncodeIssue::new(
            path,
            format!(
                "a text of {} bytes{} does not fit a NUL-terminated text of at most {max}",
                bytes.len(),
                if bytes.contains(&0) {
                    " holding a NUL"
                } else {
                    ""
                }
            ),
        ));
    }
    w.put_bytes(&bytes)
        .and_then(|()| w.put_u8(0))
        .map_err(EncodeIssue::runtime)
}
