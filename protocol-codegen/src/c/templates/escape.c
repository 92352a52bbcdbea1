/* Byte escaping between flags (the runtime's `escape`): the substitute sent after the escape
 * byte in place of a reserved byte, and the byte a substitute stands for; -1 for a byte that
 * is neither. */
${up}UNUSED static ${up}INLINE int ${xlo}substitute(uint8_t byte)
{
    switch (byte) {
${substitutes}    default: return -1;
    }
}

${up}UNUSED static ${up}INLINE int ${xlo}original(uint8_t byte)
{
    switch (byte) {
${originals}    default: return -1;
    }
}

/* The frame at the start of `wire[0..len]`, from its opening flag to the next flag,
 * unescaped into `out[0..cap]`, flags included (`*used`: the bytes of `wire` it took): its
 * length, or ${up}ERR_FRAME (no opening or closing flag, an escape byte not followed by a
 * substitute, a frame longer than `cap`). */
static int ${xlo}unescape_from(const uint8_t *wire, size_t len, uint8_t *out, size_t cap, size_t *used)
{
    size_t i, n = 0;
    int escaped = 0;
    if (len == 0 || wire[0] != ${flag} || cap == 0) return ${up}ERR_FRAME;
    out[n++] = ${flag};
    for (i = 1; i < len; i++) {
        uint8_t byte = wire[i];
        if (byte == ${flag}) {
            if (escaped || n >= cap) return ${up}ERR_FRAME;
            out[n++] = ${flag};
            *used = i + 1u;
            return (int)n;
        }
        if (escaped) {
            int original = ${xlo}original(byte);
            if (original < 0) return ${up}ERR_FRAME;
            byte = (uint8_t)original;
            escaped = 0;
        } else if (byte == ${escape}) {
            escaped = 1;
            continue;
        }
        if (n >= cap) return ${up}ERR_FRAME;
        out[n++] = byte;
    }
    return ${up}ERR_FRAME;
}

int ${xlo}unescape(const uint8_t *wire, size_t len, uint8_t *out, size_t cap)
{
    size_t used = 0;
    return ${xlo}unescape_from(wire, len, out, cap, &used);
}

/* Escapes the sealed frame `buf[0..len]` in place (its flags stay as they are), moving the
 * bytes towards the end of `buf` from the back, so each moves once: the length on the wire,
 * or ${up}ERR_SHORT_BUFFER with `buf` unchanged. A negative `len` (the seal's error) is
 * returned as it is. */
static int ${xlo}escape(uint8_t *buf, size_t cap, int len)
{
    size_t i, total, w;
    if (len < 2) return len;
    total = (size_t)len;
    for (i = 1; i + 1u < (size_t)len; i++) {
        if (${xlo}substitute(buf[i]) >= 0) total++;
    }
    if (total > cap) return ${up}ERR_SHORT_BUFFER;
    w = total - 1u;
    for (i = (size_t)len - 1u; i-- > 1u;) {
        int sub = ${xlo}substitute(buf[i]);
        if (sub >= 0) {
            buf[--w] = (uint8_t)sub;
            buf[--w] = ${escape};
        } else {
            buf[--w] = buf[i];
        }
    }
    buf[total - 1u] = ${flag};
    return (int)total;
}
