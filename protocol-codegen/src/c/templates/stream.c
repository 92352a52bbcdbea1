/* Bit streams (the runtime's `bitstream`): the `width`-bit member (1 to 64) at bit `at` of
 * `b[0..len]`, bit 0 being the most significant bit of byte 0, read and written bit by bit. */
${up}UNUSED static uint64_t ${lo}get_stream(const uint8_t *b, size_t len, size_t at, unsigned width)
{
    uint64_t v = 0;
    size_t k;
    if (width == 0 || width > 64 || at + width > len * 8u) return 0;
    for (k = at; k < at + width; k++) v = (v << 1) | (uint64_t)((b[k / 8u] >> (7u - k % 8u)) & 1u);
    return v;
}

/* Sets a member (the other bits as they are); 0 when the value does not fit `width`. */
${up}UNUSED static int ${lo}set_stream(uint8_t *b, size_t len, size_t at, unsigned width, uint64_t value)
{
    size_t k;
    if (width == 0 || width > 64 || at + width > len * 8u) return 0;
    if (width < 64 && (value >> width) != 0) return 0;
    for (k = at + width; k-- > at; value >>= 1) {
        uint8_t bit = (uint8_t)(1u << (7u - k % 8u));
        if (value & 1u) b[k / 8u] |= bit; else b[k / 8u] &= (uint8_t)~bit;
    }
    return 1;
}
