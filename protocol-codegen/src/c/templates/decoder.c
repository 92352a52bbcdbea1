/* -- ${what} -- */

/* The probe of a candidate whose first bytes match a format's sync: the first format whose
 * sync they match says which (`*format`). */
static int ${dlo}probe_link_synced(const uint8_t *b, size_t avail, size_t limit, size_t *n, int *format)
{
${by_sync}    *format = ${first_fi};
    return ${first_lo}probe_synced(b, avail, limit < ${first_up}MAX_FRAME_LEN ? limit : ${first_up}MAX_FRAME_LEN, n);
}

/* The probe of a candidate: a format's sync bytes, then its rules. */
static int ${dlo}probe_link(const uint8_t *b, size_t avail, size_t limit, size_t *n)
{
    int format = 0;
    if (!(${sync_at_b})) return ${up}REJECT_BAD_HEADER;
    return ${dlo}probe_link_synced(b, avail, limit, n, &format);
}

void ${dlo}decoder_init(${dlo}decoder *d)
{
    memset(d, 0, sizeof *d);
}

/* Where the first candidate of `b[0..len]` starts: a format's sync bytes, or a prefix of them
 * that runs to the end; `len` when there is none. */
static size_t ${dlo}find_candidate(const uint8_t *b, size_t len)
{
    size_t i;
    for (i = 0; i < len; i++) {
        if (${lead_at_i}(${sync_at_i})) return i;
    }
    return len;
}

/* Whether a complete valid frame starts after the first byte of the pending candidate
 * `b[0..pending]`: then the candidate is taken for a truncated frame. */
static int ${dlo}frame_inside(const uint8_t *b, size_t pending)
{
    size_t k, n = 0;
    for (k = 1; ${inside}; k++) {
        if (${lead_at_k}${dlo}probe_link(b + k, pending - k, ${dup}DECODER_BUFFER_LEN, &n) \
            == ${up}PROBE_FRAME) return 1;
    }
    return 0;
}

/* Copies as much of the input behind the pending bytes as fits, moving them to the front of
 * the buffer first when the input would not fit behind them. */
static void ${dlo}stage(${dlo}decoder *d, const uint8_t **input, size_t *len)
{
    size_t room, n;
    if (*len == 0) return;
    if (d->start > 0 && d->end + *len > ${dup}DECODER_BUFFER_LEN) {
        memmove(d->buf, d->buf + d->start, d->end - d->start);
        d->end -= d->start;
        d->start = 0;
    }
    room = ${dup}DECODER_BUFFER_LEN - d->end;
    n = *len < room ? *len : room;
    memcpy(d->buf + d->end, *input, n);
    d->end += n;
    d->position += n;
    *input += n;
    *len -= n;
}

/* One event's worth of work. */
static int ${dlo}step(${dlo}decoder *d, const uint8_t **input, size_t *len, int at_end, ${lo}event *ev)
{
    for (;;) {
        size_t pending, skip, n = 0;
        uint64_t offset;
        int r, format = 0;
        if (d->start >= d->end) {
            d->start = 0;
            d->end = 0;
        }
        ${dlo}stage(d, input, len);
        pending = d->end - d->start;
        if (pending == 0) return 0;
        offset = d->position - pending;
        skip = ${dlo}find_candidate(d->buf + d->start, pending);
        if (skip > 0) {
            d->start += skip;
            d->stats.skipped_bytes += skip;
            ev->kind = ${up}EVENT_SKIPPED;
            ev->format = 0;
            ev->offset = offset;
            ev->len = skip;
            ev->bytes = NULL;
            return 1;
        }
        r = ${dlo}probe_link_synced(d->buf + d->start, pending, ${dup}DECODER_BUFFER_LEN, &n, &format);
        if (r == ${up}PROBE_FRAME) {
            ev->kind = ${up}EVENT_FRAME;
            ev->format = format;
            ev->offset = offset;
            ev->len = n;
            ev->bytes = d->buf + d->start;
            d->start += n;
            d->stats.frames++;
            d->stats.frame_bytes += n;
            return 1;
        }
        if (r == ${up}PROBE_NEED) {
            if (*len > 0) continue;
            if (!at_end && !${dlo}frame_inside(d->buf + d->start, pending)) return 0;
            r = ${up}REJECT_TRUNCATED;
        }
        d->start += 1;
        ${lo}count_reject(&d->stats, r);
        ev->kind = ${up}EVENT_REJECTED;
        ev->format = 0;
        ev->offset = offset;
        ev->len = 1;
        ev->bytes = NULL;
        ev->reason = (${lo}reject)r;
        return 1;
    }
}

int ${dlo}decoder_next(${dlo}decoder *d, const uint8_t **input, size_t *len, ${lo}event *event)
{
    return ${dlo}step(d, input, len, 0, event);
}

int ${dlo}decoder_flush(${dlo}decoder *d, ${lo}event *event)
{
    size_t none = 0;
    const uint8_t *input = NULL;
    return ${dlo}step(d, &input, &none, 1, event);
}
