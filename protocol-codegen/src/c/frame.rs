//! The frame rules in C: the probe of a candidate (the runtime engine's order of checks:
//! constants, header checks, the length within its bounds before its bytes are awaited, frame
//! checks, trailers), the decoder of one frame's bytes, and the encoders. Every position,
//! size and bound is the IR's, through the same lowering as the Rust engine's `FrameLayout`
//! ([`lower_layout`]).

use std::fmt::Write as _;

use crate::ir::{Check, DirectionRule, Frame, HeaderValue, Length, Pos, Prim, Protocol, Role};
use crate::layout::{LayoutPlan, lower_layout};
use protocol_runtime::layout::LengthRule;

use super::names::{self, Names};
use super::payload::mask;
use super::types::{slot_name, slots};

/// `(from_end, n)` of a position, as the C helpers take it.
fn pos(p: Pos) -> String {
    match p {
        Pos::Start(n) => format!("0, {n}u"),
        Pos::End(n) => format!("1, {n}u"),
    }
}

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

/// The frame rules: helpers, probe, decode, encoders.
pub fn frame(p: &Protocol, n: &Names) -> String {
    let f = &p.frames[0];
    let plan = lower_layout(f);
    let mut out = String::from("/* ---- Frame rules ---- */\n\n");
    helpers(f, n, &mut out);
    probe(f, &plan, n, &mut out);
    decode(p, n, &mut out);
    encode(p, n, &mut out);
    out
}

fn helpers(f: &Frame, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let sync: Vec<String> = f.sync.iter().map(|b| format!("{b:#04x}")).collect();
    let _ = write!(
        out,
        "/* What a probe found: a frame, or the need of more bytes (else a rejection's reason). */\n#define {up}PROBE_FRAME 0\n#define {up}PROBE_NEED (-1)\n\nstatic const uint8_t {lo}sync[{len}] = {{{sync}}};\n#define {up}SYNC_LEN {len}u\n\n\
/* A position from the frame's start or back from its end, in a frame of `len` bytes;\n * SIZE_MAX when it falls outside. */\n{up}UNUSED static size_t {lo}pos(size_t len, int from_end, size_t n)\n{{\n    if (from_end) return len >= n ? len - n : SIZE_MAX;\n    return n <= len ? n : SIZE_MAX;\n}}\n\n\
/* A value of `width` bits at bit `shift` of the word of `size` bytes at a position. */\n{up}UNUSED static int {lo}field(const uint8_t *f, size_t len, int from_end, size_t at, unsigned size, int big, unsigned shift, unsigned width, uint64_t *out)\n{{\n    size_t o = {lo}pos(len, from_end, at);\n    uint64_t m = width >= 64 ? ~(uint64_t)0 : (((uint64_t)1 << width) - 1);\n    if (o == SIZE_MAX || len - o < size) return 0;\n    *out = ({lo}get(f + o, size, big) >> shift) & m;\n    return 1;\n}}\n\n\
{up}UNUSED static int {lo}put_field(uint8_t *f, size_t len, int from_end, size_t at, unsigned size, int big, unsigned shift, unsigned width, uint64_t value)\n{{\n    size_t o = {lo}pos(len, from_end, at);\n    uint64_t m = width >= 64 ? ~(uint64_t)0 : (((uint64_t)1 << width) - 1);\n    if (o == SIZE_MAX || len - o < size || value > m) return 0;\n    {lo}set(f + o, size, big, {lo}get(f + o, size, big) | (value << shift));\n    return 1;\n}}\n\n\
/* Whether the check stored at `at` is the check of the bytes `from..to`. */\n{up}UNUSED static int {lo}verify(const uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, uint64_t (*check)(const uint8_t *, size_t))\n{{\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    return {lo}get(f + at, width, big) == check(f + from, to - from);\n}}\n\n\
/* Computes the check of `from..to` and stores it at `at`. */\n{up}UNUSED static int {lo}store(uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, uint64_t (*check)(const uint8_t *, size_t))\n{{\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    {lo}set(f + at, width, big, check(f + from, to - from));\n    return 1;\n}}\n\n",
        len = f.sync.len(),
        sync = sync.join(", ")
    );
}

fn check_args(lo: &str, c: &Check, len: &str) -> String {
    format!(
        "{len}, {lo}pos({len}, {}), {lo}pos({len}, {}), {lo}pos({len}, {}), {}u, {}, {lo}check_{}",
        pos(c.from),
        pos(c.to),
        pos(c.at),
        c.size,
        big(c.endian),
        c.name
    )
}

fn probe(f: &Frame, plan: &LayoutPlan<'_>, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let span = plan.header_len.max(plan.sync.len());
    let shortest = span.max(plan.min_len).max(1);
    let _ = write!(
        out,
        "/* The engine's rules for a candidate whose first bytes match the sync bytes (as many\n * as there are), in `b[0..avail]`; frames longer than `limit` are too long. Returns\n * {up}PROBE_FRAME with the frame's length in `*n`, {up}PROBE_NEED with the bytes needed\n * in `*n`, or the reason of a rejection. */\nstatic int {lo}probe_synced(const uint8_t *b, size_t avail, size_t limit, size_t *n)\n{{\n    const size_t span = {span}u;\n    size_t total;\n    uint64_t raw = 0;\n    if (span > limit) {{\n        if (avail < {up}SYNC_LEN) {{\n            *n = {up}SYNC_LEN;\n            return {up}PROBE_NEED;\n        }}\n        return {up}REJECT_BAD_LENGTH;\n    }}\n    if (avail < span) {{\n        *n = span;\n        return {up}PROBE_NEED;\n    }}\n"
    );
    for (vi, c) in &plan.constants {
        let _ = writeln!(
            out,
            "    if (!{lo}field(b, span, {}, &raw) || raw != {}) return {up}REJECT_BAD_HEADER;",
            word(&f.values[*vi]),
            names::u64_lit(c.value)
        );
    }
    for &ci in &plan.header_checks {
        let _ = writeln!(
            out,
            "    if (!{lo}verify(b, {})) return {up}REJECT_BAD_HEADER_CHECK;",
            check_args(lo, &f.checks[ci], "span")
        );
    }
    match (plan.length, plan.length_value) {
        (LengthRule::Field { adjust, .. }, Some(vi)) => {
            let _ = writeln!(
                out,
                "    if (!{lo}field(b, span, {}, &raw) || raw > (uint64_t)INT64_MAX) return {up}REJECT_BAD_LENGTH;",
                word(&f.values[vi])
            );
            if adjust >= 0 {
                let _ = write!(
                    out,
                    "    if (raw > (uint64_t)INT64_MAX - {adjust}u) return {up}REJECT_BAD_LENGTH;\n    raw += {adjust}u;\n"
                );
            } else {
                let neg = adjust.unsigned_abs();
                let _ = write!(
                    out,
                    "    if (raw < {neg}u) return {up}REJECT_BAD_LENGTH;\n    raw -= {neg}u;\n"
                );
            }
            let _ = write!(
                out,
                "    if (raw > (uint64_t)SIZE_MAX) return {up}REJECT_BAD_LENGTH;\n    total = (size_t)raw;\n"
            );
        }
        (LengthRule::Fixed(len), _) => {
            let _ = writeln!(out, "    total = {len}u;");
        }
        _ => unreachable!("refused by support::unsupported"),
    }
    let _ = write!(
        out,
        "    if (limit < {shortest}u || total < {shortest}u || total > limit) return {up}REJECT_BAD_LENGTH;\n    if (avail < total) {{\n        *n = total;\n        return {up}PROBE_NEED;\n    }}\n"
    );
    for &ci in &plan.frame_checks {
        let _ = writeln!(
            out,
            "    if (!{lo}verify(b, {})) return {up}REJECT_BAD_CHECKSUM;",
            check_args(lo, &f.checks[ci], "total")
        );
    }
    for (i, m) in plan.markers.iter().enumerate() {
        let bytes: Vec<String> = m.bytes.iter().map(|b| format!("{b:#04x}")).collect();
        let _ = write!(
            out,
            "    {{\n        static const uint8_t marker{i}[{len}] = {{{}}};\n        size_t at = {lo}pos(total, {});\n        if (at == SIZE_MAX || total - at < {len}u || memcmp(b + at, marker{i}, {len}u) != 0) return {up}REJECT_BAD_TRAILER;\n    }}\n",
            bytes.join(", "),
            pos(m.at),
            len = m.bytes.len()
        );
    }
    let _ = write!(
        out,
        "    (void)raw;\n    *n = total;\n    return {up}PROBE_FRAME;\n}}\n\n\
/* The probe of a candidate: the sync bytes, then the rules above. */\nstatic int {lo}probe(const uint8_t *b, size_t avail, size_t limit, size_t *n)\n{{\n    size_t i;\n    for (i = 0; i < avail && i < {up}SYNC_LEN; i++) {{\n        if (b[i] != {lo}sync[i]) return {up}REJECT_BAD_HEADER;\n    }}\n    return {lo}probe_synced(b, avail, limit, n);\n}}\n\n"
    );
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

fn decode(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[0];
    let _ = write!(
        out,
        "int {lo}decode(const uint8_t *bytes, size_t len, {lo}packet *out)\n{{\n    size_t n = 0;\n    uint64_t raw = 0;\n    struct {lo}rd r;\n    int e = 0;\n    if ({lo}probe(bytes, len, {up}MAX_FRAME_LEN, &n) != {up}PROBE_FRAME || n != len) return {up}ERR_FRAME;\n    memset(out, 0, sizeof *out);\n"
    );
    for v in f
        .values
        .iter()
        .filter(|v| matches!(v.role, Role::User { .. }))
    {
        let value = if v.prim == Prim::Bool {
            "(raw != 0)".to_string()
        } else {
            format!("({})raw", names::unsigned_of(v.prim.size()))
        };
        let _ = writeln!(
            out,
            "    if (!{lo}field(bytes, len, {}, &raw)) return {up}ERR_FRAME;\n    out->header.{} = {value};",
            word(v),
            names::field(&v.name)
        );
    }
    // The dispatch key, one variable per field, then the command it names.
    let _ = writeln!(out, "    {{\n        uint64_t key[{}];", f.dispatch.len());
    for (k, &vi) in f.dispatch.iter().enumerate() {
        let v = &f.values[vi];
        let _ = writeln!(
            out,
            "        if (!{lo}field(bytes, len, {}, &raw)) return {up}ERR_FRAME;\n        key[{k}] = {};",
            word(v),
            truncated(v, "raw")
        );
    }
    out.push_str("        ");
    for c in &p.commands {
        let conds: Vec<String> = f
            .dispatch
            .iter()
            .zip(&c.id)
            .enumerate()
            .map(|(k, (&vi, id))| {
                let v = &f.values[vi];
                format!("key[{k}] == {}", names::u64_lit(truncate(v.prim, *id)))
            })
            .collect();
        let _ = write!(
            out,
            "if ({}) out->command = {up}{};\n        else ",
            conds.join(" && "),
            c.name
        );
    }
    let _ = writeln!(out, "return {up}ERR_UNKNOWN_COMMAND;\n    }}");
    if !p.directions.is_empty() {
        out.push_str("    ");
        for d in &p.directions {
            let cond = match &d.rule {
                DirectionRule::InSet { value, set } => {
                    let v = &f.values[*value];
                    let a = &p.addresses[*set];
                    format!(
                        "{lo}field(bytes, len, {}, &raw) && {} >= {} && {} <= {}",
                        word(v),
                        truncated(v, "raw"),
                        names::u64_lit(truncate(v.prim, a.first)),
                        truncated(v, "raw"),
                        names::u64_lit(truncate(v.prim, a.last))
                    )
                }
                DirectionRule::Equals { value, equals } => {
                    let v = &f.values[*value];
                    format!(
                        "{lo}field(bytes, len, {}, &raw) && {} == {}",
                        word(v),
                        truncated(v, "raw"),
                        names::u64_lit(*equals)
                    )
                }
            };
            let _ = write!(
                out,
                "if ({cond}) out->direction = {up}{};\n    else ",
                d.name.to_uppercase()
            );
        }
        let _ = writeln!(out, "return {up}ERR_UNKNOWN_DIRECTION;");
    }
    let _ = writeln!(
        out,
        "    r.p = bytes + {up}HEADER_LEN;\n    r.len = len - {up}HEADER_LEN - {up}TRAILER_LEN;\n    r.pos = 0;"
    );
    for (ci, di, si) in slots(p) {
        let dir = if p.directions.is_empty() {
            String::new()
        } else {
            format!(
                " && out->direction == {up}{}",
                p.directions[di].name.to_uppercase()
            )
        };
        let _ = writeln!(
            out,
            "    if (out->command == {up}{}{dir}) e = {lo}read_{}(&r, &out->payload.{});",
            p.commands[ci].name,
            names::snake(&p.structs[si].name),
            slot_name(p, ci, di)
        );
    }
    let _ = writeln!(
        out,
        "    if (e != 0) return e;\n    if (r.pos != r.len) return {up}ERR_PAYLOAD_LENGTH;\n    return 0;\n}}\n"
    );
}

/// `value` truncated to the bits of `prim` (a bool stays 0 or 1).
fn truncate(prim: Prim, value: u64) -> u64 {
    if prim == Prim::Bool {
        u64::from(value != 0)
    } else {
        value & mask(8 * prim.size() as u32)
    }
}

fn encode(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[0];
    let widest = f
        .dispatch
        .iter()
        .map(|&vi| f.values[vi].prim.size())
        .max()
        .unwrap_or(1);
    let _ = writeln!(
        out,
        "/* The dispatch key of every command, in command order. */\nstatic const {} {lo}ids[{}][{}] = {{",
        names::unsigned_of(widest),
        p.commands.len().max(1),
        f.dispatch.len()
    );
    for c in &p.commands {
        let ids: Vec<String> = c.id.iter().map(|&v| format!("{v:#x}u")).collect();
        let _ = writeln!(out, "    {{{}}},", ids.join(", "));
    }
    let _ = write!(
        out,
        "}};\n\n/* The frame around a payload of `payload_len` bytes already written after the header. */\nstatic int {lo}seal(uint8_t *buf, size_t payload_len, const {lo}header *h, {lo}command command)\n{{\n    size_t total = {up}HEADER_LEN + payload_len + {up}TRAILER_LEN;\n    if (payload_len > {up}MAX_PAYLOAD_LEN) return {up}ERR_OUT_OF_RANGE;\n    memset(buf, 0, {up}HEADER_LEN);\n    memset(buf + {up}HEADER_LEN + payload_len, 0, {up}TRAILER_LEN);\n    memcpy(buf, {lo}sync, {up}SYNC_LEN);\n    (void)h;\n    (void)command;\n"
    );
    for (vi, v) in f.values.iter().enumerate() {
        let value = match &v.role {
            Role::User { .. } => format!("(uint64_t)h->{}", names::field(&v.name)),
            Role::Length => match &f.length {
                Length::Field { adjust, .. } => {
                    let _ = writeln!(
                        out,
                        "    if ((int64_t)total - ({adjust}) < 0) return {up}ERR_OUT_OF_RANGE;"
                    );
                    format!("(uint64_t)((int64_t)total - ({adjust}))")
                }
                Length::Fixed(_) => continue,
            },
            Role::Dispatch => {
                let k = f.dispatch.iter().position(|&d| d == vi).unwrap_or(0);
                format!("(uint64_t){lo}ids[command][{k}]")
            }
            Role::Const(c) => names::u64_lit(*c),
            Role::Ack(_) | Role::Flag | Role::WideLength => {
                unreachable!("refused by support::unsupported")
            }
        };
        let _ = writeln!(
            out,
            "    /* {} */\n    if (!{lo}put_field(buf, total, {}, {value})) return {up}ERR_OUT_OF_RANGE;",
            v.name,
            word(v)
        );
    }
    for c in &f.checks {
        let _ = writeln!(
            out,
            "    if (!{lo}store(buf, {})) return {up}ERR_OUT_OF_RANGE;",
            check_args(lo, c, "total")
        );
    }
    for t in &f.trailers {
        let bytes: Vec<String> = t.bytes.iter().map(|b| format!("{b:#04x}")).collect();
        let _ = write!(
            out,
            "    {{\n        static const uint8_t trailer[{len}] = {{{}}};\n        size_t at = {lo}pos(total, {});\n        if (at == SIZE_MAX || total - at < {len}u) return {up}ERR_OUT_OF_RANGE;\n        memcpy(buf + at, trailer, {len}u);\n    }}\n",
            bytes.join(", "),
            pos(t.at),
            len = t.bytes.len()
        );
    }
    let _ = writeln!(out, "    return (int)total;\n}}\n");
    for (ci, c) in p.commands.iter().enumerate() {
        for (di, si) in c.payloads.iter().enumerate() {
            let (arg, write) = match si {
                Some(si) => (
                    format!("const {} *payload, ", n.ty(&p.structs[*si].name)),
                    format!(
                        "    if ((e = {lo}write_{}(&w, payload)) != 0) return e;\n",
                        names::snake(&p.structs[*si].name)
                    ),
                ),
                None => (String::new(), String::new()),
            };
            let _ = write!(
                out,
                "int {lo}encode_{}(const {lo}header *header, {arg}uint8_t *buf, size_t cap)\n{{\n    struct {lo}wr w;\n    int e = 0;\n    if (cap < {up}HEADER_LEN + {up}TRAILER_LEN) return {up}ERR_SHORT_BUFFER;\n    w.p = buf + {up}HEADER_LEN;\n    w.cap = cap - {up}HEADER_LEN - {up}TRAILER_LEN;\n    w.pos = 0;\n{write}    (void)e;\n    return {lo}seal(buf, w.pos, header, {up}{});\n}}\n\n",
                slot_name(p, ci, di),
                c.name
            );
        }
    }
    let _ = writeln!(
        out,
        "int {lo}encode(const {lo}packet *packet, uint8_t *buf, size_t cap)\n{{"
    );
    for (ci, c) in p.commands.iter().enumerate() {
        for (di, si) in c.payloads.iter().enumerate() {
            let dir = if p.directions.is_empty() {
                String::new()
            } else {
                format!(
                    " && packet->direction == {up}{}",
                    p.directions[di].name.to_uppercase()
                )
            };
            let payload = match si {
                Some(_) => format!("&packet->payload.{}, ", slot_name(p, ci, di)),
                None => String::new(),
            };
            let _ = writeln!(
                out,
                "    if (packet->command == {up}{}{dir}) return {lo}encode_{}(&packet->header, {payload}buf, cap);",
                c.name,
                slot_name(p, ci, di)
            );
        }
    }
    let _ = writeln!(out, "    return {up}ERR_OUT_OF_RANGE;\n}}\n");
}
