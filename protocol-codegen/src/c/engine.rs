//! The stream decoder in C, with the runtime engine's rules (`protocol_runtime::decoder`): the
//! search for the sync (its bytes, or a byte of its set and the bytes after it; or a prefix
//! of them at the end of the input), the probe of each
//! candidate, a rejection that costs one byte (the search resumes at the byte after the
//! rejected start), the early-truncation rule (a candidate still waiting for bytes is
//! rejected as truncated as soon as a complete valid frame starts inside it), and the
//! counters, where every byte fed is counted once.
//!
//! There is a decoder per serial frame format and, where several formats carry the commands,
//! the link's decoder of all of them (the runtime's `LayoutRef::others`): a candidate goes to
//! the first of its formats whose sync it matches, bounded by that format's largest frame.
//!
//! The caller's chunks are copied into a fixed buffer of the largest frame's size; a frame
//! event points into it. Frames longer than the buffer cannot exist: the buffer is the largest
//! frame of the decoder's formats, so the bound is theirs.

use std::fmt::Write as _;

use crate::ir::{Protocol, Transport};

use super::names::{Fx, Names};

/// A stream decoder the C code has: one per serial frame format, and the link's decoder of
/// every command format when it has several.
pub struct Decoder {
    /// Lower-case prefix of its items (`mavlink_`, `mavlink_v1_`, `mavlink_any_`).
    pub lo: String,
    /// Upper-case prefix of its items.
    pub up: String,
    /// The frame formats it finds (indices into [`Protocol::frames`]), in the order a
    /// candidate is given to them (the runtime's `LayoutRef::others` after the first).
    pub formats: Vec<usize>,
    /// What it is, for its comment.
    pub what: String,
}

/// The stream decoders of a spec: one per serial frame format, then the link's (`any`).
pub fn decoders(p: &Protocol, n: &Names) -> Vec<Decoder> {
    let mut out: Vec<Decoder> = p
        .frames
        .iter()
        .enumerate()
        .filter(|(_, f)| matches!(f.transport, Transport::Serial))
        .map(|(fi, f)| {
            let x = Fx::new(p, fi);
            Decoder {
                lo: x.lo,
                up: x.up,
                formats: vec![fi],
                what: format!("A stream decoder of `{}` frames", f.name),
            }
        })
        .collect();
    if !p.link.is_empty() {
        out.push(Decoder {
            lo: format!("{}any_", n.lo),
            up: format!("{}ANY_", n.up),
            formats: p.link.clone(),
            what: "The link's stream decoder, of every command format".into(),
        });
    }
    out
}

/// The stream decoder's types and functions, for the header.
pub fn declarations(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = format!(
        "/* ---- Stream decoder ---- */

/** Why a candidate frame was rejected. */
typedef enum {lo}reject {{
    {up}REJECT_BAD_HEADER = 1,   /**< The sync bytes or a constant of the header do not match. */
    {up}REJECT_BAD_HEADER_CHECK, /**< A header check does not match. */
    {up}REJECT_BAD_LENGTH,       /**< The length is outside the format's bounds. */
    {up}REJECT_BAD_CHECKSUM,     /**< A frame check does not match. */
    {up}REJECT_BAD_TRAILER,      /**< A trailer does not match. */
    {up}REJECT_TRUNCATED         /**< The frame's bytes never came. */
}} {lo}reject;

/** The name of a rejection reason. */
const char *{lo}reject_name({lo}reject reason);

/** What a decoder counted: every byte fed is in `frame_bytes` or `skipped_bytes` once it
 *  is no longer pending (a rejected candidate's first byte is skipped). */
typedef struct {lo}stats {{
    uint64_t frames, frame_bytes, skipped_bytes;
    uint64_t bad_header, bad_header_check, bad_length, bad_checksum, bad_trailer, truncated;
}} {lo}stats;

typedef enum {lo}event_kind {{
    {up}EVENT_FRAME = 1, /**< A valid frame: `bytes`, `len` (valid until the next call). */
    {up}EVENT_REJECTED,  /**< A candidate at `offset` was rejected for `reason`. */
    {up}EVENT_SKIPPED    /**< `len` bytes at `offset` where no candidate starts. */
}} {lo}event_kind;

typedef struct {lo}event {{
    {lo}event_kind kind;
    int format;          /**< A frame's format (its index in the spec's frame formats). */
    uint64_t offset;     /**< Stream offset of the first byte. */
    size_t len;
    const uint8_t *bytes;
    {lo}reject reason;
}} {lo}event;

"
    );
    for d in decoders(p, n) {
        let (lo, dlo, dup) = (&n.lo, &d.lo, &d.up);
        let _ = write!(
            out,
            "/** {what}: a fixed buffer of the largest frame, no heap. */
typedef struct {dlo}decoder {{
    size_t start, end;   /**< The pending bytes are buf[start..end]. */
    uint64_t position;   /**< Bytes taken from all inputs. */
    {lo}stats stats;
    uint8_t buf[{dup}DECODER_BUFFER_LEN];
}} {dlo}decoder;

/** Makes a decoder empty, its counters zero. */
void {dlo}decoder_init({dlo}decoder *d);

/** The next event, taking bytes from `*input` (advanced, `*len` decreased): 1 with `*event`
 *  set, or 0 when the input is used up and the decoder waits for more. */
int {dlo}decoder_next({dlo}decoder *d, const uint8_t **input, size_t *len, {lo}event *event);

/** Declares the end of the input: the next event among the pending bytes (a pending
 *  candidate is rejected as truncated). Call until it returns 0. */
int {dlo}decoder_flush({dlo}decoder *d, {lo}event *event);

",
            what = d.what
        );
    }
    out
}
/// The stream decoders' functions, for the source: the shared ones, then each decoder's.
pub fn engine(p: &Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let mut out = format!(
        "/* ---- Stream decoder ---- */

const char *{lo}reject_name({lo}reject reason)
{{
    switch (reason) {{
    case {up}REJECT_BAD_HEADER: return \"bad header\";
    case {up}REJECT_BAD_HEADER_CHECK: return \"bad header check\";
    case {up}REJECT_BAD_LENGTH: return \"bad length\";
    case {up}REJECT_BAD_CHECKSUM: return \"bad checksum\";
    case {up}REJECT_BAD_TRAILER: return \"bad trailer\";
    case {up}REJECT_TRUNCATED: return \"truncated frame\";
    default: return NULL;
    }}
}}

{up}UNUSED static void {lo}count_reject({lo}stats *s, int reason)
{{
    s->skipped_bytes++;
    switch (reason) {{
    case {up}REJECT_BAD_HEADER: s->bad_header++; break;
    case {up}REJECT_BAD_HEADER_CHECK: s->bad_header_check++; break;
    case {up}REJECT_BAD_LENGTH: s->bad_length++; break;
    case {up}REJECT_BAD_CHECKSUM: s->bad_checksum++; break;
    case {up}REJECT_BAD_TRAILER: s->bad_trailer++; break;
    default: s->truncated++; break;
    }}
}}

"
    );
    for d in decoders(p, n) {
        decoder(p, n, &d, &mut out);
    }
    out
}

/// The functions of one stream decoder. A candidate goes to the first of its formats whose
/// sync it matches (the first format when none does), with the format's largest frame as the
/// bound (the runtime's `select` and `probe_link`).
fn decoder(p: &Protocol, n: &Names, d: &Decoder, out: &mut String) {
    let (lo, up, dlo, dup) = (&n.lo, &n.up, &d.lo, &d.up);
    let formats: Vec<Fx> = d.formats.iter().map(|&fi| Fx::new(p, fi)).collect();
    let inside = inside_bound(p, d);
    let any_sync: Vec<String> = formats
        .iter()
        .map(|x| format!("{}sync_matches(b + i, len - i)", x.lo))
        .collect();
    // The first byte of every format's sync, where each has one: a start whose byte is none
    // of them is no candidate, decided without a call per byte.
    let mut leads: Vec<u8> = d
        .formats
        .iter()
        .filter_map(|&fi| {
            let f = &p.frames[fi];
            f.sync_set
                .is_empty()
                .then(|| f.sync.first().copied())
                .flatten()
        })
        .collect();
    leads.sort_unstable();
    leads.dedup();
    let all_led = d.formats.iter().all(|&fi| {
        let f = &p.frames[fi];
        f.sync_set.is_empty() && !f.sync.is_empty()
    });
    let lead = |at: &str| -> String {
        if !all_led {
            return String::new();
        }
        let tests: Vec<String> = leads
            .iter()
            .map(|b| format!("b[{at}] == {b:#04x}"))
            .collect();
        format!("({}) && ", tests.join(" || "))
    };
    let (lead_i, lead_k) = (lead("i"), lead("k"));
    let mut select = String::new();
    for x in &formats {
        let _ = write!(
            select,
            "    if ({xlo}sync_matches(b, avail)) {{\n        *format = {fi};\n        return {xlo}probe_synced(b, avail, limit < {xup}MAX_FRAME_LEN ? limit : {xup}MAX_FRAME_LEN, n);\n    }}\n",
            xlo = x.lo,
            xup = x.up,
            fi = x.fi
        );
    }
    let first = &formats[0];
    let _ = write!(
        out,
        "/* -- {what} -- */

/* The probe of a candidate whose first bytes match a format's sync: the first format whose
 * sync they match says which (`*format`). */
static int {dlo}probe_link_synced(const uint8_t *b, size_t avail, size_t limit, size_t *n, int *format)
{{
{select}    *format = {first_fi};
    return {first_lo}probe_synced(b, avail, limit < {first_up}MAX_FRAME_LEN ? limit : {first_up}MAX_FRAME_LEN, n);
}}

/* The probe of a candidate: a format's sync bytes, then its rules. */
static int {dlo}probe_link(const uint8_t *b, size_t avail, size_t limit, size_t *n)
{{
    int format = 0;
    if (!({sync_any_b})) return {up}REJECT_BAD_HEADER;
    return {dlo}probe_link_synced(b, avail, limit, n, &format);
}}

void {dlo}decoder_init({dlo}decoder *d)
{{
    memset(d, 0, sizeof *d);
}}

/* Where the first candidate of `b[0..len]` starts: a format's sync bytes, or a prefix of them
 * that runs to the end; `len` when there is none. */
static size_t {dlo}find_candidate(const uint8_t *b, size_t len)
{{
    size_t i;
    for (i = 0; i < len; i++) {{
        if ({lead_i}({sync_any})) return i;
    }}
    return len;
}}

/* Whether a complete valid frame starts after the first byte of the pending candidate
 * `b[0..pending]`: then the candidate is taken for a truncated frame. */
static int {dlo}frame_inside(const uint8_t *b, size_t pending)
{{
    size_t k, n = 0;
    for (k = 1; {inside}; k++) {{
        if ({lead_k}{dlo}probe_link(b + k, pending - k, {dup}DECODER_BUFFER_LEN, &n) == {up}PROBE_FRAME) return 1;
    }}
    return 0;
}}

/* Copies as much of the input behind the pending bytes as fits, moving them to the front of
 * the buffer first when the input would not fit behind them. */
static void {dlo}stage({dlo}decoder *d, const uint8_t **input, size_t *len)
{{
    size_t room, n;
    if (*len == 0) return;
    if (d->start > 0 && d->end + *len > {dup}DECODER_BUFFER_LEN) {{
        memmove(d->buf, d->buf + d->start, d->end - d->start);
        d->end -= d->start;
        d->start = 0;
    }}
    room = {dup}DECODER_BUFFER_LEN - d->end;
    n = *len < room ? *len : room;
    memcpy(d->buf + d->end, *input, n);
    d->end += n;
    d->position += n;
    *input += n;
    *len -= n;
}}

/* One event's worth of work. */
static int {dlo}step({dlo}decoder *d, const uint8_t **input, size_t *len, int at_end, {lo}event *ev)
{{
    for (;;) {{
        size_t pending, skip, n = 0;
        uint64_t offset;
        int r, format = 0;
        if (d->start >= d->end) {{
            d->start = 0;
            d->end = 0;
        }}
        {dlo}stage(d, input, len);
        pending = d->end - d->start;
        if (pending == 0) return 0;
        offset = d->position - pending;
        skip = {dlo}find_candidate(d->buf + d->start, pending);
        if (skip > 0) {{
            d->start += skip;
            d->stats.skipped_bytes += skip;
            ev->kind = {up}EVENT_SKIPPED;
            ev->format = 0;
            ev->offset = offset;
            ev->len = skip;
            ev->bytes = NULL;
            return 1;
        }}
        r = {dlo}probe_link_synced(d->buf + d->start, pending, {dup}DECODER_BUFFER_LEN, &n, &format);
        if (r == {up}PROBE_FRAME) {{
            ev->kind = {up}EVENT_FRAME;
            ev->format = format;
            ev->offset = offset;
            ev->len = n;
            ev->bytes = d->buf + d->start;
            d->start += n;
            d->stats.frames++;
            d->stats.frame_bytes += n;
            return 1;
        }}
        if (r == {up}PROBE_NEED) {{
            if (*len > 0) continue;
            if (!at_end && !{dlo}frame_inside(d->buf + d->start, pending)) return 0;
            r = {up}REJECT_TRUNCATED;
        }}
        d->start += 1;
        {lo}count_reject(&d->stats, r);
        ev->kind = {up}EVENT_REJECTED;
        ev->format = 0;
        ev->offset = offset;
        ev->len = 1;
        ev->bytes = NULL;
        ev->reason = ({lo}reject)r;
        return 1;
    }}
}}

int {dlo}decoder_next({dlo}decoder *d, const uint8_t **input, size_t *len, {lo}event *event)
{{
    return {dlo}step(d, input, len, 0, event);
}}

int {dlo}decoder_flush({dlo}decoder *d, {lo}event *event)
{{
    size_t none = 0;
    const uint8_t *input = NULL;
    return {dlo}step(d, &input, &none, 1, event);
}}

",
        what = d.what,
        first_fi = first.fi,
        first_lo = first.lo,
        first_up = first.up,
        sync_any = any_sync.join(" || "),
        sync_any_b = formats
            .iter()
            .map(|x| format!("{}sync_matches(b, avail)", x.lo))
            .collect::<Vec<_>>()
            .join(" || ")
    );
}

/// The condition on a start `k` inside a pending candidate that the truncation rule tries:
/// the runtime tries only starts with room for its shortest frame after them, which matters
/// only where a frame can be shorter than that (a bare header).
fn inside_bound(p: &Protocol, d: &Decoder) -> String {
    let frames = || d.formats.iter().map(|&fi| &p.frames[fi]);
    if frames().all(|f| f.bare_len.is_none()) {
        return "k < pending".into();
    }
    let shortest = frames()
        .map(|f| {
            let plan = crate::layout::lower_layout(f);
            let span = plan
                .header_len
                .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
            span.max(plan.min_len).max(1)
        })
        .min()
        .unwrap_or(1);
    format!("k < pending && pending - k >= {shortest}u")
}
