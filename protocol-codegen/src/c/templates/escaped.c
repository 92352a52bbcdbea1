/* -- ${what} -- */

/* The candidate is cut by flags, its bytes unescaped as they come (the runtime's
 * `decoder/escaped.rs`): `owner` is the stream offset of its opening flag, `state` holds
 * these bits. */
static const unsigned ${dlo}escaped_byte = 1u;    /* The last byte was the escape byte. */
static const unsigned ${dlo}escaped_counted = 2u; /* The opening flag closed the frame before and is counted with it. */

void ${dlo}decoder_init(${dlo}decoder *d)
{
    memset(d, 0, sizeof *d);
}

/* Takes `n` bytes of the input. */
static void ${dlo}escaped_take(${dlo}decoder *d, const uint8_t **input, size_t *len, size_t n)
{
    *input += n;
    *len -= n;
    d->position += n;
}

/* The candidate's bytes on the wire not counted yet, up to the position less `keep`. */
static uint64_t ${dlo}escaped_uncounted(const ${dlo}decoder *d, uint64_t keep)
{
    uint64_t n = d->position - d->owner;
    uint64_t less = keep + ((d->state & ${dlo}escaped_counted) != 0u ? 1u : 0u);
    return n > less ? n - less : 0u;
}

/* Appends an unescaped byte to the candidate; 0 when the candidate would be longer than a
 * frame may be. */
static int ${dlo}escaped_push(${dlo}decoder *d, uint8_t byte)
{
    if (d->end - d->start >= ${dup}DECODER_BUFFER_LEN) return 0;
    if (d->end >= ${dup}DECODER_BUFFER_LEN) {
        memmove(d->buf, d->buf + d->start, d->end - d->start);
        d->end -= d->start;
        d->start = 0;
    }
    d->buf[d->end++] = byte;
    return 1;
}

/* Starts a candidate at a flag at stream offset `offset`. */
static void ${dlo}escaped_open(${dlo}decoder *d, uint64_t offset, unsigned state)
{
    d->start = 0;
    d->end = 0;
    d->owner = offset;
    d->state = state;
    (void)${dlo}escaped_push(d, ${flag});
}

/* An event without bytes: a skipped run or a rejected candidate. */
static int ${dlo}escaped_event(${lo}event *ev, ${lo}event_kind kind, uint64_t offset, size_t len, int reason)
{
    ev->kind = kind;
    ev->format = 0;
    ev->offset = offset;
    ev->len = len;
    ev->bytes = NULL;
    ev->reason = (${lo}reject)reason;
    return 1;
}

/* Rejects the candidate for `reason`: its bytes on the wire up to the position, but for the
 * last `keep` (a closing flag that opens the next candidate), are skipped. */
static int ${dlo}escaped_reject(${dlo}decoder *d, int reason, uint64_t keep, ${lo}event *ev)
{
    uint64_t skipped = ${dlo}escaped_uncounted(d, keep);
    ${dlo}escaped_event(ev, ${up}EVENT_REJECTED, d->owner, 1u, reason);
    d->start = 0;
    d->end = 0;
    d->state = 0;
    ${lo}count_reject(&d->stats, reason);
    if (skipped > 0u) d->stats.skipped_bytes += skipped - 1u;
    return 1;
}

/* A closed candidate is rejected; its closing flag, at `flag_at`, opens the next one. */
static int ${dlo}escaped_reject_closed(${dlo}decoder *d, int reason, uint64_t flag_at, ${lo}event *ev)
{
    ${dlo}escaped_reject(d, reason, 1u, ev);
    ${dlo}escaped_open(d, flag_at, 0u);
    return 1;
}

/* A lone flag (idle fill, or the flag after a frame that no frame follows): skipped, unless it
 * was counted with the frame it closed (then 0: nothing to report). */
static int ${dlo}escaped_drop_lone_flag(${dlo}decoder *d, ${lo}event *ev)
{
    d->start = 0;
    d->end = 0;
    if ((d->state & ${dlo}escaped_counted) != 0u) return 0;
    d->stats.skipped_bytes++;
    return ${dlo}escaped_event(ev, ${up}EVENT_SKIPPED, d->owner, 1u, 0);
}

/* A flag (just taken) closes the candidate: a frame when the format's rules accept its
 * unescaped bytes, else a rejection; the flag opens the next candidate either way. 0 when
 * there is nothing to report. */
static int ${dlo}escaped_close(${dlo}decoder *d, ${lo}event *ev)
{
    uint64_t flag_at = d->position - 1u;
    size_t len, n = 0;
    int r;
    if ((d->state & ${dlo}escaped_byte) != 0u) return ${dlo}escaped_reject_closed(d, ${up}REJECT_BAD_ESCAPE, flag_at, ev);
    if (d->end - d->start == 1u) {
        r = ${dlo}escaped_drop_lone_flag(d, ev);
        ${dlo}escaped_open(d, flag_at, 0u);
        return r;
    }
    if (!${dlo}escaped_push(d, ${flag})) return ${dlo}escaped_reject_closed(d, ${up}REJECT_BAD_LENGTH, flag_at, ev);
    len = d->end - d->start;
    r = ${xlo}probe(d->buf + d->start, len, ${dup}DECODER_BUFFER_LEN, &n);
    if (r == ${up}PROBE_FRAME && n == len) {
        ev->kind = ${up}EVENT_FRAME;
        ev->format = 0;
        ev->offset = d->owner;
        ev->len = len;
        ev->bytes = d->buf + d->start;
        d->stats.frames++;
        d->stats.frame_bytes += ${dlo}escaped_uncounted(d, 0u);
        /* The frame's closing flag opens the next candidate; it stays in place while the
         * caller holds the frame (the next bytes go behind it). */
        d->start = d->end - 1u;
        d->owner = flag_at;
        d->state = ${dlo}escaped_counted;
        return 1;
    }
    if (r == ${up}PROBE_FRAME || r == ${up}PROBE_NEED) r = ${up}REJECT_BAD_LENGTH;
    return ${dlo}escaped_reject_closed(d, r, flag_at, ev);
}

/* One event's worth of work: bytes before a flag are skipped, a flag opens a candidate, the
 * bytes after it are unescaped into the buffer, the next flag closes it. */
static int ${dlo}escaped_step(${dlo}decoder *d, const uint8_t **input, size_t *len, int at_end, ${lo}event *ev)
{
    for (;;) {
        uint8_t byte;
        if (d->start >= d->end) {
            size_t skip = 0;
            d->start = 0;
            d->end = 0;
            if (*len == 0) return 0;
            while (skip < *len && (*input)[skip] != ${flag}) skip++;
            if (skip > 0) {
                ${dlo}escaped_event(ev, ${up}EVENT_SKIPPED, d->position, skip, 0);
                ${dlo}escaped_take(d, input, len, skip);
                d->stats.skipped_bytes += skip;
                return 1;
            }
            ${dlo}escaped_take(d, input, len, 1u);
            ${dlo}escaped_open(d, d->position - 1u, 0u);
            continue;
        }
        if (*len == 0) {
            if (!at_end) return 0;
            if (d->end - d->start == 1u && (d->state & ${dlo}escaped_byte) == 0u) return ${dlo}escaped_drop_lone_flag(d, ev);
            return ${dlo}escaped_reject(d, ${up}REJECT_TRUNCATED, 0u, ev);
        }
        byte = (*input)[0];
        ${dlo}escaped_take(d, input, len, 1u);
        if (byte == ${flag}) {
            if (${dlo}escaped_close(d, ev)) return 1;
            continue;
        }
        if ((d->state & ${dlo}escaped_byte) != 0u) {
            int original = ${xlo}original(byte);
            d->state &= ~${dlo}escaped_byte;
            if (original < 0) return ${dlo}escaped_reject(d, ${up}REJECT_BAD_ESCAPE, 0u, ev);
            byte = (uint8_t)original;
        } else if (byte == ${escape}) {
            d->state |= ${dlo}escaped_byte;
            continue;
        }
        if (!${dlo}escaped_push(d, byte)) return ${dlo}escaped_reject(d, ${up}REJECT_BAD_LENGTH, 0u, ev);
    }
}

int ${dlo}decoder_next(${dlo}decoder *d, const uint8_t **input, size_t *len, ${lo}event *event)
{
    return ${dlo}escaped_step(d, input, len, 0, event);
}

int ${dlo}decoder_flush(${dlo}decoder *d, ${lo}event *event)
{
    size_t none = 0;
    const uint8_t *input = NULL;
    return ${dlo}escaped_step(d, &input, &none, 1, event);
}
