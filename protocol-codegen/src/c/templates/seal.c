/* The frame around a payload of `payload_len` bytes already written after the header. */
static int ${xlo}seal(uint8_t *buf, size_t payload_len, const ${xlo}header *h, size_t command)
{
    const size_t start = ${xup}HEADER_LEN, ext = 0;
    size_t body, total;
    if (payload_len > ${xup}MAX_PAYLOAD_LEN) return ${up}ERR_OUT_OF_RANGE;
    body = start + payload_len + ${xup}TRAILER_LEN;
    total = body;
    memset(buf, 0, start + ext);
    memset(buf + start + ext + payload_len, 0, ${xup}TRAILER_LEN);
${sync}    (void)h;
    (void)command;
${values}${sync_set}${trailers}${checks}    return (int)total;
}
