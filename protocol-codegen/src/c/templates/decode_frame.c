int ${xlo}decode_frame${sfx}(const uint8_t *bytes, size_t len, ${params}${xlo}packet *out)
{
    size_t start = ${xup}HEADER_LEN, end;
    uint64_t raw = 0;
    struct ${lo}rd r;
    int e = 0;
${filled}    if (len > ${xup}MAX_FRAME_LEN${short}) return ${up}ERR_FRAME;
    memset(out, 0, ${zero});
    (void)raw;
    end = len - ${xup}TRAILER_LEN;
${flag_trailer}${header}${ack}${given_direction}${key}    if (end < start) return ${up}ERR_FRAME;
${can_command}${unstuff}${directions}${payload}    return 0;
}
