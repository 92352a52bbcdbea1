/* The C twin of the QEMU firmware (`examples/firmware-qemu/src/main.rs`), on QEMU's mps2-an386
 * (a Cortex-M4): the HFLink and referee codecs that `protocol gen c` prints decode every golden
 * vector and the vectors' noisy streams, the results are printed over semihosting, then the
 * instructions per decoded frame of the C stream decoder are counted on the Rust firmware's
 * workload, and the firmware exits. `run.sh` builds it with arm-none-eabi-gcc -Os, runs it and
 * checks its output with `protocol-benches`' `qemu-check`, as the Rust firmware's.
 *
 * The lines are the Rust firmware's, and mean the same (see its header), except that a frame
 * the codec refuses names the C error code (`frame SPEC NAME error payload_length`) and the
 * decoder is named `C` in the `measure` lines. Counting works as there: SysTick counts QEMU's
 * virtual clock, one tick per 40 instructions under `-icount shift=0`, calibrated by a
 * `subs`/`bne` loop of a known instruction count.
 *
 * `vectors.h` is written by `qemu-check --c-vectors` from tests/vectors/ (the bytes the Rust
 * firmware's build script embeds). Startup, semihosting and SysTick are the few lines below:
 * no C library beyond newlib-nano's memcpy and memset. */
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "hflink.h"
#include "referee.h"
#include "vectors.h"

/* Passes over the workload for each measurement, and bytes per chunk, as in the Rust firmware. */
#define PASSES 64u
#define CHUNK 64u

#define COUNT(a) (sizeof(a) / sizeof((a)[0]))

/* ---- Semihosting (ARM semihosting over `bkpt 0xab` on M-profile) ---- */

#define SYS_OPEN 0x01
#define SYS_WRITE 0x05
#define SYS_EXIT 0x18
#define ADP_STOPPED_APPLICATION_EXIT 0x20026
#define ADP_STOPPED_RUNTIME_ERROR 0x20023

static int semihost(int op, const void *arg)
{
    register int r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

static void exit_with(int reason)
{
    /* On 32-bit ARM, SYS_EXIT takes the reason itself in r1. */
    semihost(SYS_EXIT, (const void *)(uintptr_t)reason);
    for (;;) {
    }
}

/* One output line, built in a buffer and printed with one semihosting call. */
static char line[640];
static size_t line_len;

static void put(const char *s)
{
    while (*s && line_len < sizeof line - 1) line[line_len++] = *s++;
}

static void put_u64(uint64_t v)
{
    char digits[21];
    size_t n = 0;
    do {
        digits[n++] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v);
    while (n && line_len < sizeof line - 1) line[line_len++] = digits[--n];
}

static void put_hex(const uint8_t *bytes, size_t len)
{
    static const char digit[] = "0123456789abcdef";
    size_t i;
    for (i = 0; i < len && line_len < sizeof line - 2; i++) {
        line[line_len++] = digit[bytes[i] >> 4];
        line[line_len++] = digit[bytes[i] & 15u];
    }
}

/* The host's standard output: the file `:tt` opened for writing (mode 4, "w"), as the Rust
   firmware's `hprintln!` does (QEMU sends the console calls, such as SYS_WRITE0, to stderr). */
static int stdout_handle = -1;

static void end_line(void)
{
    uint32_t args[3];
    line[line_len++] = '\n';
    if (stdout_handle < 0) {
        args[0] = (uint32_t)(uintptr_t)":tt";
        args[1] = 4u;
        args[2] = 3u;
        stdout_handle = semihost(SYS_OPEN, args);
    }
    args[0] = (uint32_t)stdout_handle;
    args[1] = (uint32_t)(uintptr_t)line;
    args[2] = (uint32_t)line_len;
    semihost(SYS_WRITE, args);
    line_len = 0;
}

/* ---- SysTick: a free-running 24-bit down-counter of the core clock ---- */

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

static void start_systick(void)
{
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0;
    SYST_CSR = 5u; /* enabled, core clock, no interrupt */
}

/* Keeps the compiler from assuming anything about what `p` points to (Rust's `black_box`). */
#define BLACK_BOX(p) __asm__ volatile("" : : "r"(p) : "memory")

/* `n` runs of `subs; bne`: 2 n instructions. */
static void delay_loop(uint32_t n)
{
    __asm__ volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(n) : : "cc");
}

static void measure(const char *spec, const char *decoder, uint32_t frames, size_t bytes, uint32_t start,
                    uint32_t end)
{
    put("measure ");
    put(spec);
    put(" ");
    put(decoder);
    put(" ");
    put_u64(frames);
    put(" ");
    put_u64(bytes);
    put(" ");
    put_u64((start - end) & 0x00FFFFFFu);
    end_line();
}

/* The noisy workload: every golden frame, then the vector's stream, in one buffer. */
static size_t workload(const vector *frames, size_t n_frames, const vector *streams, size_t n_streams,
                       uint8_t *buf, size_t cap)
{
    size_t len = 0, i;
    for (i = 0; i < n_frames + n_streams; i++) {
        const vector *v = i < n_frames ? &frames[i] : &streams[i - n_frames];
        if (len + v->len > cap) return 0;
        memcpy(buf + len, v->bytes, v->len);
        len += v->len;
    }
    return len;
}

static void measure_loop(const char *spec, const uint8_t *buf, size_t len)
{
    uint32_t pass, start = SYST_CVR, end;
    size_t at;
    for (pass = 0; pass < PASSES; pass++) {
        for (at = 0; at < len; at += CHUNK) {
            const uint8_t *chunk = buf + at;
            size_t n = len - at < CHUNK ? len - at : CHUNK;
            BLACK_BOX(chunk);
            BLACK_BOX(n);
        }
    }
    end = SYST_CVR;
    measure(spec, "loop", 0, len * PASSES, start, end);
}

/* The golden-frame, stream and measuring functions of one codec (prefix `p`, upper-case `P`). */
#define CODEC(p, P)                                                                                    \
    static const char *p##_error_name(int e)                                                           \
    {                                                                                                  \
        switch (e) {                                                                                   \
        case P##_ERR_SHORT_BUFFER: return "short_buffer";                                              \
        case P##_ERR_OUT_OF_RANGE: return "out_of_range";                                              \
        case P##_ERR_PAYLOAD_LENGTH: return "payload_length";                                          \
        case P##_ERR_UNKNOWN_COMMAND: return "unknown_command";                                        \
        case P##_ERR_UNKNOWN_DIRECTION: return "unknown_direction";                                    \
        case P##_ERR_INVALID_ENUM: return "invalid_enum";                                              \
        case P##_ERR_FRAME: return "frame";                                                            \
        case P##_ERR_SIZE_MISMATCH: return "size_mismatch";                                            \
        case P##_ERR_UNTERMINATED: return "unterminated";                                              \
        case P##_ERR_PAYLOAD_CHECK: return "payload_check";                                            \
        case P##_ERR_OUTSIDE_CLAMP: return "outside_clamp";                                            \
        case P##_ERR_INVALID_STUFFING: return "invalid_stuffing";                                      \
        default: return "unknown_error";                                                               \
        }                                                                                              \
    }                                                                                                  \
                                                                                                       \
    static void p##_golden(const vector *v)                                                            \
    {                                                                                                  \
        static p##_packet packet;                                                                      \
        uint8_t out[512];                                                                              \
        int e = p##_decode(v->bytes, v->len, &packet), n;                                              \
        put("frame " #p " ");                                                                          \
        put(v->name);                                                                                  \
        if (e != 0) {                                                                                  \
            put(" error ");                                                                            \
            put(p##_error_name(e));                                                                    \
        } else if ((n = p##_encode(&packet, out, sizeof out)) < 0) {                                   \
            put(" encode-error ");                                                                     \
            put(p##_error_name(n));                                                                    \
        } else {                                                                                       \
            put(" ok ");                                                                               \
            put(p##_command_name(packet.command));                                                     \
            put(" ");                                                                                  \
            put_hex(out, (size_t)n);                                                                   \
        }                                                                                              \
        end_line();                                                                                    \
    }                                                                                                  \
                                                                                                       \
    static void p##_stream_event(const vector *v, const p##_event *event)                              \
    {                                                                                                  \
        static p##_packet packet;                                                                      \
        if (event->kind != P##_EVENT_FRAME) return;                                                    \
        put("stream " #p " ");                                                                         \
        put(v->name);                                                                                  \
        put(" frame ");                                                                                \
        put_u64(event->offset);                                                                        \
        put(" ");                                                                                      \
        put_hex(event->bytes, event->len);                                                             \
        if (p##_decode_frame(event->bytes, event->len, &packet) != 0) put(" undecodable");             \
        end_line();                                                                                    \
    }                                                                                                  \
                                                                                                       \
    /* A stream vector, fed in chunks of 7 bytes, then flushed. */                                     \
    static void p##_stream(const vector *v)                                                            \
    {                                                                                                  \
        static p##_decoder decoder;                                                                    \
        p##_event event;                                                                               \
        const p##_stats *s = &decoder.stats;                                                           \
        size_t at;                                                                                     \
        p##_decoder_init(&decoder);                                                                    \
        for (at = 0; at < v->len; at += 7) {                                                           \
            const uint8_t *chunk = v->bytes + at;                                                      \
            size_t n = v->len - at < 7 ? v->len - at : 7;                                              \
            while (p##_decoder_next(&decoder, &chunk, &n, &event)) p##_stream_event(v, &event);        \
        }                                                                                              \
        while (p##_decoder_flush(&decoder, &event)) p##_stream_event(v, &event);                       \
        put("stream " #p " ");                                                                         \
        put(v->name);                                                                                  \
        put(" stats ");                                                                                \
        put_u64(s->frames);                                                                            \
        put(" ");                                                                                      \
        put_u64(s->skipped_bytes);                                                                     \
        put(" ");                                                                                      \
        put_u64(s->bad_header + s->bad_header_check + s->bad_length + s->bad_checksum +                \
                s->bad_trailer + s->truncated);                                                        \
        end_line();                                                                                    \
    }                                                                                                  \
                                                                                                       \
    /* The measured job: 64-byte chunks to the stream decoder, every frame decoded into its            \
       packet and counted when it decodes; then the stream decoder alone. */                           \
    static void p##_measure(const uint8_t *buf, size_t len)                                            \
    {                                                                                                  \
        static p##_decoder decoder;                                                                    \
        uint32_t pass, frames = 0, start, end;                                                         \
        size_t at;                                                                                     \
        p##_decoder_init(&decoder);                                                                    \
        start = SYST_CVR;                                                                              \
        for (pass = 0; pass < PASSES; pass++) {                                                        \
            for (at = 0; at < len; at += CHUNK) {                                                      \
                const uint8_t *chunk = buf + at;                                                       \
                size_t n = len - at < CHUNK ? len - at : CHUNK;                                        \
                p##_event event;                                                                       \
                BLACK_BOX(chunk);                                                                      \
                while (p##_decoder_next(&decoder, &chunk, &n, &event)) {                               \
                    p##_packet packet;                                                                 \
                    if (event.kind == P##_EVENT_FRAME &&                                               \
                        p##_decode_frame(event.bytes, event.len, &packet) == 0) {                         \
                        BLACK_BOX(&packet);                                                            \
                        frames++;                                                                      \
                    }                                                                                  \
                }                                                                                      \
            }                                                                                          \
        }                                                                                              \
        end = SYST_CVR;                                                                                \
        measure(#p, "C", frames, len * PASSES, start, end);                                            \
                                                                                                       \
        /* The framing alone: the frames the stream decoder yields, not decoded into packets. */       \
        p##_decoder_init(&decoder);                                                                    \
        frames = 0;                                                                                    \
        start = SYST_CVR;                                                                              \
        for (pass = 0; pass < PASSES; pass++) {                                                        \
            for (at = 0; at < len; at += CHUNK) {                                                      \
                const uint8_t *chunk = buf + at;                                                       \
                size_t n = len - at < CHUNK ? len - at : CHUNK;                                        \
                p##_event event;                                                                       \
                BLACK_BOX(chunk);                                                                      \
                while (p##_decoder_next(&decoder, &chunk, &n, &event)) {                               \
                    if (event.kind == P##_EVENT_FRAME) {                                               \
                        BLACK_BOX(event.bytes);                                                        \
                        frames++;                                                                      \
                    }                                                                                  \
                }                                                                                      \
            }                                                                                          \
        }                                                                                              \
        end = SYST_CVR;                                                                                \
        measure(#p, "C-framing", frames, len * PASSES, start, end);                                    \
    }

CODEC(hflink, HFLINK)
CODEC(referee, REFEREE)

int main(void);

int main(void)
{
    static uint8_t buf[4096];
    size_t i, len;
    const uint32_t delay = 1000000u;
    uint32_t start, end;

    put("firmware-qemu-c: Cortex-M4, generated HFLink and referee C codecs");
    end_line();
    for (i = 0; i < COUNT(hflink_frames); i++) hflink_golden(&hflink_frames[i]);
    for (i = 0; i < COUNT(referee_frames); i++) referee_golden(&referee_frames[i]);
    for (i = 0; i < COUNT(hflink_streams); i++) hflink_stream(&hflink_streams[i]);
    for (i = 0; i < COUNT(referee_streams); i++) referee_stream(&referee_streams[i]);

    start_systick();
    start = SYST_CVR;
    delay_loop(delay);
    end = SYST_CVR;
    put("calibrate ");
    put_u64(2u * (uint64_t)delay);
    put(" ");
    put_u64((start - end) & 0x00FFFFFFu);
    end_line();

    len = workload(hflink_frames, COUNT(hflink_frames), hflink_streams, COUNT(hflink_streams), buf, sizeof buf);
    measure_loop("hflink", buf, len);
    hflink_measure(buf, len);
    len = workload(referee_frames, COUNT(referee_frames), referee_streams, COUNT(referee_streams), buf,
                   sizeof buf);
    measure_loop("referee", buf, len);
    referee_measure(buf, len);

    put("done");
    end_line();
    exit_with(ADP_STOPPED_APPLICATION_EXIT);
    return 0;
}

/* ---- Startup ---- */

extern uint32_t __data_load, __data_start, __data_end, __bss_start, __bss_end;

void reset_handler(void);
void fault_handler(void);

void reset_handler(void)
{
    uint32_t *src = &__data_load, *dst = &__data_start;
    while (dst < &__data_end) *dst++ = *src++;
    for (dst = &__bss_start; dst < &__bss_end;) *dst++ = 0;
    /* The FPU (CP10 and CP11, full access): the codecs' `float` fields use it. */
    *(volatile uint32_t *)0xE000ED88u |= 0xFu << 20;
    __asm__ volatile("dsb\n\tisb" ::: "memory");
    main();
    exit_with(ADP_STOPPED_APPLICATION_EXIT);
}

void fault_handler(void)
{
    put("fault");
    end_line();
    exit_with(ADP_STOPPED_RUNTIME_ERROR);
}

/* The initial stack pointer (the end of link.ld's RAM), reset, and every other exception to the
   fault handler. */
__attribute__((section(".vector_table"), used)) void (*const vector_table[16])(void) = {
    (void (*)(void))0x20010000u, reset_handler, fault_handler, fault_handler,
    fault_handler,               fault_handler, fault_handler, 0,
    0,                           0,             0,             fault_handler,
    fault_handler,               0,             fault_handler, fault_handler,
};
