
/* `${struct_name}.${field_name}` read as the packet it carries: the command whose id
 * `${key_name}` holds${in_direction}, its payload read from the bytes into the member of
 * `out` that a frame of format `${format}` would hold it in (the header is zeroed). Returns 0,
 * ${up}ERR_UNKNOWN_COMMAND when the id names no command, or the error of reading the payload
 * (${up}ERR_PAYLOAD_LENGTH for one that is not the command's). */
int ${lo}read_carried_${snake}_${field}(const ${ty} *carrier, ${params}${xlo}packet *out)
{
    struct ${lo}rd r;
    int e = 0;
    memset(out, 0, offsetof(${xlo}packet, payload));
    switch ((uint64_t)carrier->${key}) {
${cases}    default:
        return ${up}ERR_UNKNOWN_COMMAND;
    }
${direction}    r.p = carrier->${field};
    r.len = carrier->${field}_len;
    r.pos = 0;
${reads}    if (e != 0) return e;
    if (r.pos != r.len) return ${up}ERR_PAYLOAD_LENGTH;
    return 0;
}
