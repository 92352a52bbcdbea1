//! The probe of a candidate frame: the runtime engine's order of checks (constants, header
//! checks, the length within its bounds before its bytes are awaited, frame checks, trailer
//! markers), on the bytes received so far.

use crate::ir::{Frame, Pos};
use crate::layout::LayoutPlan;
use protocol_runtime::layout::LengthRule;

use super::super::names::{self, Fx, Names};
use super::super::template::fill;
use super::wire::{byte_list, check_args, pos, word};

/// `pfx_probe_synced` and `pfx_probe` of format `x`.
pub(super) fn probe(f: &Frame, plan: &LayoutPlan<'_>, n: &Names, x: &Fx, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let span = plan
        .header_len
        .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
    let shortest = span.max(plan.min_len).max(1);
    out.push_str(&probe_head(f, plan, n, x, span));
    for (vi, c) in &plan.constants {
        let (word, value) = (word(&f.values[*vi]), names::u64_lit(c.value));
        out.push_str(&fill!(
            "    if (!${lo}field(b, span, ${word}, &raw) || raw != ${value}) return ${up}REJECT_BAD_HEADER;\n",
            lo,
            word,
            value,
            up
        ));
    }
    for &ci in &plan.header_checks {
        let args = check_args(n, x, &f.checks[ci], "span");
        out.push_str(&fill!(
            "    if (!${lo}verify(b, ${args})) return ${up}REJECT_BAD_HEADER_CHECK;\n",
            lo,
            args,
            up
        ));
    }
    let frame_len = length(f, plan, n, out);
    out.push_str(&fill!(
        r"
    if (limit < ${shortest}u || total < ${shortest}u || total > limit) return ${up}REJECT_BAD_LENGTH;
    if (avail < total) {
        *n = total;
        return ${up}PROBE_NEED;
    }
",
        shortest,
        up
    ));
    for &ci in &plan.frame_checks {
        let args = check_args(n, x, &f.checks[ci], frame_len);
        out.push_str(&fill!(
            "    if (!${lo}verify(b, ${args})) return ${up}REJECT_BAD_CHECKSUM;\n",
            lo,
            args,
            up
        ));
    }
    markers(plan, n, frame_len, out);
    let xlo = &x.lo;
    out.push_str(&fill!(
        r"
    (void)raw;
    *n = total;
    return ${up}PROBE_FRAME;
}

/* The probe of a candidate: the sync bytes, then the rules above. */
static int ${xlo}probe(const uint8_t *b, size_t avail, size_t limit, size_t *n)
{
    if (!${xlo}sync_matches(b, avail)) return ${up}REJECT_BAD_HEADER;
    return ${xlo}probe_synced(b, avail, limit, n);
}

",
        up,
        xlo
    ));
}

/// The start of `pfx_probe_synced`: its declarations, and the bytes of the header awaited
/// (a frame whose header alone exceeds `limit` is too long).
fn probe_head(f: &Frame, plan: &LayoutPlan<'_>, n: &Names, x: &Fx, span: usize) -> String {
    let (up, xlo, xup) = (&n.up, &x.lo, &x.up);
    let body = match plan.length {
        LengthRule::Conditional { .. } => "    size_t body;\n",
        _ => "",
    };
    // A sync cut by the end of the bytes may be no candidate at all: decided first.
    let need_sync = if f.sync.is_empty() && f.sync_set.is_empty() {
        String::new()
    } else {
        fill!(
            r"
        if (avail < ${xup}SYNC_LEN) {
            *n = ${xup}SYNC_LEN;
            return ${up}PROBE_NEED;
        }
",
            xup,
            up
        )
    };
    fill!(
        r"
/* The engine's rules for a candidate whose first bytes match the sync bytes (as many
 * as there are), in `b[0..avail]`; frames longer than `limit` are too long. Returns
 * ${up}PROBE_FRAME with the frame's length in `*n`, ${up}PROBE_NEED with the bytes needed
 * in `*n`, or the reason of a rejection. */
static int ${xlo}probe_synced(const uint8_t *b, size_t avail, size_t limit, size_t *n)
{
    const size_t span = ${span}u;
    size_t total;
${body}    uint64_t raw = 0;
    if (span > limit) {
${need_sync}        return ${up}REJECT_BAD_LENGTH;
    }
    if (avail < span) {
        *n = span;
        return ${up}PROBE_NEED;
    }
",
        up,
        xlo,
        span,
        body,
        need_sync
    )
}

/// The frame's length (`total`) by the format's length rule; the C variable the checks
/// cover the frame to (`body`, without a flag trailer, for a conditional length).
fn length(f: &Frame, plan: &LayoutPlan<'_>, n: &Names, out: &mut String) -> &'static str {
    let (lo, up) = (&n.lo, &n.up);
    let frame_len = match (plan.length, plan.length_value) {
        (LengthRule::Field { adjust, .. } | LengthRule::FieldOrBare { adjust, .. }, Some(vi)) => {
            let word = word(&f.values[vi]);
            out.push_str(&fill!(
                "    if (!${lo}field(b, span, ${word}, &raw)) return ${up}REJECT_BAD_LENGTH;\n",
                lo,
                word,
                up
            ));
            out.push_str(&adjusted(adjust, up));
            out.push_str(&fill!(
                r"
    if (raw > (uint64_t)SIZE_MAX) return ${up}REJECT_BAD_LENGTH;
    total = (size_t)raw;
",
                up
            ));
            "total"
        }
        (LengthRule::Fixed(len), _) => {
            out.push_str(&fill!("    total = ${len}u;\n", len));
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
    frame_len
}

/// `raw` (a `uint64_t` holding a count) plus `adjust`, or a rejection for bad length when the
/// sum is negative or beyond `INT64_MAX` (the runtime's checked arithmetic).
fn adjusted(adjust: i64, up: &str) -> String {
    let mut out = fill!(
        "    if (raw > (uint64_t)INT64_MAX) return ${up}REJECT_BAD_LENGTH;\n",
        up
    );
    if adjust >= 0 {
        out.push_str(&fill!(
            r"
    if (raw > (uint64_t)INT64_MAX - ${adjust}u) return ${up}REJECT_BAD_LENGTH;
    raw += ${adjust}u;
",
            adjust,
            up
        ));
    } else {
        let neg = adjust.unsigned_abs();
        out.push_str(&fill!(
            r"
    if (raw < ${neg}u) return ${up}REJECT_BAD_LENGTH;
    raw -= ${neg}u;
",
            neg,
            up
        ));
    }
    out
}

/// The length of a frame whose parts depend on header values (the runtime's
/// `conditional::measure`): the count of the length field, or of the wider length its marker
/// announces (awaited when its bytes have not come; a marker form whose smallest frame or wider
/// length lies beyond `limit` is rejected first), the body (`body`: the frame without its flag
/// trailer) and the total with the flag trailer when its flag is set.
fn conditional_length(f: &Frame, adjust: i64, length_value: usize, n: &Names, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    let word_of = |vi: usize| word(&f.values[vi]);
    let length = word_of(length_value);
    out.push_str(&fill!(
        r"
    if (!${lo}field(b, span, ${length}, &raw)) return ${up}REJECT_BAD_LENGTH;
    {
        uint64_t extra = 0;
",
        lo,
        length,
        up
    ));
    if let Some(e) = &f.length_extension {
        let wide = &f.values[e.value];
        let needed = match wide.at {
            Pos::Start(at) => at + wide.word.prim.size(),
            Pos::End(_) => usize::MAX,
        };
        let smallest = i128::from(e.marker) + i128::from(adjust) + e.len as i128;
        let too_long = if smallest < 0 || smallest > usize::MAX as i128 || needed == usize::MAX {
            fill!("            return ${up}REJECT_BAD_LENGTH;\n", up)
        } else {
            fill!(
                "            if (${smallest}u > limit || ${needed}u > limit) return ${up}REJECT_BAD_LENGTH;\n",
                smallest,
                needed,
                up
            )
        };
        let (marker, wide, extra) = (names::u64_lit(e.marker), word_of(e.value), e.len);
        out.push_str(&fill!(
            r"
        if (raw == ${marker}) {
${too_long}            if (avail < ${needed}u) {
                *n = ${needed}u;
                return ${up}PROBE_NEED;
            }
            if (!${lo}field(b, ${needed}u, ${wide}, &raw) || raw < ${marker}) return ${up}REJECT_BAD_LENGTH;
            extra = ${extra}u;
        } else if (raw > ${marker}) {
            return ${up}REJECT_BAD_LENGTH;
        }
",
            marker,
            too_long,
            needed,
            up,
            lo,
            wide,
            extra
        ));
    }
    for line in adjusted(adjust, up).lines() {
        out.push_str(&format!("    {line}\n"));
    }
    out.push_str(&fill!(
        r"
        raw += extra;
        if (raw > (uint64_t)SIZE_MAX) return ${up}REJECT_BAD_LENGTH;
        body = (size_t)raw;
    }
    total = body;
",
        up
    ));
    if let Some(t) = &f.flag_trailer {
        let (flag, len) = (word_of(t.flag), t.len);
        out.push_str(&fill!(
            r"
    if (${lo}field(b, span, ${flag}, &raw) && raw != 0) {
        if (total > SIZE_MAX - ${len}u) return ${up}REJECT_BAD_LENGTH;
        total += ${len}u;
    }
",
            lo,
            flag,
            len,
            up
        ));
    }
}

/// The bare header in the probe (the runtime's `LengthRule::FieldOrBare`): a frame of exactly
/// the bare length is complete and verified once its header checks hold and its bytes have
/// come (fields after the length may lie in it, beyond the header span).
fn bare_probe(bare: usize, n: &Names, out: &mut String) {
    let up = &n.up;
    out.push_str(&fill!(
        r"
    if (total == ${bare}u && ${bare}u >= span && ${bare}u > 0 && total <= limit) {
        *n = total;
        return avail < total ? ${up}PROBE_NEED : ${up}PROBE_FRAME;
    }
",
        bare,
        up
    ));
}

/// The trailer markers: each must hold its bytes at its position in the frame of `frame_len`
/// bytes.
fn markers(plan: &LayoutPlan<'_>, n: &Names, frame_len: &str, out: &mut String) {
    let (lo, up) = (&n.lo, &n.up);
    for (i, m) in plan.markers.iter().enumerate() {
        let (bytes, at, len) = (byte_list(m.bytes), pos(m.at), m.bytes.len());
        out.push_str(&fill!(
            r"
    {
        static const uint8_t marker${i}[${len}] = {${bytes}};
        size_t at = ${lo}pos(${frame_len}, ${at});
        if (at == SIZE_MAX || ${frame_len} - at < ${len}u \
            || memcmp(b + at, marker${i}, ${len}u) != 0) return ${up}REJECT_BAD_TRAILER;
    }
",
            i,
            len,
            bytes,
            lo,
            frame_len,
            at,
            up
        ));
    }
}
