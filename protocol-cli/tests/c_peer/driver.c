/* The C side of the conformance test (`tests/it/c_peer.rs`): reads commands on stdin, one per
 * line, and prints one line per result, in the text the Rust side prints for the same input.
 *
 *   P FI HEX           decode HEX as a frame of format FI; print `ok TEXT` or `err NAME`,
 *                      then each packet it carries (`carried ok TEXT` or `carried err
 *                      NAME`) and the frame the packet encodes to (`enc HEX`, or `enc err`)
 *   D FI DIR HEX       as `P`, the frame sent in direction DIR (a spec whose decoder is
 *                      given the direction)
 *   C FI EXT ID HEX    decode the CAN frame of id ID (extended when EXT is 1) and data HEX
 *                      with CAN format FI; print as `P`, the encoded frame as `enc ID HEX`
 *   S DI CHUNK HEX     feed HEX to stream decoder DI in chunks of CHUNK bytes, then flush;
 *                      print every event and the counters
 *
 * `spec.h` names the spec: it includes the generated header and defines P(x) and U(x), the
 * spec's lower- and upper-case prefixes, and the lists FORMATS(X), CAN_FORMATS(X), GIVEN(X)
 * and DECODERS(X) of the spec's frame formats, CAN formats, formats whose decoder is given the
 * direction and stream decoders, each item
 * X(index, lower-case prefix, upper-case prefix); per format FI, ESCAPED_FI (1 when it escapes
 * its bytes between flags) and UNESCAPE_FI(wire, len, out, cap) (its `unescape`, or -1); and
 * NO_DECODERS for a spec without stream decoder (a CAN-only link). `carried.h` defines, per
 * format FI, `carried_FI()`, which prints the packets a decoded packet carries. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "spec.h"

static char line[1 << 23];
static uint8_t bytes[1 << 22];
static char text[1 << 18];

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

/* `decode_frame` (the framing trusted) of bytes `decode` accepted, against `decode`'s packet
 * in `text`: a line the Rust side never prints when they differ (`decode` is the probe, then
 * `decode_frame`, so this holds while that stays so). `decode_frame` also runs on the bytes
 * `decode` refuses (random frames, under the sanitizers): it must read them within their
 * length, whatever it makes of them. */
#define same_as_decode(trusted, packet, format_fn)                                              \
    do {                                                                                        \
        static char again[sizeof text];                                                         \
        if ((trusted) != 0) {                                                                   \
            printf("decode_frame refused a frame decode took: %s\n", err_name(trusted));        \
        } else {                                                                                \
            format_fn((packet), again, sizeof again);                                           \
            if (strcmp(again, text) != 0) printf("decode_frame decoded %s\n", again);           \
        }                                                                                       \
    } while (0)

/* Per format FI, `carried_FI(packet)`: the packets a decoded packet's carrying fields carry,
 * one line each (`carried ok TEXT` or `carried err NAME`). */
#include "carried.h"

/* Per frame format FI (`FORMATS` of `spec.h`): `ok TEXT` or `err NAME`; with `encode` (bytes
 * as sent, not a stream decoder's frame), the packets it carries and the frame the packet
 * encodes to. A format that
 * escapes its bytes decodes bytes as sent with `decode`, and with `decode_frame` once
 * unescaped; a stream decoder's frame is unescaped already, and `decode_frame` reads it. An
 * escaped frame takes up to twice MAX_FRAME_LEN bytes. */
#define DESCRIBE(fi, lo, up)                                                                    \
    static void describe_##fi(const uint8_t *b, size_t n, int encode)                          \
    {                                                                                           \
        lo##packet pk, pk_frame;                                                                \
        uint8_t out[2 * up##MAX_FRAME_LEN];                                                     \
        uint8_t plain[up##MAX_FRAME_LEN];                                                       \
        int m = encode ? UNESCAPE_##fi(b, n, plain, sizeof plain) : -1;                         \
        int e = ESCAPED_##fi && !encode ? lo##decode_frame(b, n, &pk) : lo##decode(b, n, &pk);  \
        int trusted = m >= 0 ? lo##decode_frame(plain, (size_t)m, &pk_frame)                    \
                             : lo##decode_frame(b, n, &pk_frame);                               \
        int len;                                                                                \
        if (e != 0) {                                                                           \
            printf("err %s\n", err_name(e));                                                    \
            return;                                                                             \
        }                                                                                       \
        lo##format(&pk, text, sizeof text);                                                     \
        printf("ok %s\n", text);                                                                \
        same_as_decode(trusted, &pk_frame, lo##format);                                         \
        if (!encode) return;                                                                    \
        carried_##fi(&pk);                                                                      \
        len = lo##encode(&pk, out, sizeof out);                                                 \
        if (len < 0) {                                                                          \
            printf("enc err\n");                                                                \
            return;                                                                             \
        }                                                                                       \
        printf("enc ");                                                                         \
        put_hex(out, (size_t)len);                                                              \
        printf("\n");                                                                           \
        /* A buffer one byte short is refused, whatever the frame. */                           \
        e = lo##encode(&pk, out, (size_t)len - 1);                                              \
        if (e != U(ERR_SHORT_BUFFER)) printf("a buffer one byte short gave %d\n", e);           \
    }
FORMATS(DESCRIBE)

static void describe(int format, const uint8_t *b, size_t n, int encode)
{
    switch (format) {
#define CASE(fi, lo, up)                                                                        \
    case fi:                                                                                    \
        describe_##fi(b, n, encode);                                                            \
        return;
        FORMATS(CASE)
#undef CASE
    default:
        printf("no format %d\n", format);
    }
}

/* Per format FI whose decoder is given the direction (`GIVEN`): as `describe`, the frame
 * decoded as sent in direction `dir`. */
#define DESCRIBE_GIVEN(fi, lo, up)                                                              \
    static void describe_given_##fi(int dir, const uint8_t *b, size_t n)                       \
    {                                                                                           \
        lo##packet pk, pk_frame;                                                                \
        uint8_t out[2 * up##MAX_FRAME_LEN];                                                     \
        uint8_t plain[up##MAX_FRAME_LEN];                                                       \
        int m = UNESCAPE_##fi(b, n, plain, sizeof plain);                                       \
        int e = lo##decode_given(b, n, (P(direction))dir, &pk);                                 \
        int trusted = m >= 0 ? lo##decode_frame_given(plain, (size_t)m, (P(direction))dir, &pk_frame) \
                             : lo##decode_frame_given(b, n, (P(direction))dir, &pk_frame);      \
        int len;                                                                                \
        if (e != 0) {                                                                           \
            printf("err %s\n", err_name(e));                                                    \
            return;                                                                             \
        }                                                                                       \
        lo##format(&pk, text, sizeof text);                                                     \
        printf("ok %s\n", text);                                                                \
        same_as_decode(trusted, &pk_frame, lo##format);                                         \
        len = lo##encode(&pk, out, sizeof out);                                                 \
        if (len < 0) {                                                                          \
            printf("enc err\n");                                                                \
            return;                                                                             \
        }                                                                                       \
        printf("enc ");                                                                         \
        put_hex(out, (size_t)len);                                                              \
        printf("\n");                                                                           \
        e = lo##encode(&pk, out, (size_t)len - 1);                                              \
        if (e != U(ERR_SHORT_BUFFER)) printf("a buffer one byte short gave %d\n", e);           \
    }
GIVEN(DESCRIBE_GIVEN)

static void describe_given(int format, int dir, const uint8_t *b, size_t n)
{
    (void)dir;
    (void)b;
    (void)n;
    switch (format) {
#define CASE(fi, lo, up)                                                                        \
    case fi:                                                                                    \
        describe_given_##fi(dir, b, n);                                                         \
        return;
        GIVEN(CASE)
#undef CASE
    default:
        printf("no format %d with given directions\n", format);
    }
}

/* Per CAN format FI (`CAN_FORMATS`): a CAN frame decoded, and the CAN frame the packet
 * encodes to (`enc ID DATA`). */
#define DESCRIBE_CAN(fi, lo, up)                                                                \
    static void describe_can_##fi(uint32_t id, int extended, const uint8_t *b, size_t n)       \
    {                                                                                           \
        lo##packet pk;                                                                          \
        uint8_t data[8];                                                                        \
        uint32_t out_id = 0;                                                                    \
        int e = lo##decode_can(id, extended != 0, b, n, &pk);                                   \
        int len;                                                                                \
        if (e != 0) {                                                                           \
            printf("err %s\n", err_name(e));                                                    \
            return;                                                                             \
        }                                                                                       \
        lo##format(&pk, text, sizeof text);                                                     \
        printf("ok %s\n", text);                                                                \
        len = lo##encode_can(&pk, &out_id, data);                                               \
        if (len < 0) {                                                                          \
            printf("enc err\n");                                                                \
            return;                                                                             \
        }                                                                                       \
        printf("enc %lu ", (unsigned long)out_id);                                              \
        put_hex(data, (size_t)len);                                                             \
        printf("\n");                                                                           \
    }
CAN_FORMATS(DESCRIBE_CAN)

static void describe_can(int format, uint32_t id, int extended, const uint8_t *b, size_t n)
{
    (void)id;
    (void)extended;
    (void)b;
    (void)n;
    switch (format) {
#define CASE(fi, lo, up)                                                                        \
    case fi:                                                                                    \
        describe_can_##fi(id, extended, b, n);                                                  \
        return;
        CAN_FORMATS(CASE)
#undef CASE
    default:
        printf("no CAN format %d\n", format);
    }
}

#ifndef NO_DECODERS
static void event(const P(event) *ev)
{
    switch (ev->kind) {
    case U(EVENT_FRAME):
        printf("frame %llu ", (unsigned long long)ev->offset);
        put_hex(ev->bytes, ev->len);
        printf(" ");
        describe(ev->format, ev->bytes, ev->len, 0);
        break;
    case U(EVENT_REJECTED):
        printf("rejected %llu %s\n", (unsigned long long)ev->offset, P(reject_name)(ev->reason));
        break;
    case U(EVENT_SKIPPED):
        printf("skipped %llu %llu\n", (unsigned long long)ev->offset, (unsigned long long)ev->len);
        break;
    }
}

static void print_stats(const P(stats) *s)
{
    printf("stats %llu %llu %llu %llu %llu %llu %llu %llu %llu\n", (unsigned long long)s->frames,
           (unsigned long long)s->frame_bytes, (unsigned long long)s->skipped_bytes,
           (unsigned long long)s->bad_header, (unsigned long long)s->bad_header_check,
           (unsigned long long)s->bad_length, (unsigned long long)s->bad_checksum,
           (unsigned long long)s->bad_trailer, (unsigned long long)s->truncated);
}

/* Per stream decoder DI (`DECODERS`): the input fed in chunks of `chunk` bytes, then flushed;
 * every event and the counters. */
#define STREAM(di, lo, up)                                                                      \
    static void stream_##di(size_t chunk, const uint8_t *b, size_t n)                          \
    {                                                                                           \
        static lo##decoder d;                                                                   \
        P(event) ev;                                                                            \
        size_t at = 0;                                                                          \
        lo##decoder_init(&d);                                                                   \
        while (at < n) {                                                                        \
            size_t len = n - at < chunk ? n - at : chunk;                                       \
            const uint8_t *in = b + at;                                                         \
            at += len;                                                                          \
            while (lo##decoder_next(&d, &in, &len, &ev)) event(&ev);                            \
            if (len != 0) printf("input left over: %llu\n", (unsigned long long)len);          \
        }                                                                                       \
        while (lo##decoder_flush(&d, &ev)) event(&ev);                                          \
        print_stats(&d.stats);                                                                  \
    }
DECODERS(STREAM)

static void stream(int decoder, size_t chunk, const uint8_t *b, size_t n)
{
    switch (decoder) {
#define CASE(di, lo, up)                                                                        \
    case di:                                                                                    \
        stream_##di(chunk, b, n);                                                               \
        return;
        DECODERS(CASE)
#undef CASE
    default:
        printf("no decoder %d\n", decoder);
    }
}
#else
static void stream(int decoder, size_t chunk, const uint8_t *b, size_t n)
{
    (void)chunk;
    (void)b;
    (void)n;
    printf("no decoder %d\n", decoder);
}
#endif

int main(void)
{
    while (fgets(line, sizeof line, stdin)) {
        char *rest = line + 2;
        if (line[0] == 'P' && line[1] == ' ') {
            int format = (int)strtol(rest, &rest, 10);
            describe(format, bytes, unhex(rest + 1, bytes, sizeof bytes), 1);
        } else if (line[0] == 'D' && line[1] == ' ') {
            int format = (int)strtol(rest, &rest, 10);
            int dir = (int)strtol(rest, &rest, 10);
            describe_given(format, dir, bytes, unhex(rest + 1, bytes, sizeof bytes));
        } else if (line[0] == 'C' && line[1] == ' ') {
            int format = (int)strtol(rest, &rest, 10);
            int extended = (int)strtol(rest, &rest, 10);
            uint32_t id = (uint32_t)strtoul(rest, &rest, 10);
            describe_can(format, id, extended, bytes, unhex(rest + 1, bytes, sizeof bytes));
        } else if (line[0] == 'S' && line[1] == ' ') {
            int decoder = (int)strtol(rest, &rest, 10);
            size_t chunk = (size_t)strtoul(rest, &rest, 10);
            stream(decoder, chunk, bytes, unhex(rest + 1, bytes, sizeof bytes));
        } else {
            printf("unknown command\n");
        }
        printf("end\n");
    }
    return 0;
}
