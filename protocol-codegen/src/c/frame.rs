//! The frame rules in C: the probe of a candidate (the runtime engine's order of checks:
//! constants, header checks, the length within its bounds before its bytes are awaited, frame
//! checks, trailers), the decoder of one frame's bytes, and the encoders. Every position,
//! size and bound is the IR's, through the same lowering as the Rust engine's `FrameLayout`
//! ([`lower_layout`]).

use std::fmt::Write as _;

use crate::ir::{
    Check, DirectionRule, Frame, HeaderValue, Length, Pos, Prim, Protocol, Role, Transport,
};
use crate::layout::{LayoutPlan, lower_layout};
use protocol_runtime::layout::LengthRule;

use super::names::{self, Fx, Names, mask};
use super::shape::{Carries, Slot, carries, slots_of, user_values};

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

/// The frame rules: the shared helpers, then for every frame format its sync, probe, decoder
/// of one frame and encoders (and, for a CAN format, its CAN frame functions).
pub fn frame(p: &Protocol, n: &Names) -> String {
    let mut out = String::from("/* ---- Frame rules ---- */\n\n");
    helpers(n, &mut out);
    for fi in 0..p.frames.len() {
        let x = Fx::new(p, fi);
        let f = &p.frames[fi];
        let plan = lower_layout(f);
        let _ = writeln!(out, "/* -- Frame format `{}` -- */\n", f.name);
        out.push_str(&sync_matches(f, n, &x));
        probe(f, &plan, n, &x, &mut out);
        decode(p, n, &x, &mut out);
        encode(p, n, &x, &mut out);
        if let Transport::Can { .. } = f.transport {
            can(n, &x, &mut out);
        }
    }
    out
}

fn helpers(n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let _ = write!(
        out,
        "/* What a probe found: a frame, or the need of more bytes (else a rejection's reason). */\n#define {up}PROBE_FRAME 0\n#define {up}PROBE_NEED (-1)\n\n\
/* Whether the check stored at `at` is the check of the bytes `from..to` (a check without
 * value, such as one whose per-command byte names no command, matches nothing). */\n{up}UNUSED static {up}INLINE int {lo}verify(const uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))\n{{\n    uint64_t value = 0;\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    return check(f + from, to - from, &value) && {lo}get(f + at, width, big) == value;\n}}\n\n\
/* Computes the check of `from..to` and stores it at `at`. */\n{up}UNUSED static {up}INLINE int {lo}store(uint8_t *f, size_t len, size_t from, size_t to, size_t at, unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))\n{{\n    uint64_t value = 0;\n    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;\n    if (!check(f + from, to - from, &value)) return 0;\n    {lo}set(f + at, width, big, value);\n    return 1;\n}}\n\n"
    );
}

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

/// `raw` (a `uint64_t` holding a count) plus `adjust`, or a rejection for bad length when the
/// sum is negative or beyond `INT64_MAX` (the runtime's checked arithmetic).
fn adjusted(adjust: i64, up: &str) -> String {
    let mut out = format!("    if (raw > (uint64_t)INT64_MAX) return {up}REJECT_BAD_LENGTH;\n");
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
    out
}

fn probe(f: &Frame, plan: &LayoutPlan<'_>, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let span = plan
        .header_len
        .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
    let shortest = span.max(plan.min_len).max(1);
    let conditional = matches!(plan.length, LengthRule::Conditional { .. });
    let _ = write!(
        out,
        "/* The engine's rules for a candidate whose first bytes match the sync bytes (as many\n * as there are), in `b[0..avail]`; frames longer than `limit` are too long. Returns\n * {up}PROBE_FRAME with the frame's length in `*n`, {up}PROBE_NEED with the bytes needed\n * in `*n`, or the reason of a rejection. */\nstatic int {xlo}probe_synced(const uint8_t *b, size_t avail, size_t limit, size_t *n)\n{{\n    const size_t span = {span}u;\n    size_t total;\n{body_decl}    uint64_t raw = 0;\n    if (span > limit) {{\n{need_sync}        return {up}REJECT_BAD_LENGTH;\n    }}\n    if (avail < span) {{\n        *n = span;\n        return {up}PROBE_NEED;\n    }}\n",
        body_decl = if conditional {
            "    size_t body;\n"
        } else {
            ""
        },
        // A sync cut by the end of the bytes may be no candidate at all: decided first.
        need_sync = if f.sync.is_empty() && f.sync_set.is_empty() {
            String::new()
        } else {
            format!(
                "        if (avail < {xup}SYNC_LEN) {{\n            *n = {xup}SYNC_LEN;\n            return {up}PROBE_NEED;\n        }}\n"
            )
        }
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
            check_args(n, x, &f.checks[ci], "span")
        );
    }
    let frame_len = match (plan.length, plan.length_value) {
        (LengthRule::Field { adjust, .. } | LengthRule::FieldOrBare { adjust, .. }, Some(vi)) => {
            let _ = writeln!(
                out,
                "    if (!{lo}field(b, span, {}, &raw)) return {up}REJECT_BAD_LENGTH;",
                word(&f.values[vi])
            );
            out.push_str(&adjusted(adjust, up));
            let _ = write!(
                out,
                "    if (raw > (uint64_t)SIZE_MAX) return {up}REJECT_BAD_LENGTH;\n    total = (size_t)raw;\n"
            );
            "total"
        }
        (LengthRule::Fixed(len), _) => {
            let _ = writeln!(out, "    total = {len}u;");
            "total"
        }
        (LengthRule::Conditional { adjust, .. }, Some(vi)) => {
            conditional_length(f, adjust, vi, n, out);
            "body"
        }
        _ => unreachable!("refused by support::unsupported"),
    };
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
            check_args(n, x, &f.checks[ci], frame_len)
        );
    }
    for (i, m) in plan.markers.iter().enumerate() {
        let bytes: Vec<String> = m.bytes.iter().map(|b| format!("{b:#04x}")).collect();
        let _ = write!(
            out,
            "    {{\n        static const uint8_t marker{i}[{len}] = {{{}}};\n        size_t at = {lo}pos({frame_len}, {});\n        if (at == SIZE_MAX || {frame_len} - at < {len}u || memcmp(b + at, marker{i}, {len}u) != 0) return {up}REJECT_BAD_TRAILER;\n    }}\n",
            bytes.join(", "),
            pos(m.at),
            len = m.bytes.len()
        );
    }
    let _ = write!(
        out,
        "    (void)raw;\n    *n = total;\n    return {up}PROBE_FRAME;\n}}\n\n\
/* The probe of a candidate: the sync bytes, then the rules above. */\nstatic int {xlo}probe(const uint8_t *b, size_t avail, size_t limit, size_t *n)\n{{\n    if (!{xlo}sync_matches(b, avail)) return {up}REJECT_BAD_HEADER;\n    return {xlo}probe_synced(b, avail, limit, n);\n}}\n\n"
    );
}

/// The length of a frame whose parts depend on header values (the runtime's
/// `conditional::measure`): the count of the length field, or of the wider length its marker
/// announces (awaited when its bytes have not come; a marker form whose smallest frame or wider
/// length lies beyond `limit` is rejected first), the body (`body`: the frame without its flag
/// trailer) and the total with the flag trailer when its flag is set.
fn conditional_length(f: &Frame, adjust: i64, length_value: usize, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let _ = writeln!(
        out,
        "    if (!{lo}field(b, span, {}, &raw)) return {up}REJECT_BAD_LENGTH;\n    {{\n        uint64_t extra = 0;",
        word(&f.values[length_value])
    );
    if let Some(e) = &f.length_extension {
        let wide = &f.values[e.value];
        let needed = match wide.at {
            Pos::Start(at) => at + wide.word.prim.size(),
            Pos::End(_) => usize::MAX,
        };
        let smallest = i128::from(e.marker) + i128::from(adjust) + e.len as i128;
        let too_long = if smallest < 0 || smallest > usize::MAX as i128 || needed == usize::MAX {
            format!("            return {up}REJECT_BAD_LENGTH;\n")
        } else {
            format!(
                "            if ({smallest}u > limit || {needed}u > limit) return {up}REJECT_BAD_LENGTH;\n"
            )
        };
        let _ = write!(
            out,
            "        if (raw == {marker}) {{\n{too_long}            if (avail < {needed}u) {{\n                *n = {needed}u;\n                return {up}PROBE_NEED;\n            }}\n            if (!{lo}field(b, {needed}u, {}, &raw) || raw < {marker}) return {up}REJECT_BAD_LENGTH;\n            extra = {}u;\n        }} else if (raw > {marker}) {{\n            return {up}REJECT_BAD_LENGTH;\n        }}\n",
            word(wide),
            e.len,
            marker = names::u64_lit(e.marker)
        );
    }
    for line in adjusted(adjust, up).lines() {
        let _ = writeln!(out, "    {line}");
    }
    let _ = writeln!(
        out,
        "        raw += extra;\n        if (raw > (uint64_t)SIZE_MAX) return {up}REJECT_BAD_LENGTH;\n        body = (size_t)raw;\n    }}\n    total = body;"
    );
    if let Some(t) = &f.flag_trailer {
        let _ = writeln!(
            out,
            "    if ({lo}field(b, span, {}, &raw) && raw != 0) {{\n        if (total > SIZE_MAX - {len}u) return {up}REJECT_BAD_LENGTH;\n        total += {len}u;\n    }}",
            word(&f.values[t.flag]),
            len = t.len
        );
    }
}

/// The sync's bytes after its lead byte: all of them, or those after the byte of a sync set.
fn sync_rest(f: &Frame) -> String {
    let bytes: Vec<String> = f.sync.iter().map(|b| format!("{b:#04x}")).collect();
    bytes.join(", ")
}

/// `SYNC_LEN` and `pfx_sync_matches` of a format: whether a candidate's first bytes match the
/// sync as far as they go (the runtime's `sync_matches`): the sync bytes, or after a byte of
/// the sync set the sync bytes that follow it.
fn sync_matches(f: &Frame, n: &Names, x: &Fx) -> String {
    let (xlo, xup) = (&x.lo, &x.up);
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
    // One comparison per sync byte, unrolled: the stream decoder asks at every byte it scans.
    for (i, byte) in f.sync.iter().enumerate() {
        let _ = writeln!(
            body,
            "    if (avail <= {at}u) return 1;\n    if (b[{at}] != {byte:#04x}) return 0;",
            at = lead + i
        );
    }
    format!(
        "#define {xup}SYNC_LEN {}u\n\n/* Whether `b[0..avail]` matches the sync as far as it goes. */\n{}UNUSED static {}INLINE int {xlo}sync_matches(const uint8_t *b, size_t avail)\n{{\n{body}    (void)b;\n    (void)avail;\n    return 1;\n}}\n\n",
        lead + f.sync.len(),
        n.up,
        n.up
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

fn decode(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let f = &p.frames[x.fi];
    let fill = fill_len(p, x.fi);
    let filled = if fill > 0 {
        format!("    uint8_t filled[{fill}];\n")
    } else {
        String::new()
    };
    let given = x.fi == 0 && p.directions_given();
    if given {
        // The direction comes from the caller: one decoder per direction.
        let _ = writeln!(
            out,
            "int {xlo}decode(const uint8_t *bytes, size_t len, {xlo}packet *out)\n{{\n    return {xlo}decode_given(bytes, len, {up}DIRECTION_COUNT, out);\n}}\n"
        );
        for d in &p.directions {
            let _ = writeln!(
                out,
                "int {xlo}decode_{}(const uint8_t *bytes, size_t len, {xlo}packet *out)\n{{\n    return {xlo}decode_given(bytes, len, {up}{}, out);\n}}\n",
                d.name,
                d.name.to_uppercase()
            );
        }
    }
    // The checking entry point: the probe of the stream decoder's rules on the whole bytes,
    // then the reading of a checked frame.
    let (checking, trusting, direction, pass) = if given {
        (
            format!(
                "{xlo}decode_given(const uint8_t *bytes, size_t len, {lo}direction direction, {xlo}packet *out)"
            ),
            format!(
                "{xlo}decode_frame_given(const uint8_t *bytes, size_t len, {lo}direction direction, {xlo}packet *out)"
            ),
            "direction, ",
            "_given",
        )
    } else {
        (
            format!("{xlo}decode(const uint8_t *bytes, size_t len, {xlo}packet *out)"),
            format!("{xlo}decode_frame(const uint8_t *bytes, size_t len, {xlo}packet *out)"),
            "",
            "",
        )
    };
    if given {
        let _ = writeln!(
            out,
            "int {xlo}decode_frame(const uint8_t *bytes, size_t len, {xlo}packet *out)\n{{\n    return {xlo}decode_frame_given(bytes, len, {up}DIRECTION_COUNT, out);\n}}\n"
        );
    }
    let _ = writeln!(
        out,
        "int {checking}\n{{\n    size_t n = 0;\n    if ({xlo}probe(bytes, len, {xup}MAX_FRAME_LEN, &n) != {up}PROBE_FRAME || n != len) return {up}ERR_FRAME;\n    return {xlo}decode_frame{pass}(bytes, len, {direction}out);\n}}\n"
    );
    // The framing is trusted, but any bytes are read within `len`: the payload's end is
    // computed only when the trailer fits.
    let short = if f.trailer_len > 0 {
        format!(" || len < {xup}TRAILER_LEN")
    } else {
        String::new()
    };
    // Everything before the payload is zeroed, and a payload struct just before it is read:
    // not the whole union, whose largest member may be many times the frame's.
    let zero = if carries(p, x.fi) == Carries::Bytes {
        "    memset(out, 0, sizeof *out);\n".to_string()
    } else {
        format!("    memset(out, 0, offsetof({xlo}packet, payload));\n")
    };
    let _ = write!(
        out,
        "int {trusting}\n{{\n    size_t start = {xup}HEADER_LEN, end;\n    uint64_t raw = 0;\n    struct {lo}rd r;\n    int e = 0;\n{filled}    if (len > {xup}MAX_FRAME_LEN{short}) return {up}ERR_FRAME;\n{zero}    (void)raw;\n    end = len - {xup}TRAILER_LEN;\n"
    );
    for v in user_values(f) {
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
    if let (Some(e), Length::Field { value, .. }) = (&f.length_extension, &f.length) {
        let _ = writeln!(
            out,
            "    /* The wider length, when the length field holds its marker. */\n    if ({lo}field(bytes, len, {}, &raw) && raw == {}) start += {}u;",
            word(&f.values[*value]),
            names::u64_lit(e.marker),
            e.len
        );
    }
    if f.ack.is_some() {
        ack_decode(f, n, out);
    }
    if let Some(t) = &f.flag_trailer {
        let name = names::field(&t.name);
        let _ = writeln!(
            out,
            "    /* `{}`: the last bytes, when its flag is set. */\n    if ({lo}field(bytes, len, {}, &raw) && raw != 0) {{\n        if (end < {len}u) return {up}ERR_FRAME;\n        end -= {len}u;\n        out->header.{name}_present = 1;\n        memcpy(out->header.{name}, bytes + end + {xup}TRAILER_LEN, {len}u);\n    }}",
            t.name,
            word(&f.values[t.flag]),
            len = t.len
        );
    }
    let _ = writeln!(out, "    if (end < start) return {up}ERR_FRAME;");
    if given {
        given_direction(p, n, out);
    }
    match carries(p, x.fi) {
        Carries::Commands => {
            dispatch_key(p, n, x, out);
            if !given {
                directions(p, n, x.fi, out);
            }
        }
        Carries::Can => can_command(p, n, x, out),
        Carries::Message(_) => {}
        Carries::Bytes => {
            let _ = writeln!(
                out,
                "    /* The payload's bytes as they are. */\n    if (end - start > sizeof out->payload) return {up}ERR_PAYLOAD_LENGTH;\n    out->payload_len = end - start;\n    if (out->payload_len > 0) memcpy(out->payload, bytes + start, out->payload_len);\n    r.p = NULL;\n    r.len = r.pos = 0;\n    (void)r;\n    (void)e;\n    return 0;\n}}\n"
            );
            return;
        }
    }
    if let Some((after, insert)) = &f.stuffing {
        unstuff(after, *insert, n, x, out);
    }
    read_payload(p, n, x, out);
}

/// The direction the decoder is given: none is an unknown direction; a direction whose frames
/// carry one struct reads it from where the dispatch key would be.
fn given_direction(p: &Protocol, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let _ = writeln!(
        out,
        "    if ((int)direction < 0 || direction >= {up}DIRECTION_COUNT) return {up}ERR_UNKNOWN_DIRECTION;\n    out->direction = direction;"
    );
    for d in &p.directions {
        let Some((si, start)) = d.message else {
            continue;
        };
        let _ = writeln!(
            out,
            "    if (direction == {up}{}) {{\n        out->command = {up}COMMAND_COUNT; /* none */\n        if (end < {start}u) return {up}ERR_FRAME;\n        r.p = bytes + {start}u;\n        r.len = end - {start}u;\n        r.pos = 0;\n        memset(&out->payload.{name}, 0, sizeof out->payload.{name});\n        if ((e = {lo}read_{}(&r, &out->payload.{name})) != 0) return e;\n        return r.pos != r.len ? {up}ERR_PAYLOAD_LENGTH : 0;\n    }}",
            d.name.to_uppercase(),
            names::snake(&p.structs[si].name),
            name = d.name
        );
    }
}

/// The bytes of the zero-filled copy a payload is read from when its format fills it (0: the
/// format reads every payload as sent): the largest of its structs and of its payloads.
fn fill_len(p: &Protocol, fi: usize) -> usize {
    let f = &p.frames[fi];
    let fills = f.truncate_zeros || (!f.extensions && base_sizes(p, fi));
    if !fills {
        return 0;
    }
    slots_of(p, fi)
        .iter()
        .filter_map(|s| s.si)
        .map(|si| p.structs[si].size)
        .max()
        .unwrap_or(0)
        .max(f.payload_max)
        .max(1)
}

/// Whether a payload of format `fi` has extension fields (the format then carries the fields
/// before them, when it carries no extensions).
fn base_sizes(p: &Protocol, fi: usize) -> bool {
    slots_of(p, fi)
        .iter()
        .any(|s| s.si.is_some_and(|si| p.structs[si].base_size.is_some()))
}

/// The direction from the header of format `fi`, its rules tested in order (on a link, each
/// command format names its own direction field).
fn directions(p: &Protocol, n: &Names, fi: usize, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[fi];
    if p.directions.is_empty() {
        return;
    }
    out.push_str("    ");
    for d in &p.directions {
        let cond = match &d.rule.in_frame(f) {
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

/// The dispatch key, one variable per field, then the command it names among those the
/// format carries.
fn dispatch_key(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
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
    if let [vi] = f.dispatch[..] {
        // One key field: a switch (a jump table where the ids are dense).
        let narrow = f.values[vi].prim.size() <= 4;
        let _ = writeln!(
            out,
            "        switch ({}key[0]) {{",
            if narrow { "(uint32_t)" } else { "" }
        );
        for (ci, c) in p.commands.iter().enumerate() {
            if !f.commands.contains(&ci) || c.id.len() != 1 {
                continue;
            }
            let id = truncate(f.values[vi].prim, c.id[0]);
            let label = if narrow {
                format!("{id:#x}u")
            } else {
                names::u64_lit(id)
            };
            let _ = writeln!(
                out,
                "        case {label}: out->command = {up}{}; break;",
                c.name
            );
        }
        let _ = writeln!(
            out,
            "        default: return {up}ERR_UNKNOWN_COMMAND;\n        }}\n    }}"
        );
        return;
    }
    out.push_str("        ");
    for (ci, c) in p.commands.iter().enumerate() {
        if !f.commands.contains(&ci) || c.id.len() != f.dispatch.len() {
            continue;
        }
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

/// The command of a CAN frame: the one whose CAN id is the frame's whole identifier word (bits
/// above the id's width, which no bus delivers, name no command).
fn can_command(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
    let Some(v) = f.values.iter().find(|v| v.name == "can_id") else {
        return;
    };
    let _ = write!(
        out,
        "    if (!{lo}field(bytes, len, {}, {}u, {}, 0u, {}u, &raw)) return {up}ERR_FRAME;\n    ",
        pos(v.at),
        v.word.prim.size(),
        big(v.word.endian),
        8 * v.word.prim.size()
    );
    for c in &p.commands {
        if let Some(id) = c.can_id {
            let _ = write!(
                out,
                "if (raw == {}) out->command = {up}{};\n    else ",
                names::u64_lit(id),
                c.name
            );
        }
    }
    let _ = writeln!(out, "return {up}ERR_UNKNOWN_COMMAND;");
}

/// The payload `bytes[start..end]` read into the packet's member of its slot: in a format
/// without extension fields exactly the bytes before them, zero-filled to the struct's size
/// (as a payload its sender cut short of trailing zeros is, where the format says so).
fn read_payload(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let f = &p.frames[x.fi];
    // A stuffed payload is read where `unstuff` left it.
    if f.stuffing.is_none() {
        let _ = writeln!(out, "    r.p = bytes + start;\n    r.len = end - start;");
    }
    let _ = writeln!(out, "    r.pos = 0;");
    let slots: Vec<Slot> = slots_of(p, x.fi)
        .into_iter()
        .filter(|s| s.si.is_some() && s.keyless.is_none())
        .collect();
    if fill_len(p, x.fi) > 0 {
        out.push_str("    {\n        size_t size = 0, base = SIZE_MAX;\n");
        for slot in &slots {
            let si = slot.si.unwrap_or_default();
            let s = &p.structs[si];
            let base = s.base_size.filter(|_| !f.extensions);
            let size = if f.truncate_zeros || base.is_some() {
                s.size
            } else {
                0
            };
            let base = base.map_or("SIZE_MAX".to_string(), |b| format!("{b}u"));
            let _ = writeln!(
                out,
                "        if ({}) {{\n            size = {size}u;\n            base = {base};\n        }}",
                slot.test(p, n, "out")
            );
        }
        let _ = write!(
            out,
            "        /* A format without extension fields carries the bytes before them. */\n        if (base != SIZE_MAX && r.len != base) return {up}ERR_PAYLOAD_LENGTH;\n        /* A payload short of its struct's size is zero-filled. */\n        if (r.len < size) {{\n            memcpy(filled, r.p, r.len);\n            memset(filled + r.len, 0, size - r.len);\n            r.p = filled;\n            r.len = size;\n        }}\n    }}\n"
        );
    }
    let read = |slot: &Slot| {
        format!(
            "e = (memset(&out->payload.{name}, 0, sizeof out->payload.{name}), {lo}read_{}(&r, &out->payload.{name}));",
            names::snake(&p.structs[slot.si.unwrap_or_default()].name),
            name = slot.name
        )
    };
    if slots.len() > 1 && slots.iter().all(|s| s.command.is_some()) {
        // One case per command, then its directions: a jump rather than a test per slot.
        out.push_str("    switch (out->command) {\n");
        let mut commands: Vec<usize> = slots.iter().filter_map(|s| s.command).collect();
        commands.dedup();
        for ci in commands {
            let _ = writeln!(out, "    case {up}{}:", p.commands[ci].name);
            let mut first = true;
            for slot in slots.iter().filter(|s| s.command == Some(ci)) {
                let test = p
                    .directions
                    .get(slot.direction)
                    .map(|d| format!("if (out->direction == {up}{}) ", d.name.to_uppercase()));
                let _ = writeln!(
                    out,
                    "        {}{}{}",
                    if first { "" } else { "else " },
                    test.unwrap_or_default(),
                    read(slot)
                );
                first = false;
            }
            out.push_str("        break;\n");
        }
        out.push_str("    default:\n        break;\n    }\n");
    } else {
        for slot in &slots {
            let _ = writeln!(out, "    {}{}", slot.guard(p, n, "out"), read(slot));
        }
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

fn encode(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let up = &n.up;
    let (xlo, xup) = (&x.lo, &x.up);
    let f = &p.frames[x.fi];
    let kind = carries(p, x.fi);
    if kind == Carries::Commands {
        let widest = f
            .dispatch
            .iter()
            .map(|&vi| f.values[vi].prim.size())
            .max()
            .unwrap_or(1);
        let _ = writeln!(
            out,
            "/* The dispatch key of every command, in command order (as the format's fields hold it). */\nstatic const {} {xlo}ids[{}][{}] = {{",
            names::unsigned_of(widest),
            p.commands.len().max(1),
            f.dispatch.len()
        );
        for c in &p.commands {
            let ids: Vec<String> = f
                .dispatch
                .iter()
                .zip(&c.id)
                .map(|(&vi, &v)| format!("{:#x}u", truncate(f.values[vi].prim, v)))
                .collect();
            let ids = if ids.is_empty() {
                vec!["0u".to_string()]
            } else {
                ids
            };
            let _ = writeln!(out, "    {{{}}},", ids.join(", "));
        }
        out.push_str("};\n\n");
    }
    if kind == Carries::Can {
        let ids: Vec<String> = p
            .commands
            .iter()
            .map(|c| format!("{:#x}u", c.can_id.unwrap_or(0)))
            .collect();
        let _ = writeln!(
            out,
            "/* The CAN id of every command, in command order (0: none). */\nstatic const uint32_t {xlo}can_ids[{}] = {{{}}};\n",
            ids.len().max(1),
            if ids.is_empty() {
                "0u".to_string()
            } else {
                ids.join(", ")
            }
        );
    }
    if f.truncate_zeros {
        let _ = write!(
            out,
            "/* The bytes of a payload its sender keeps: all but its trailing zeros, and at least the\n * first byte of a non-empty payload (the runtime's `zeros::trimmed_len`). */\nstatic size_t {xlo}trimmed(const uint8_t *p, size_t len)\n{{\n    size_t kept = len;\n    while (kept > 0 && p[kept - 1] == 0) kept--;\n    return kept == 0 && len > 0 ? 1 : kept;\n}}\n\n"
        );
    }
    if let Some((after, insert)) = &f.stuffing {
        stuff(after, *insert, n, out);
    }
    seal(p, n, x, out);
    for slot in slots_of(p, x.fi) {
        encoder(p, n, x, &slot, out);
    }
    if kind == Carries::Bytes {
        let _ = writeln!(
            out,
            "int {xlo}encode_bytes(const {xlo}header *header, const uint8_t *payload, size_t len, uint8_t *buf, size_t cap)\n{{\n    if (len > {xup}MAX_PAYLOAD_LEN) return {up}ERR_OUT_OF_RANGE;\n    if (cap < {xup}HEADER_LEN + {xup}TRAILER_LEN || len > cap - {xup}HEADER_LEN - {xup}TRAILER_LEN) return {up}ERR_SHORT_BUFFER;\n    if (len > 0) memcpy(buf + {xup}HEADER_LEN, payload, len);\n    return {xlo}seal({}len, header, 0);\n}}\n",
            seal_place(p, x, &format!("{xup}HEADER_LEN"))
        );
    }
    if f.ack.is_some() {
        ack_encoder(f, n, x, out);
    }
    let _ = writeln!(
        out,
        "int {xlo}encode(const {xlo}packet *packet, uint8_t *buf, size_t cap)\n{{"
    );
    if f.ack.is_some() {
        let _ = writeln!(
            out,
            "    if (packet->ack) return {xlo}encode_ack(&packet->header, packet->payload.ack_data.bytes, packet->payload.ack_data.len, buf, cap);"
        );
    }
    if kind == Carries::Bytes {
        let _ = writeln!(
            out,
            "    return {xlo}encode_bytes(&packet->header, packet->payload, packet->payload_len, buf, cap);"
        );
    }
    for slot in slots_of(p, x.fi) {
        let payload = match slot.si {
            Some(_) => format!("&packet->payload.{}, ", slot.name),
            None => String::new(),
        };
        let _ = writeln!(
            out,
            "    {}return {xlo}encode_{}(&packet->header, {payload}buf, cap);",
            slot.guard(p, n, "packet"),
            slot.name
        );
    }
    if matches!(kind, Carries::Commands | Carries::Can) {
        let _ = writeln!(out, "    return {up}ERR_OUT_OF_RANGE;");
    }
    out.push_str("}\n\n");
}

/// Whether a format's frames are sealed apart from where their encoder wrote the payload: a
/// wider length moves the payload, a flag trailer adds bytes, a direction's message starts
/// before the header's end. The seal then takes the buffer's size and the payload's start.
fn framed_apart(p: &Protocol, fi: usize) -> bool {
    let f = &p.frames[fi];
    f.length_extension.is_some()
        || f.flag_trailer.is_some()
        || (fi == 0 && p.directions.iter().any(|d| d.message.is_some()))
}

/// The arguments of `pfx_seal` before the payload's length: the buffer, and for a format
/// sealed apart its size and the payload's start.
fn seal_place(p: &Protocol, x: &Fx, start: &str) -> String {
    if framed_apart(p, x.fi) {
        format!("buf, cap, {start}, ")
    } else {
        "buf, ".to_string()
    }
}

/// `pfx_seal`: the frame around a payload already written after the header (moved behind a
/// wider length when the frame needs one), with the flag trailer when the header has it.
fn seal(p: &Protocol, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let f = &p.frames[x.fi];
    if framed_apart(p, x.fi) {
        let _ = write!(
            out,
            "/* The frame around a payload of `payload_len` bytes already written at `start` (after the\n * header), in a buffer of `cap` bytes; `command` SIZE_MAX for a frame without dispatch key. */\nstatic int {xlo}seal(uint8_t *buf, size_t cap, size_t start, size_t payload_len, const {xlo}header *h, size_t command)\n{{\n    size_t ext = 0, flagged = 0, body, total;\n    if (start > {xup}HEADER_LEN || payload_len > {xup}MAX_PAYLOAD_LEN + ({xup}HEADER_LEN - start)) return {up}ERR_OUT_OF_RANGE;\n    body = start + payload_len + {xup}TRAILER_LEN;\n"
        );
    } else {
        // The header and trailer around the payload, in the buffer the encoder checked.
        let _ = write!(
            out,
            "/* The frame around a payload of `payload_len` bytes already written after the header. */\nstatic int {xlo}seal(uint8_t *buf, size_t payload_len, const {xlo}header *h, size_t command)\n{{\n    const size_t start = {xup}HEADER_LEN, ext = 0;\n    size_t body, total;\n    if (payload_len > {xup}MAX_PAYLOAD_LEN) return {up}ERR_OUT_OF_RANGE;\n    body = start + payload_len + {xup}TRAILER_LEN;\n"
        );
    }
    let adjust = match &f.length {
        Length::Field { adjust, .. } => *adjust,
        Length::Fixed(_) => 0,
    };
    if let Some(e) = &f.length_extension {
        // The runtime's `extension_for`: the count of the short form reaches the marker.
        let _ = writeln!(
            out,
            "    if ((int64_t)body - ({adjust}) >= 0 && (uint64_t)((int64_t)body - ({adjust})) >= {}) ext = {}u;",
            names::u64_lit(e.marker),
            e.len
        );
    }
    if let Some(t) = &f.flag_trailer {
        let _ = writeln!(
            out,
            "    if (h->{}_present) flagged = {}u;",
            names::field(&t.name),
            t.len
        );
    }
    let sized = if framed_apart(p, x.fi) {
        format!(
            "    body += ext;\n    total = body + flagged;\n    if (total > cap) return {up}ERR_SHORT_BUFFER;\n    if (ext > 0) memmove(buf + start + ext, buf + start, payload_len);\n"
        )
    } else {
        "    total = body;\n".to_string()
    };
    let _ = write!(
        out,
        "{sized}    memset(buf, 0, start + ext);\n    memset(buf + start + ext + payload_len, 0, {xup}TRAILER_LEN);\n{sync}    (void)h;\n    (void)command;\n",
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
    let is_can = matches!(f.transport, Transport::Can { .. });
    for (vi, v) in f.values.iter().enumerate() {
        let value = match &v.role {
            // A CAN frame's id is the command's.
            _ if is_can && v.name == "can_id" => format!("(uint64_t){xlo}can_ids[command]"),
            Role::User { .. } => format!("(uint64_t)h->{}", names::field(&v.name)),
            Role::Length => match (&f.length, &f.length_extension) {
                (Length::Field { .. }, Some(e)) => {
                    // The runtime's `conditional_count`: the count in the wider field, the
                    // marker in this one, when it does not fit below the marker.
                    let wide = &f.values[e.value];
                    let _ = write!(
                        out,
                        "    {{\n        uint64_t count;\n        if ((int64_t)body - ({adjust}) < 0) return {up}ERR_OUT_OF_RANGE;\n        count = (uint64_t)((int64_t)body - ({adjust}));\n        if (count >= {marker}) {{\n            if (count - {len}u < {marker}) return {up}ERR_OUT_OF_RANGE;\n            if (!{lo}put_field(buf, body, {}, count - {len}u)) return {up}ERR_OUT_OF_RANGE;\n            count = {marker};\n        }}\n        /* {} */\n        if (!{lo}put_field(buf, body, {}, count)) return {up}ERR_OUT_OF_RANGE;\n    }}\n",
                        word(wide),
                        v.name,
                        word(v),
                        marker = names::u64_lit(e.marker),
                        len = e.len
                    );
                    continue;
                }
                (Length::Field { .. }, None) => {
                    let _ = writeln!(
                        out,
                        "    if ((int64_t)body - ({adjust}) < 0) return {up}ERR_OUT_OF_RANGE;"
                    );
                    format!("(uint64_t)((int64_t)body - ({adjust}))")
                }
                (Length::Fixed(_), _) => continue,
            },
            Role::Dispatch => {
                let k = f.dispatch.iter().position(|&d| d == vi).unwrap_or(0);
                let _ = writeln!(
                    out,
                    "    /* {} */\n    if (command != SIZE_MAX && !{lo}put_field(buf, body, {}, (uint64_t){xlo}ids[command][{k}])) return {up}ERR_OUT_OF_RANGE;",
                    v.name,
                    word(v)
                );
                continue;
            }
            Role::Const(c) => names::u64_lit(*c),
            Role::Flag => "(uint64_t)(flagged > 0 ? 1u : 0u)".to_string(),
            Role::WideLength => continue,
            // A command frame's acknowledgement flag: not the acknowledgement's value.
            Role::Ack(equals) => names::u64_lit(1 - (*equals).min(1)),
        };
        let _ = writeln!(
            out,
            "    /* {} */\n    if (!{lo}put_field(buf, body, {}, {value})) return {up}ERR_OUT_OF_RANGE;",
            v.name,
            word(v)
        );
    }
    if !f.sync_set.is_empty() {
        let _ = writeln!(
            out,
            "    /* The first header value is the sync: one of its set. */\n    if (!{xlo}sync_matches(buf, 1)) return {up}ERR_OUT_OF_RANGE;"
        );
    }
    for t in &f.trailers {
        let bytes: Vec<String> = t.bytes.iter().map(|b| format!("{b:#04x}")).collect();
        let _ = write!(
            out,
            "    {{\n        static const uint8_t trailer[{len}] = {{{}}};\n        size_t at = {lo}pos(body, {});\n        if (at == SIZE_MAX || body - at < {len}u) return {up}ERR_OUT_OF_RANGE;\n        memcpy(buf + at, trailer, {len}u);\n    }}\n",
            bytes.join(", "),
            pos(t.at),
            len = t.bytes.len()
        );
    }
    for c in &f.checks {
        let _ = writeln!(
            out,
            "    if (!{lo}store(buf, {})) return {up}ERR_OUT_OF_RANGE;",
            check_args(n, x, c, "body")
        );
    }
    if let Some(t) = &f.flag_trailer {
        let _ = writeln!(
            out,
            "    if (flagged > 0) memcpy(buf + body, h->{}, flagged);",
            names::field(&t.name)
        );
    }
    let _ = writeln!(out, "    return (int)total;\n}}\n");
}

/// The encoder of one slot: its payload written after the header (in a format without
/// extension fields, the bytes before them; cut short of its trailing zeros where the format
/// says so), then the frame sealed around it.
fn encoder(p: &Protocol, n: &Names, x: &Fx, slot: &Slot, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let f = &p.frames[x.fi];
    let base = slot
        .si
        .and_then(|si| p.structs[si].base_size.filter(|_| !f.extensions));
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
    let mut decl = String::new();
    // The message of a direction the decoder is given starts where the dispatch key would.
    let start = slot
        .keyless
        .map_or(format!("{xup}HEADER_LEN"), |start| format!("{start}u"));
    let mut place = format!(
        "    w.p = buf + {start};\n    w.cap = cap - {start} - {xup}TRAILER_LEN;\n    w.pos = 0;\n"
    );
    if let (Some(base), Some(si)) = (base, slot.si) {
        // The whole struct is written aside, then the bytes before its extension fields kept.
        let _ = writeln!(decl, "    uint8_t whole[{}];", p.structs[si].size.max(1));
        place = "    w.p = whole;\n    w.cap = sizeof whole;\n    w.pos = 0;\n".to_string();
        let _ = write!(
            write,
            "    if (w.pos > {base}u) w.pos = {base}u;\n    if (w.pos > cap - {xup}HEADER_LEN - {xup}TRAILER_LEN) return {up}ERR_SHORT_BUFFER;\n    memcpy(buf + {xup}HEADER_LEN, whole, w.pos);\n    w.p = buf + {xup}HEADER_LEN;\n"
        );
    }
    if f.truncate_zeros && slot.command.is_some() {
        let _ = writeln!(write, "    w.pos = {xlo}trimmed(w.p, w.pos);");
    }
    if f.stuffing.is_some() && slot.command.is_some() {
        write.push_str(&format!("    if ((e = {lo}stuff(&w)) != 0) return e;\n"));
    }
    let command = match (slot.command, slot.keyless) {
        (Some(ci), _) => format!("{up}{}", p.commands[ci].name),
        (None, Some(_)) => "SIZE_MAX".into(),
        (None, None) => "0".into(),
    };
    let _ = write!(
        out,
        "int {xlo}encode_{}(const {xlo}header *header, {arg}uint8_t *buf, size_t cap)\n{{\n    struct {lo}wr w;\n    int e = 0;\n{decl}    if (cap < {start} + {xup}TRAILER_LEN) return {up}ERR_SHORT_BUFFER;\n{place}{write}    (void)e;\n    return {xlo}seal({}w.pos, header, {command});\n}}\n\n",
        slot.name,
        seal_place(p, x, &start)
    );
}

/// A CAN format's functions on CAN frames: the virtual frame (the id as a big-endian `u32`,
/// the data length, the data) built from a received frame and decoded, and an encoded frame's
/// id and data.
fn can(n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let _ = write!(
        out,
        "int {xlo}decode_can(uint32_t id, bool extended, const uint8_t *data, size_t len, {xlo}packet *out)\n{{\n    uint8_t virt[13];\n    if (extended != ({xup}CAN_EXTENDED != 0) || len > 8u) return {up}ERR_FRAME;\n    {lo}set(virt, 4u, 1, id);\n    virt[4] = (uint8_t)len;\n    if (len > 0) memcpy(virt + 5, data, len);\n    return {xlo}decode(virt, 5u + len, out);\n}}\n\n\
int {xlo}encode_can(const {xlo}packet *packet, uint32_t *id, uint8_t data[8])\n{{\n    uint8_t virt[{xup}MAX_FRAME_LEN];\n    int len = {xlo}encode(packet, virt, sizeof virt);\n    if (len < 0) return len;\n    if (len < 5 || len > 13) return {up}ERR_OUT_OF_RANGE;\n    *id = (uint32_t){lo}get(virt, 4u, 1);\n    memcpy(data, virt + 5, (size_t)len - 5u);\n    return len - 5;\n}}\n\n"
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
        "    if (!{lo}field(bytes, len, {}, &raw)) return {up}ERR_FRAME;\n    if (raw == {}) {{\n        size_t end;\n        if (len < {up}ACK_HEADER_LEN) return {up}ERR_FRAME;\n        end = {end};\n        if (end < {up}ACK_HEADER_LEN) return {up}ERR_FRAME;\n        if (end - {up}ACK_HEADER_LEN > {up}ACK_MAX_LEN) return {up}ERR_PAYLOAD_LENGTH;\n        out->ack = true;\n        out->command = {up}COMMAND_COUNT;\n        memset(&out->payload.ack_data, 0, sizeof out->payload.ack_data);\n        out->payload.ack_data.len = end - {up}ACK_HEADER_LEN;\n        memcpy(out->payload.ack_data.bytes, bytes + {up}ACK_HEADER_LEN, out->payload.ack_data.len);\n        return 0;\n    }}\n",
        word(v),
        names::u64_lit(equals)
    );
}

/// The encoder of an acknowledgement: its data after the acknowledgement's header, the header
/// values, the flag at its value and no dispatch key; with no data and a bare header, the
/// header alone (no frame checks, no trailers), as the runtime's `seal` does.
fn ack_encoder(f: &Frame, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let (xlo, xup) = (&x.lo, &x.up);
    let plan = lower_layout(f);
    let bare = if f.bare_len.is_some() {
        "len == 0"
    } else {
        "0"
    };
    let _ = write!(
        out,
        "int {xlo}encode_ack(const {xlo}header *h, const uint8_t *data, size_t len, uint8_t *buf, size_t cap)\n{{\n    int bare = {bare};\n    size_t total;\n    if (len > {xup}ACK_MAX_LEN) return {up}ERR_OUT_OF_RANGE;\n    total = {xup}ACK_HEADER_LEN + len + (bare ? 0u : {xup}TRAILER_LEN);\n    if (!bare && total < {xup}MIN_FRAME_LEN) return {up}ERR_OUT_OF_RANGE;\n    if (cap < total) return {up}ERR_SHORT_BUFFER;\n    memset(buf, 0, {xup}ACK_HEADER_LEN);\n    memcpy(buf + {xup}ACK_HEADER_LEN, data, len);\n    if (!bare) memset(buf + {xup}ACK_HEADER_LEN + len, 0, {xup}TRAILER_LEN);\n"
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
            "    if (!{xlo}sync_matches(buf, 1)) return {up}ERR_OUT_OF_RANGE;"
        );
    }
    for &ci in &plan.header_checks {
        let _ = writeln!(
            out,
            "    if (!{lo}store(buf, {})) return {up}ERR_OUT_OF_RANGE;",
            check_args(n, x, &f.checks[ci], "total")
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
            check_args(n, x, &f.checks[ci], "total")
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
fn unstuff(after: &[u8], insert: u8, n: &Names, x: &Fx, out: &mut String) {
    let (up, xup) = (&n.up, &x.up);
    let _ = write!(
        out,
        "    {{\n        static const uint8_t pattern[{k}] = {{{}}};\n        static uint8_t plain[{xup}MAX_PAYLOAD_LEN > 0 ? {xup}MAX_PAYLOAD_LEN : 1];\n        const uint8_t *s = bytes + start;\n        size_t sn = end - start, i = 0, o = 0;\n        while (i < sn) {{\n            if (o >= {xup}MAX_PAYLOAD_LEN) return {up}ERR_PAYLOAD_LENGTH;\n            plain[o++] = s[i++];\n            if (o >= {k}u && memcmp(plain + o - {k}u, pattern, {k}u) == 0) {{\n                if (i < sn && s[i] == {insert:#04x}) i++;\n                else return {up}ERR_INVALID_STUFFING;\n            }}\n        }}\n        r.p = plain;\n        r.len = o;\n    }}\n",
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
