/* Referee firmware with the generated C codec (`protocol gen c specs/referee.toml`): the job of
 * `main.c` for the referee link (decode every frame that arrives, decode its payload, encode
 * the packet back, keep the counters), as the Rust referee firmware of `footprint.sh
 * --crc-tables` does, for a size comparison. Measured, not run. */
#include "referee.h"

volatile uint8_t rx_uart[64];
volatile uint8_t tx_sink;
volatile uint64_t stats_sink;

static referee_decoder decoder;

void reset_handler(void);

void reset_handler(void)
{
    uint8_t rx[64];
    uint8_t out[REFEREE_MAX_FRAME_LEN];
    size_t i;
    referee_decoder_init(&decoder);
    for (;;) {
        const uint8_t *input = rx;
        size_t len = sizeof rx;
        referee_event event;
        for (i = 0; i < sizeof rx; i++) rx[i] = rx_uart[i];
        while (referee_decoder_next(&decoder, &input, &len, &event)) {
            referee_packet packet;
            int n;
            if (event.kind != REFEREE_EVENT_FRAME || referee_decode_frame(event.bytes, event.len, &packet) != 0) continue;
            n = referee_encode(&packet, out, sizeof out);
            if (n > 0) tx_sink = out[n - 1];
        }
        stats_sink = decoder.stats.frames;
    }
}
