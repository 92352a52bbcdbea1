/* Using the C codec of HFLink (`generated/hflink.h` and `generated/hflink.c`, written by
 * `protocol gen c specs/hflink.toml -o examples/c/generated`; `run.sh` regenerates them,
 * builds this program and runs it).
 *
 * A host encodes a SET_ROBOT_SPEED request, then decodes a capture of that frame with noise
 * around it, fed in chunks of 5 bytes, as a UART driver would hand them over. */
#include <stdio.h>

#include "hflink.h"

int main(void)
{
    hflink_header header = {0x01, 0x11}; /* from the PC (a master) to the MCU (a slave) */
    hflink_chassis_coord speed = {0.4f, 0.0f, -0.25f};
    uint8_t frame[HFLINK_MAX_FRAME_LEN];
    uint8_t capture[64];
    size_t captured = 0, at, i;
    int len = hflink_encode_set_robot_speed_request(&header, &speed, frame, sizeof frame);
    hflink_decoder decoder;
    hflink_event event;
    if (len < 0) {
        fprintf(stderr, "encode failed: %d\n", len);
        return 1;
    }
    printf("encoded %d bytes:", len);
    for (i = 0; i < (size_t)len; i++) printf(" %02x", frame[i]);
    printf("\n");

    /* Garbage, a stray 0xFF, the frame with a flipped bit, the frame. */
    capture[captured++] = 0x42;
    capture[captured++] = 0xFF;
    for (i = 0; i < (size_t)len; i++) capture[captured++] = frame[i] ^ (i == 9 ? 0x10 : 0);
    for (i = 0; i < (size_t)len; i++) capture[captured++] = frame[i];

    hflink_decoder_init(&decoder);
    for (at = 0; at < captured; at += 5) {
        const uint8_t *chunk = capture + at;
        size_t n = captured - at < 5 ? captured - at : 5;
        while (hflink_decoder_next(&decoder, &chunk, &n, &event)) {
            hflink_packet packet;
            switch (event.kind) {
            case HFLINK_EVENT_FRAME:
                if (hflink_decode_frame(event.bytes, event.len, &packet) == 0 &&
                    packet.command == HFLINK_SET_ROBOT_SPEED && packet.direction == HFLINK_REQUEST) {
                    printf("@%llu %s from 0x%02x: x=%g y=%g z=%g\n", (unsigned long long)event.offset,
                           hflink_command_name(packet.command), packet.header.sender,
                           packet.payload.set_robot_speed_request.x,
                           packet.payload.set_robot_speed_request.y,
                           packet.payload.set_robot_speed_request.z);
                }
                break;
            case HFLINK_EVENT_REJECTED:
                printf("@%llu rejected: %s\n", (unsigned long long)event.offset, hflink_reject_name(event.reason));
                break;
            case HFLINK_EVENT_SKIPPED:
                printf("@%llu skipped %llu bytes\n", (unsigned long long)event.offset, (unsigned long long)event.len);
                break;
            }
        }
    }
    while (hflink_decoder_flush(&decoder, &event)) {
        printf("@%llu pending bytes at the end\n", (unsigned long long)event.offset);
    }
    printf("frames %llu, skipped bytes %llu, bad checksums %llu, bad lengths %llu\n",
           (unsigned long long)decoder.stats.frames, (unsigned long long)decoder.stats.skipped_bytes,
           (unsigned long long)decoder.stats.bad_checksum, (unsigned long long)decoder.stats.bad_length);
    return decoder.stats.frames == 1 ? 0 : 1;
}
