//! Where things lie in a frame, as the C helpers take them: a position, a header value's word,
//! a check's range; the truncation of a header value to its type; and the statements that
//! write a format's fixed bytes (its sync and trailers) into a frame being encoded.

use protocol_runtime::layout::WordField;

use crate::ir::{ByteOrder, Check, Frame, HeaderValue, Pos, Prim};
use crate::layout::word_field;

use super::super::names::{self, Fx, Names, mask};
use super::super::template::fill;

/// `(from_end, n)` of a position, as the C helpers take it.
pub(super) fn pos(p: Pos) -> String {
    match p {
        Pos::Start(n) => format!("0, {n}u"),
        Pos::End(n) => format!("1, {n}u"),
    }
}

/// `1` for big-endian, `0` for little-endian, as the C helpers take it.
pub(super) fn big(order: ByteOrder) -> u8 {
    u8::from(order == ByteOrder::Big)
}

/// The arguments of a word field (the frame and packet rules' `WordField`) for
/// `pfx_field`/`pfx_put_field`.
pub(super) fn field_word(w: WordField) -> String {
    format!(
        "{}, {}u, {}, {}u, {}u",
        pos(w.at),
        w.size,
        big(w.order),
        w.shift,
        w.width
    )
}

/// The arguments of a header value's word for `pfx_field`/`pfx_put_field`.
pub(super) fn word(v: &HeaderValue) -> String {
    field_word(word_field(v))
}

/// The arguments of `pfx_verify`/`pfx_store` for check `c` of format `x`, in a frame of
/// `len` bytes.
pub(super) fn check_args(n: &Names, x: &Fx, c: &Check, len: &str) -> String {
    let lo = &n.lo;
    format!(
        "{len}, {lo}pos({len}, {}), {lo}pos({len}, {}), {lo}pos({len}, {}), {}u, {}, {}check_{}",
        pos(c.from),
        pos(c.to),
        pos(c.at),
        c.size,
        big(c.endian),
        x.lo,
        c.name
    )
}

/// `value` truncated to the bits of `prim` (a bool stays 0 or 1).
pub(super) fn truncate(prim: Prim, value: u64) -> u64 {
    if prim == Prim::Bool {
        u64::from(value != 0)
    } else {
        value & mask(8 * prim.size() as u32)
    }
}

/// A header value's bits truncated to its type (`truncate` of the runtime codec).
pub(super) fn truncated(v: &HeaderValue, raw: &str) -> String {
    if v.prim == Prim::Bool {
        format!("({raw} != 0 ? 1u : 0u)")
    } else {
        format!(
            "({raw} & {})",
            names::u64_lit(mask(8 * v.prim.size() as u32))
        )
    }
}

/// Bytes as the initialiser of a C array (`0xaa, 0x55`).
pub(super) fn byte_list(bytes: &[u8]) -> String {
    let bytes: Vec<String> = bytes.iter().map(|b| format!("{b:#04x}")).collect();
    bytes.join(", ")
}

/// The statements that write a format's sync bytes into `buf` (after the byte of a sync set,
/// which a header value writes), or nothing for a format without.
pub(super) fn write_sync(f: &Frame) -> String {
    if f.sync.is_empty() {
        return String::new();
    }
    let (bytes, len, lead) = (
        byte_list(&f.sync),
        f.sync.len(),
        usize::from(!f.sync_set.is_empty()),
    );
    fill!(
        r"
    {
        static const uint8_t rest[${len}] = {${bytes}};
        memcpy(buf + ${lead}, rest, ${len}u);
    }
",
        len,
        bytes,
        lead
    )
}

/// The statements that write a format's fixed trailers into a frame of `len` bytes in `buf`.
pub(super) fn write_trailers(f: &Frame, n: &Names, len: &str) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = String::new();
    for t in &f.trailers {
        let (bytes, at, k) = (byte_list(&t.bytes), pos(t.at), t.bytes.len());
        out.push_str(&fill!(
            r"
    {
        static const uint8_t trailer[${k}] = {${bytes}};
        size_t at = ${lo}pos(${len}, ${at});
        if (at == SIZE_MAX || ${len} - at < ${k}u) return ${up}ERR_OUT_OF_RANGE;
        memcpy(buf + at, trailer, ${k}u);
    }
",
            k,
            bytes,
            lo,
            len,
            at,
            up
        ));
    }
    out
}
