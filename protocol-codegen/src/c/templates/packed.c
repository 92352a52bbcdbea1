/* Bit-packed arrays (the runtime's `packed`): element `index` of `bits`-bit elements in
 * `b[0..len]`, bits filling each byte from its lowest bit (`msb` 0) or its highest (`msb`
 * 1). The element's bytes make one word, little-endian for lowest-bit-first, big-endian for
 * highest-bit-first; `*first`, `*count` and `*at` say where it lies in that word. */
${up}UNUSED static int ${lo}packed_span(size_t len, size_t index, unsigned bits, int msb, \
    size_t *first, unsigned *count, unsigned *at)
{
    size_t start = index * bits, last = (start + bits + 7) / 8;
    if (bits == 0 || bits > 32 || last > len) return 0;
    *first = start / 8;
    *count = (unsigned)(last - *first);
    *at = msb ? 8u * *count - (unsigned)(start % 8) - bits : (unsigned)(start % 8);
    return 1;
}

${up}UNUSED static uint64_t ${lo}get_packed(const uint8_t *b, size_t len, size_t index, unsigned bits, int msb)
{
    size_t first;
    unsigned count, at;
    if (!${lo}packed_span(len, index, bits, msb, &first, &count, &at)) return 0;
    return (${lo}get(b + first, count, msb) >> at) & (((uint64_t)1 << bits) - 1);
}

/* Sets an element (the other bits as they are); 0 when the value does not fit `bits`. */
${up}UNUSED static int ${lo}set_packed(uint8_t *b, size_t len, size_t index, unsigned bits, int msb, uint64_t value)
{
    size_t first;
    unsigned count, at;
    uint64_t m = ((uint64_t)1 << bits) - 1;
    if (!${lo}packed_span(len, index, bits, msb, &first, &count, &at) || value > m) return 0;
    ${lo}set(b + first, count, msb, (${lo}get(b + first, count, msb) & ~(m << at)) | (value << at));
    return 1;
}
