/* What a probe found: a frame, or the need of more bytes (else a rejection's reason). */
#define ${up}PROBE_FRAME 0
#define ${up}PROBE_NEED (-1)

/* Whether the check stored at `at` is the check of the bytes `from..to` (a check without
 * value, such as one whose per-command byte names no command, matches nothing). */
${up}UNUSED static ${up}INLINE int ${lo}verify(const uint8_t *f, size_t len, size_t from, size_t to, size_t at, \
    unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))
{
    uint64_t value = 0;
    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;
    return check(f + from, to - from, &value) && ${lo}get(f + at, width, big) == value;
}

/* Computes the check of `from..to` and stores it at `at`. */
${up}UNUSED static ${up}INLINE int ${lo}store(uint8_t *f, size_t len, size_t from, size_t to, size_t at, \
    unsigned width, int big, int (*check)(const uint8_t *, size_t, uint64_t *))
{
    uint64_t value = 0;
    if (from == SIZE_MAX || to == SIZE_MAX || at == SIZE_MAX || from > to || len - at < width) return 0;
    if (!check(f + from, to - from, &value)) return 0;
    ${lo}set(f + at, width, big, value);
    return 1;
}
