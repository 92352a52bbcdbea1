/* The frame around a payload of `payload_len` bytes already written at `start` (after the
 * header), in a buffer of `cap` bytes; `command` SIZE_MAX for a frame without dispatch key. */
static int ${xlo}seal(uint8_t *buf, size_t cap, size_t start, size_t payload_len, const ${xlo}header *h, size_t command)
{
    size_t ext = 0, flagged = 0, body, total;
    if (start > ${xup}HEADER_LEN \
        || payload_len > ${xup}MAX_PAYLOAD_LEN + (${xup}HEADER_LEN - start)) return ${up}ERR_OUT_OF_RANGE;
    body = start + payload_len + ${xup}TRAILER_LEN;
${extension}${flagged}    body += ext;
    total = body + flagged;
    if (total > cap) return ${up}ERR_SHORT_BUFFER;
    if (ext > 0) memmove(buf + start + ext, buf + start, payload_len);
    memset(buf, 0, start + ext);
    memset(buf + start + ext + payload_len, 0, ${xup}TRAILER_LEN);
${sync}    (void)h;
    (void)command;
${values}${sync_set}${trailers}${checks}${flag_copy}    return (int)total;
}
