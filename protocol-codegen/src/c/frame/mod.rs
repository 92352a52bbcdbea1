//! The frame rules in C: the probe of a candidate (`probe`), the decoder of one frame's bytes
//! (`decode`), the encoders (`encode`), and the packet rules between a checked frame and a
//! packet, each with its decoding and encoding side by side (`rules`: acknowledgements, byte
//! stuffing, trailing-zero truncation). Every position, size and bound is the IR's, through
//! the same lowering as the Rust engine's `FrameLayout` ([`lower_layout`]). This module holds
//! what they share: a format's sync, and the arguments of the helpers that read and write a
//! header value or a check.

mod decode;
mod encode;
mod probe;
mod rules;

use crate::ir::{Check, Frame, HeaderValue, Pos, Prim, Protocol, Transport};
use crate::layout::lower_layout;

use super::names::{self, Fx, Names, mask};
use super::template::fill;

/// The frame rules: the shared helpers (`templates/frame.c`), then for every frame format its
/// sync, probe, decoder of one frame and encoders (and, for a CAN format, its CAN frame
/// functions, `templates/can.c`).
pub fn frame(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = String::from("/* ---- Frame rules ---- */\n\n");
    out.push_str(&fill!(include_str!("../templates/frame.c"), lo, up));
    out.push('\n');
    for fi in 0..p.frames.len() {
        let x = Fx::new(p, fi);
        let f = &p.frames[fi];
        out.push_str(&format!("/* -- Frame format `{}` -- */\n\n", f.name));
        out.push_str(&sync_matches(f, n, &x));
        probe::probe(f, &lower_layout(f), n, &x, &mut out);
        decode::decode(p, n, &x, &mut out);
        encode::encode(p, n, &x, &mut out);
        if let Transport::Can { .. } = f.transport {
            let (xlo, xup) = (&x.lo, &x.up);
            out.push_str(&fill!(include_str!("../templates/can.c"), lo, up, xlo, xup));
            out.push('\n');
        }
    }
    out
}

/// `(from_end, n)` of a position, as the C helpers take it.
fn pos(p: Pos) -> String {
    match p {
        Pos::Start(n) => format!("0, {n}u"),
        Pos::End(n) => format!("1, {n}u"),
    }
}

/// `1` for big-endian, `0` for little-endian, as the C helpers take it.
fn big(order: crate::ir::ByteOrder) -> u8 {
    u8::from(order == crate::ir::ByteOrder::Big)
}

/// The arguments of a header value's word for `pfx_field`/`pfx_put_field`.
fn word(v: &HeaderValue) -> String {
    format!(
        "{}, {}u, {}, {}u, {}u",
        pos(v.at),
        v.word.prim.size(),
        big(v.word.endian),
        v.shift,
        v.width
    )
}

/// The arguments of `pfx_verify`/`pfx_store` for check `c` of format `x`, in a frame of
/// `len` bytes.
fn check_args(n: &Names, x: &Fx, c: &Check, len: &str) -> String {
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
fn truncate(prim: Prim, value: u64) -> u64 {
    if prim == Prim::Bool {
        u64::from(value != 0)
    } else {
        value & mask(8 * prim.size() as u32)
    }
}

/// A header value's bits truncated to its type (`truncate` of the runtime codec).
fn truncated(v: &HeaderValue, raw: &str) -> String {
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
fn byte_list(bytes: &[u8]) -> String {
    let bytes: Vec<String> = bytes.iter().map(|b| format!("{b:#04x}")).collect();
    bytes.join(", ")
}

/// The statements that write a format's sync bytes into `buf` (after the byte of a sync set,
/// which a header value writes), or nothing for a format without.
fn write_sync(f: &Frame) -> String {
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
fn write_trailers(f: &Frame, n: &Names, len: &str) -> String {
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

/// `SYNC_LEN` and `pfx_sync_matches` of a format: whether a candidate's first bytes match the
/// sync as far as they go (the runtime's `sync_matches`): the sync bytes, or after a byte of
/// the sync set the sync bytes that follow it.
fn sync_matches(f: &Frame, n: &Names, x: &Fx) -> String {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let lead = usize::from(!f.sync_set.is_empty());
    let mut body = String::new();
    if lead == 1 {
        let cases: String = f
            .sync_set
            .iter()
            .map(|b| format!("    case {b:#04x}:\n"))
            .collect();
        body.push_str(&fill!(
            r"
    if (avail == 0) return 1;
    switch (b[0]) {
${cases}        break;
    default:
        return 0;
    }
",
            cases
        ));
    }
    // One comparison per sync byte, unrolled: the stream decoder asks at every byte it scans.
    for (i, byte) in f.sync.iter().enumerate() {
        let (at, byte) = (lead + i, format!("{byte:#04x}"));
        body.push_str(&fill!(
            r"
    if (avail <= ${at}u) return 1;
    if (b[${at}] != ${byte}) return 0;
",
            at,
            byte
        ));
    }
    let len = lead + f.sync.len();
    fill!(
        r"
#define ${xup}SYNC_LEN ${len}u

/* Whether `b[0..avail]` matches the sync as far as it goes. */
${up}UNUSED static ${up}INLINE int ${xlo}sync_matches(const uint8_t *b, size_t avail)
{
${body}    (void)b;
    (void)avail;
    return 1;
}

",
        xup,
        len,
        up,
        xlo,
        body
    )
}
