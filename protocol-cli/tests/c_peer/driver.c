/* The C side of the conformance test (`tests/c_peer.rs`): reads commands on stdin, one per
 * line, and prints one line per result, in the text the Rust side prints for the same input.
 *
 *   P HEX          decode the frame HEX; print `ok TEXT` or `err NAME`, then the frame the
 *                  packet encodes to (`enc HEX`, or `enc err`)
 *   S CHUNK HEX    feed HEX to a stream decoder in chunks of CHUNK bytes, then flush; print
 *                  every event and the counters
 *
 * `spec.h` names the spec: it includes the generated header and defines P(x) and U(x), the
 * spec's lower- and upper-case prefixes. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spec.h"

static char line[1 << 23];
static uint8_t bytes[1 << 22];
static char text[1 << 16];

static const char *err_name(int e)
{
    switch (e) {
    case U(ERR_SHORT_BUFFER): return "short_buffer";
    case U(ERR_OUT_OF_RANGE): return "out_of_range";
    case U(ERR_PAYLOAD_LENGTH): return "payload_length";
    case U(ERR_UNKNOWN_COMMAND): return "unknown_command";
    case U(ERR_UNKNOWN_DIRECTION): return "unknown_direction";
    case U(ERR_INVALID_ENUM): return "invalid_enum";
    case U(ERR_FRAME): return "frame";
    case U(ERR_SIZE_MISMATCH): return "size_mismatch";
    case U(ERR_UNTERMINATED): return "unterminated";
    case U(ERR_PAYLOAD_CHECK): return "payload_check";
    case U(ERR_OUTSIDE_CLAMP): return "outside_clamp";
    case U(ERR_INVALID_STUFFING): return "invalid_stuffing";
    default: return "?";
    }
}

static int nibble(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

static size_t unhex(const char *s, uint8_t *out, size_t cap)
{
    size_t n = 0;
    while (nibble(s[0]) >= 0 && nibble(s[1]) >= 0 && n < cap) {
        out[n++] = (uint8_t)(nibble(s[0]) * 16 + nibble(s[1]));
        s += 2;
    }
    return n;
}

static void put_hex(const uint8_t *b, size_t n)
{
    size_t i;
    for (i = 0; i < n; i++) printf("%02x", b[i]);
}

/* `ok TEXT` or `err NAME`; with `encode`, the frame the packet encodes to. */
static void describe(const uint8_t *b, size_t n, int encode)
{
    P(packet) pk;
    uint8_t out[U(MAX_FRAME_LEN)];
    int e = P(decode)(b, n, &pk);
    int len;
    if (e != 0) {
        printf("err %s\n", err_name(e));
        return;
    }
    P(format)(&pk, text, sizeof text);
    printf("ok %s\n", text);
    if (!encode) return;
    len = P(encode)(&pk, out, sizeof out);
    if (len < 0) {
        printf("enc err\n");
        return;
    }
    printf("enc ");
    put_hex(out, (size_t)len);
    printf("\n");
    /* A buffer one byte short is refused, whatever the frame. */
    e = P(encode)(&pk, out, (size_t)len - 1);
    if (e != U(ERR_SHORT_BUFFER)) printf("a buffer one byte short gave %d\n", e);
}

static void event(const P(event) *ev)
{
    switch (ev->kind) {
    case U(EVENT_FRAME):
        printf("frame %llu ", (unsigned long long)ev->offset);
        put_hex(ev->bytes, ev->len);
        printf(" ");
        describe(ev->bytes, ev->len, 0);
        break;
    case U(EVENT_REJECTED):
        printf("rejected %llu %s\n", (unsigned long long)ev->offset, P(reject_name)(ev->reason));
        break;
    case U(EVENT_SKIPPED):
        printf("skipped %llu %llu\n", (unsigned long long)ev->offset, (unsigned long long)ev->len);
        break;
    }
}

static void stream(size_t chunk, const uint8_t *b, size_t n)
{
    static P(decoder) d;
    P(event) ev;
    size_t at = 0;
    const P(stats) *s = &d.stats;
    P(decoder_init)(&d);
    while (at < n) {
        size_t len = n - at < chunk ? n - at : chunk;
        const uint8_t *in = b + at;
        at += len;
        while (P(decoder_next)(&d, &in, &len, &ev)) event(&ev);
        if (len != 0) printf("input left over: %llu\n", (unsigned long long)len);
    }
    while (P(decoder_flush)(&d, &ev)) event(&ev);
    printf("stats %llu %llu %llu %llu %llu %llu %llu %llu %llu\n", (unsigned long long)s->frames,
           (unsigned long long)s->frame_bytes, (unsigned long long)s->skipped_bytes,
           (unsigned long long)s->bad_header, (unsigned long long)s->bad_header_check,
           (unsigned long long)s->bad_length, (unsigned long long)s->bad_checksum,
           (unsigned long long)s->bad_trailer, (unsigned long long)s->truncated);
}

int main(void)
{
    while (fgets(line, sizeof line, stdin)) {
        if (line[0] == 'P' && line[1] == ' ') {
            describe(bytes, unhex(line + 2, bytes, sizeof bytes), 1);
        } else if (line[0] == 'S' && line[1] == ' ') {
            char *rest;
            size_t chunk = (size_t)strtoul(line + 2, &rest, 10);
            stream(chunk, bytes, unhex(rest + 1, bytes, sizeof bytes));
        } else {
            printf("unknown command\n");
        }
        printf("end\n");
    }
    return 0;
}
