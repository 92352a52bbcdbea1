/* HFLink firmware with the generated C codec (`protocol gen c`): the job of the Rust
 * firmware `benches/firmware/generated` (decode every frame that arrives, decode its payload,
 * encode the packet back, keep the counters), for a size comparison. The received bytes come
 * from a volatile buffer, so nothing is constant folded. Measured, not run: there is no
 * startup code beyond the reset vector. */
#include "hflink.h"

volatile uint8_t rx_uart[64];
volatile uint8_t tx_sink;
volatile uint64_t stats_sink;

static hflink_decoder decoder;

void reset_handler(void);

void reset_handler(void)
{
    uint8_t rx[64];
    uint8_t out[HFLINK_MAX_FRAME_LEN];
    size_t i;
    hflink_decoder_init(&decoder);
    for (;;) {
        const uint8_t *input = rx;
        size_t len = sizeof rx;
        hflink_event event;
        for (i = 0; i < sizeof rx; i++) rx[i] = rx_uart[i];
        while (hflink_decoder_next(&decoder, &input, &len, &event)) {
            hflink_packet packet;
            int n;
            if (event.kind != HFLINK_EVENT_FRAME || hflink_decode_frame(event.bytes, event.len, &packet) != 0) continue;
            n = hflink_encode(&packet, out, sizeof out);
            if (n > 0) tx_sink = out[n - 1];
        }
        stats_sink = decoder.stats.frames;
    }
}
