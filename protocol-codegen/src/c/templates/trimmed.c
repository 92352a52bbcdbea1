/* The bytes of a payload its sender keeps: all but its trailing zeros, and at least the
 * first byte of a non-empty payload (the runtime's `zeros::trimmed_len`). */
static size_t ${xlo}trimmed(const uint8_t *p, size_t len)
{
    size_t kept = len;
    while (kept > 0 && p[kept - 1] == 0) kept--;
    return kept == 0 && len > 0 ? 1 : kept;
}
