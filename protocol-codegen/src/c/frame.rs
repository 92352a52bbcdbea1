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
use super::types::{Slot, keyed, slots};

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
    let _ = write!(
        out,
        "/* What a probe found: a frame, or the need of more bytes (else a rejection's reason). */\n#define {up}PROBE_FRAME 0\n#define {up}PROBE_NEED (-1)\n\n{sync}\
/* Whether the check stored at `at` is the check of the bytes `from..to` (a check without
 * value, such as one whose per-command byte names no command, matches nothing). */\n{up}UNUSED static int {lo}verify(const uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))\n{{\n    uint64_t value = 0;\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    return check(f + from, to - from, &value) && {lo}get(f + at, width, big) == value;\n}}\n\n\
/* Computes the check of `from..to` and stores it at `at`. */\n{up}UNUSED static int {lo}store(uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))\n{{\n    uint64_t value = 0;\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    if (!check(f + from, to - from, &value)) return 0;\n    {lo}set(f + at, width, big, value);\n    return 1;\n}}\n\n",
        sync = sync_matches(f, n)
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
    let span = plan
        .header_len
        .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
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
        (LengthRule::Field { adjust, .. } | LengthRule::FieldOrBare { adjust, .. }, Some(vi)) => {
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
    if let Some(bare) = plan.length.bare_len() {
        bare_probe(bare, n, out);
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
/* The probe of a candidate: the sync bytes, then the rules above. */\nstatic int {lo}probe(const uint8_t *b, size_t avail, size_t limit, size_t *n)\n{{\n    if (!{lo}sync_matches(b, avail)) return {up}REJECT_BAD_HEADER;\n    return {lo}probe_synced(b, avail, limit, n);\n}}\n\n"
    );
}

/// The sync's bytes after its lead byte: all of them, or those after the byte of a sync set.
fn sync_rest(f: &Frame) -> String {
    let bytes: Vec<String> = f.sync.iter().map(|b| format!("{b:#04x}")).collect();
    bytes.join(", ")
}

/// `SYNC_LEN` and `pfx_sync_matches`: whether a candidate's first bytes match the sync as
/// far as they go (the runtime's `sync_matches`): the sync bytes, or after a byte of the sync
/// set the sync bytes that follow it.
fn sync_matches(f: &Frame, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let lead = usize::from(!f.sync_set.is_empty());
    let mut body = String::new();
    if lead == 1 {
        let cases: String = f
            .sync_set
            .iter()
            .map(|b| format!("    case {b:#04x}:\n"))
            .collect();
        let _ = write!(
            body,
            "    if (avail == 0) return 1;\n    switch (b[0]) {{\n{cases}        break;\n    default:\n        return 0;\n    }}\n"
        );
    }
    if !f.sync.is_empty() {
        let _ = write!(
            body,
            "    {{\n        static const uint8_t rest[{len}] = {{{}}};\n        size_t i;\n        for (i = 0; i < {len}u && {lead} + i < avail; i++) {{\n            if (b[{lead} + i] != rest[i]) return 0;\n        }}\n    }}\n",
            sync_rest(f),
            len = f.sync.len()
        );
    }
    format!(
        "#define {up}SYNC_LEN {}u\n\n/* Whether `b[0..avail]` matches the sync as far as it goes. */\nstatic int {lo}sync_matches(const uint8_t *b, size_t avail)\n{{\n{body}    (void)b;\n    (void)avail;\n    return 1;\n}}\n\n",
        lead + f.sync.len()
    )
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
        "int {lo}decode(const uint8_t *bytes, size_t len, {lo}packet *out)\n{{\n    size_t n = 0;\n    uint64_t raw = 0;\n    struct {lo}rd r;\n    int e = 0;\n    if ({lo}probe(bytes, len, {up}MAX_FRAME_LEN, &n) != {up}PROBE_FRAME || n != len) return {up}ERR_FRAME;\n    memset(out, 0, sizeof *out);\n    (void)raw;\n"
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
    if f.ack.is_some() {
        ack_decode(f, n, out);
    }
    if keyed(p) {
        dispatch_key(p, n, out);
    }
    if let Some((after, insert)) = &f.stuffing {
        unstuff(after, *insert, n, out);
    }
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
                // Refused by `support::unsupported`: nothing in the header tells it.
                DirectionRule::Given => "0".to_string(),
            };
            let _ = write!(
                out,
                "if ({cond}) out->direction = {up}{};\n    else ",
                d.name.to_uppercase()
            );
        }
        let _ = writeln!(out, "return {up}ERR_UNKNOWN_DIRECTION;");
    }
    read_payload(p, n, out);
}

/// The dispatch key, one variable per field, then the command it names.
fn dispatch_key(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[0];
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
}

/// The payload of the frame `bytes[0..len]` read into the packet's member of its slot
/// (zero-filled to its struct's size first when the format truncates trailing zeros).
fn read_payload(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    // A stuffed payload is read where `unstuff` left it.
    if p.frames[0].stuffing.is_none() {
        let _ = writeln!(
            out,
            "    r.p = bytes + {up}HEADER_LEN;\n    r.len = len - {up}HEADER_LEN - {up}TRAILER_LEN;"
        );
    }
    let _ = writeln!(out, "    r.pos = 0;");
    let slots: Vec<Slot> = slots(p).into_iter().filter(|s| s.si.is_some()).collect();
    if p.frames[0].truncate_zeros {
        out.push_str(
            "    {
        /* A payload its sender cut short of trailing zeros is zero-filled. */
        static uint8_t filled[",
        );
        let _ = writeln!(
            out,
            "{up}MAX_PAYLOAD_LEN];
        size_t size = 0;"
        );
        for slot in &slots {
            let si = slot.si.unwrap_or_default();
            let _ = writeln!(
                out,
                "        if ({}) size = {}u;",
                slot.test(p, n, "out"),
                p.structs[si].size
            );
        }
        out.push_str(
            "        if (r.len < size) {
            memcpy(filled, r.p, r.len);
            memset(filled + r.len, 0, size - r.len);
            r.p = filled;
            r.len = size;
        }
    }
",
        );
    }
    for slot in &slots {
        let si = slot.si.unwrap_or_default();
        let _ = writeln!(
            out,
            "    {}e = {lo}read_{}(&r, &out->payload.{});",
            slot.guard(p, n, "out"),
            names::snake(&p.structs[si].name),
            slot.name
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
    if keyed(p) {
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
        out.push_str("};\n\n");
    }
    if f.truncate_zeros {
        let _ = write!(
            out,
            "/* The bytes of a payload its sender keeps: all but its trailing zeros, and at least the\n * first byte of a non-empty payload (the runtime's `zeros::trimmed_len`). */\nstatic size_t {lo}trimmed(const uint8_t *p, size_t len)\n{{\n    size_t kept = len;\n    while (kept > 0 && p[kept - 1] == 0) kept--;\n    return kept == 0 && len > 0 ? 1 : kept;\n}}\n\n"
        );
    }
    if let Some((after, insert)) = &f.stuffing {
        stuff(after, *insert, n, out);
    }
    let _ = write!(
        out,
        "/* The frame around a payload of `payload_len` bytes already written after the header. */\nstatic int {lo}seal(uint8_t *buf, size_t payload_len, const {lo}header *h, size_t command)\n{{\n    size_t total = {up}HEADER_LEN + payload_len + {up}TRAILER_LEN;\n    if (payload_len > {up}MAX_PAYLOAD_LEN) return {up}ERR_OUT_OF_RANGE;\n    memset(buf, 0, {up}HEADER_LEN);\n    memset(buf + {up}HEADER_LEN + payload_len, 0, {up}TRAILER_LEN);\n{sync}    (void)h;\n    (void)command;\n",
        sync = if f.sync.is_empty() {
            String::new()
        } else {
            format!(
                "    {{\n        static const uint8_t rest[{len}] = {{{}}};\n        memcpy(buf + {lead}, rest, {len}u);\n    }}\n",
                sync_rest(f),
                len = f.sync.len(),
                lead = usize::from(!f.sync_set.is_empty())
            )
        }
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
            // A command frame's acknowledgement flag: not the acknowledgement's value.
            Role::Ack(equals) => names::u64_lit(1 - (*equals).min(1)),
            Role::Flag | Role::WideLength => {
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
    if !f.sync_set.is_empty() {
        let _ = writeln!(
            out,
            "    /* The first header value is the sync: one of its set. */\n    if (!{lo}sync_matches(buf, 1)) return {up}ERR_OUT_OF_RANGE;"
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
    for slot in slots(p) {
        encoder(p, n, &slot, out);
    }
    if f.ack.is_some() {
        ack_encoder(f, n, out);
    }
    let _ = writeln!(
        out,
        "int {lo}encode(const {lo}packet *packet, uint8_t *buf, size_t cap)\n{{"
    );
    if f.ack.is_some() {
        let _ = writeln!(
            out,
            "    if (packet->ack) return {lo}encode_ack(&packet->header, packet->payload.ack_data.bytes, packet->payload.ack_data.len, buf, cap);"
        );
    }
    for slot in slots(p) {
        let payload = match slot.si {
            Some(_) => format!("&packet->payload.{}, ", slot.name),
            None => String::new(),
        };
        let _ = writeln!(
            out,
            "    {}return {lo}encode_{}(&packet->header, {payload}buf, cap);",
            slot.guard(p, n, "packet"),
            slot.name
        );
    }
    if keyed(p) {
        let _ = writeln!(out, "    return {up}ERR_OUT_OF_RANGE;");
    }
    out.push_str("}\n\n");
}

/// The encoder of one slot: its payload written after the header (and cut short of its
/// trailing zeros where the format says so), then the frame sealed around it.
fn encoder(p: &Protocol, n: &Names, slot: &Slot, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (arg, mut write) = match slot.si {
        Some(si) => (
            format!("const {} *payload, ", n.ty(&p.structs[si].name)),
            format!(
                "    if ((e = {lo}write_{}(&w, payload)) != 0) return e;\n",
                names::snake(&p.structs[si].name)
            ),
        ),
        None => (String::new(), String::new()),
    };
    if p.frames[0].truncate_zeros && slot.command.is_some() {
        write.push_str(&format!("    w.pos = {lo}trimmed(w.p, w.pos);\n"));
    }
    if p.frames[0].stuffing.is_some() && slot.command.is_some() {
        write.push_str(&format!("    if ((e = {lo}stuff(&w)) != 0) return e;\n"));
    }
    let command = match slot.command {
        Some(ci) => format!("{up}{}", p.commands[ci].name),
        None => "0".into(),
    };
    let _ = write!(
        out,
        "int {lo}encode_{}(const {lo}header *header, {arg}uint8_t *buf, size_t cap)\n{{\n    struct {lo}wr w;\n    int e = 0;\n    if (cap < {up}HEADER_LEN + {up}TRAILER_LEN) return {up}ERR_SHORT_BUFFER;\n    w.p = buf + {up}HEADER_LEN;\n    w.cap = cap - {up}HEADER_LEN - {up}TRAILER_LEN;\n    w.pos = 0;\n{write}    (void)e;\n    return {lo}seal(buf, w.pos, header, {command});\n}}\n\n",
        slot.name
    );
}

/// The bare header in the probe (the runtime's `LengthRule::FieldOrBare`): a frame of exactly
/// the bare length is complete and verified once its header checks hold.
fn bare_probe(bare: usize, n: &Names, out: &mut String) {
    let up = &n.up;
    let _ = write!(
        out,
        "    if (total == {bare}u && {bare}u >= span && {bare}u > 0 && total <= limit) {{\n        *n = total;\n        return {up}PROBE_FRAME;\n    }}\n"
    );
}

/// An acknowledgement in the decoder: when the flag holds its value, the frame carries no
/// command and its data follows the acknowledgement's header (to the frame's end for a bare
/// header, else to the trailer), at most its largest.
fn ack_decode(f: &Frame, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let Some((flag, _)) = f.ack else { return };
    let v = &f.values[flag];
    let equals = match v.role {
        Role::Ack(equals) => equals,
        _ => 1,
    };
    let end = if f.bare_len.is_some() {
        format!("len == {up}ACK_HEADER_LEN ? len : len - {up}TRAILER_LEN")
    } else {
        format!("len - {up}TRAILER_LEN")
    };
    let _ = write!(
        out,
        "    if (!{lo}field(bytes, len, {}, &raw)) return {up}ERR_FRAME;\n    if (raw == {}) {{\n        size_t end;\n        if (len < {up}ACK_HEADER_LEN) return {up}ERR_FRAME;\n        end = {end};\n        if (end < {up}ACK_HEADER_LEN) return {up}ERR_FRAME;\n        if (end - {up}ACK_HEADER_LEN > {up}ACK_MAX_LEN) return {up}ERR_PAYLOAD_LENGTH;\n        out->ack = true;\n        out->command = {up}COMMAND_COUNT;\n        out->payload.ack_data.len = end - {up}ACK_HEADER_LEN;\n        memcpy(out->payload.ack_data.bytes, bytes + {up}ACK_HEADER_LEN, out->payload.ack_data.len);\n        return 0;\n    }}\n",
        word(v),
        names::u64_lit(equals)
    );
}

/// The encoder of an acknowledgement: its data after the acknowledgement's header, the header
/// values, the flag at its value and no dispatch key; with no data and a bare header, the
/// header alone (no frame checks, no trailers), as the runtime's `seal` does.
fn ack_encoder(f: &Frame, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let plan = lower_layout(f);
    let bare = if f.bare_len.is_some() {
        "len == 0"
    } else {
        "0"
    };
    let _ = write!(
        out,
        "int {lo}encode_ack(const {lo}header *h, const uint8_t *data, size_t len, uint8_t *buf, size_t cap)\n{{\n    int bare = {bare};\n    size_t total;\n    if (len > {up}ACK_MAX_LEN) return {up}ERR_OUT_OF_RANGE;\n    total = {up}ACK_HEADER_LEN + len + (bare ? 0u : {up}TRAILER_LEN);\n    if (!bare && total < {up}MIN_FRAME_LEN) return {up}ERR_OUT_OF_RANGE;\n    if (cap < total) return {up}ERR_SHORT_BUFFER;\n    memset(buf, 0, {up}ACK_HEADER_LEN);\n    memcpy(buf + {up}ACK_HEADER_LEN, data, len);\n    if (!bare) memset(buf + {up}ACK_HEADER_LEN + len, 0, {up}TRAILER_LEN);\n"
    );
    if !f.sync.is_empty() {
        let _ = write!(
            out,
            "    {{\n        static const uint8_t rest[{len}] = {{{}}};\n        memcpy(buf + {lead}, rest, {len}u);\n    }}\n",
            sync_rest(f),
            len = f.sync.len(),
            lead = usize::from(!f.sync_set.is_empty())
        );
    }
    for v in &f.values {
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
            Role::Const(c) => names::u64_lit(*c),
            Role::Ack(equals) => names::u64_lit(*equals),
            // An acknowledgement has no dispatch key: its data takes those bytes.
            Role::Dispatch | Role::Flag | Role::WideLength => continue,
        };
        let _ = writeln!(
            out,
            "    /* {} */\n    if (!{lo}put_field(buf, total, {}, {value})) return {up}ERR_OUT_OF_RANGE;",
            v.name,
            word(v)
        );
    }
    if !f.sync_set.is_empty() {
        let _ = writeln!(
            out,
            "    if (!{lo}sync_matches(buf, 1)) return {up}ERR_OUT_OF_RANGE;"
        );
    }
    for &ci in &plan.header_checks {
        let _ = writeln!(
            out,
            "    if (!{lo}store(buf, {})) return {up}ERR_OUT_OF_RANGE;",
            check_args(lo, &f.checks[ci], "total")
        );
    }
    out.push_str("    if (bare) return (int)total;\n");
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
    for &ci in &plan.frame_checks {
        let _ = writeln!(
            out,
            "    if (!{lo}store(buf, {})) return {up}ERR_OUT_OF_RANGE;",
            check_args(lo, &f.checks[ci], "total")
        );
    }
    out.push_str("    return (int)total;\n}\n\n");
}

/// The C bytes of a stuffing pattern.
fn pattern(after: &[u8]) -> String {
    let bytes: Vec<String> = after.iter().map(|b| format!("{b:#04x}")).collect();
    bytes.join(", ")
}

/// The payload unstuffed (the runtime's `Stuffing::unstuff`) into a buffer of the largest
/// payload, which the payload is then read from: after every run of the pattern in the
/// output, the next byte must be the inserted one, and is dropped.
fn unstuff(after: &[u8], insert: u8, n: &Names, out: &mut String) {
    let up = &n.up;
    let _ = write!(
        out,
        "    {{\n        static const uint8_t pattern[{k}] = {{{}}};\n        static uint8_t plain[{up}MAX_PAYLOAD_LEN > 0 ? {up}MAX_PAYLOAD_LEN : 1];\n        const uint8_t *s = bytes + {up}HEADER_LEN;\n        size_t sn = len - {up}HEADER_LEN - {up}TRAILER_LEN, i = 0, o = 0;\n        while (i < sn) {{\n            if (o >= {up}MAX_PAYLOAD_LEN) return {up}ERR_PAYLOAD_LENGTH;\n            plain[o++] = s[i++];\n            if (o >= {k}u && memcmp(plain + o - {k}u, pattern, {k}u) == 0) {{\n                if (i < sn && s[i] == {insert:#04x}) i++;\n                else return {up}ERR_INVALID_STUFFING;\n            }}\n        }}\n        r.p = plain;\n        r.len = o;\n    }}\n",
        pattern(after),
        k = after.len()
    );
}

/// `pfx_stuff`: a written payload stuffed in place (the runtime's `Stuffing::stuff_in_place`):
/// the inserted byte after every run of the pattern, the search going on after it.
fn stuff(after: &[u8], insert: u8, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let _ = write!(
        out,
        "/* Stuffs the payload written in `w`: {insert:#04x} after every run of the pattern. */\nstatic int {lo}stuff(struct {lo}wr *w)\n{{\n    static const uint8_t pattern[{k}] = {{{}}};\n    size_t i = 0, extra = 0, cur = w->pos;\n    while (i + {k}u <= w->pos) {{\n        if (memcmp(w->p + i, pattern, {k}u) == 0) {{\n            extra++;\n            i += {k}u;\n        }} else {{\n            i++;\n        }}\n    }}\n    if (w->cap - w->pos < extra) return {up}ERR_SHORT_BUFFER;\n    i = 0;\n    while (i + {k}u <= cur) {{\n        if (memcmp(w->p + i, pattern, {k}u) == 0) {{\n            size_t end = i + {k}u;\n            memmove(w->p + end + 1, w->p + end, cur - end);\n            w->p[end] = {insert:#04x};\n            cur++;\n            i = end + 1;\n        }} else {{\n            i++;\n        }}\n    }}\n    w->pos = cur;\n    return 0;\n}}\n\n",
        pattern(after),
        k = after.len()
    );
}
