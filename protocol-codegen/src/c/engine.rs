//! The stream decoder in C, with the runtime engine's rules (`protocol_runtime::decoder`): the
//! search for the sync (its bytes, or a byte of its set and the bytes after it; or a prefix
//! of them at the end of the input), the probe of each
//! candidate, a rejection that costs one byte (the search resumes at the byte after the
//! rejected start), the early-truncation rule (a candidate still waiting for bytes is
//! rejected as truncated as soon as a complete valid frame starts inside it), and the
//! counters, where every byte fed is counted once.
//!
//! The caller's chunks are copied into a fixed buffer of the largest frame's size; a frame
//! event points into it. Frames longer than the buffer cannot exist: the buffer is the
//! format's largest frame, so the bound is the format's.

use super::names::Names;

/// The stream decoder's types and functions, for the header.
pub fn declarations(n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    format!(
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
    uint64_t offset;     /**< Stream offset of the first byte. */
    size_t len;
    const uint8_t *bytes;
    {lo}reject reason;
}} {lo}event;

/** A stream decoder: a fixed buffer of the largest frame, no heap. */
typedef struct {lo}decoder {{
    size_t start, end;   /**< The pending bytes are buf[start..end]. */
    uint64_t position;   /**< Bytes taken from all inputs. */
    {lo}stats stats;
    uint8_t buf[{up}DECODER_BUFFER_LEN];
}} {lo}decoder;

/** Makes a decoder empty, its counters zero. */
void {lo}decoder_init({lo}decoder *d);

/** The next event, taking bytes from `*input` (advanced, `*len` decreased): 1 with `*event`
 *  set, or 0 when the input is used up and the decoder waits for more. */
int {lo}decoder_next({lo}decoder *d, const uint8_t **input, size_t *len, {lo}event *event);

/** Declares the end of the input: the next event among the pending bytes (a pending
 *  candidate is rejected as truncated). Call until it returns 0. */
int {lo}decoder_flush({lo}decoder *d, {lo}event *event);

"
    )
}

/// The stream decoder's functions, for the source.
pub fn engine(p: &crate::ir::Protocol, n: &Names) -> String {
    let (lo, up) = (&n.lo, &n.up);
    let inside = inside_bound(p);
    format!(
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

void {lo}decoder_init({lo}decoder *d)
{{
    memset(d, 0, sizeof *d);
}}

/* Where the first candidate of `b[0..len]` starts: the sync bytes, or a prefix of them that
 * runs to the end; `len` when there is none. */
static size_t {lo}find_candidate(const uint8_t *b, size_t len)
{{
    size_t i;
    for (i = 0; i < len; i++) {{
        if ({lo}sync_matches(b + i, len - i)) return i;
    }}
    return len;
}}

/* Whether a complete valid frame starts after the first byte of the pending candidate
 * `b[0..pending]`: then the candidate is taken for a truncated frame. */
static int {lo}frame_inside(const uint8_t *b, size_t pending)
{{
    size_t k, n = 0;
    for (k = 1; {inside}; k++) {{
        if ({lo}probe(b + k, pending - k, {up}DECODER_BUFFER_LEN, &n) == {up}PROBE_FRAME) return 1;
    }}
    return 0;
}}

/* Copies as much of the input behind the pending bytes as fits, moving them to the front of
 * the buffer first when the input would not fit behind them. */
static void {lo}stage({lo}decoder *d, const uint8_t **input, size_t *len)
{{
    size_t room, n;
    if (*len == 0) return;
    if (d->start > 0 && d->end + *len > {up}DECODER_BUFFER_LEN) {{
        memmove(d->buf, d->buf + d->start, d->end - d->start);
        d->end -= d->start;
        d->start = 0;
    }}
    room = {up}DECODER_BUFFER_LEN - d->end;
    n = *len < room ? *len : room;
    memcpy(d->buf + d->end, *input, n);
    d->end += n;
    d->position += n;
    *input += n;
    *len -= n;
}}

static void {lo}count_reject({lo}stats *s, int reason)
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

/* One event's worth of work. */
static int {lo}step({lo}decoder *d, const uint8_t **input, size_t *len, int at_end, {lo}event *ev)
{{
    for (;;) {{
        size_t pending, skip, n = 0;
        uint64_t offset;
        int r;
        if (d->start >= d->end) {{
            d->start = 0;
            d->end = 0;
        }}
        {lo}stage(d, input, len);
        pending = d->end - d->start;
        if (pending == 0) return 0;
        offset = d->position - pending;
        skip = {lo}find_candidate(d->buf + d->start, pending);
        if (skip > 0) {{
            d->start += skip;
            d->stats.skipped_bytes += skip;
            ev->kind = {up}EVENT_SKIPPED;
            ev->offset = offset;
            ev->len = skip;
            ev->bytes = NULL;
            return 1;
        }}
        r = {lo}probe_synced(d->buf + d->start, pending, {up}DECODER_BUFFER_LEN, &n);
        if (r == {up}PROBE_FRAME) {{
            ev->kind = {up}EVENT_FRAME;
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
            if (!at_end && !{lo}frame_inside(d->buf + d->start, pending)) return 0;
            r = {up}REJECT_TRUNCATED;
        }}
        d->start += 1;
        {lo}count_reject(&d->stats, r);
        ev->kind = {up}EVENT_REJECTED;
        ev->offset = offset;
        ev->len = 1;
        ev->bytes = NULL;
        ev->reason = ({lo}reject)r;
        return 1;
    }}
}}

int {lo}decoder_next({lo}decoder *d, const uint8_t **input, size_t *len, {lo}event *event)
{{
    return {lo}step(d, input, len, 0, event);
}}

int {lo}decoder_flush({lo}decoder *d, {lo}event *event)
{{
    size_t none = 0;
    const uint8_t *input = NULL;
    return {lo}step(d, &input, &none, 1, event);
}}

"
    )
}

/// The condition on a start `k` inside a pending candidate that the truncation rule tries:
/// the runtime tries only starts with room for its shortest frame after them, which matters
/// only where a frame can be shorter than that (a bare header).
fn inside_bound(p: &crate::ir::Protocol) -> String {
    let f = &p.frames[0];
    if f.bare_len.is_none() {
        return "k < pending".into();
    }
    let plan = crate::layout::lower_layout(f);
    let span = plan
        .header_len
        .max(plan.sync.len() + usize::from(!f.sync_set.is_empty()));
    let shortest = span.max(plan.min_len).max(1);
    format!("k < pending && pending - k >= {shortest}u")
}
