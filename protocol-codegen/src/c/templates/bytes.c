/* ---- Byte order ---- */

/* A payload being read, and a frame being written. */
struct ${lo}rd { const uint8_t *p; size_t len; size_t pos; };
struct ${lo}wr { uint8_t *p; size_t cap; size_t pos; };

/* An unsigned integer of `n` bytes: the common sizes without a loop over 64-bit shifts. */
${up}UNUSED static ${up}INLINE uint64_t ${lo}get(const uint8_t *p, unsigned n, int big)
{
    uint64_t v = 0;
    unsigned i;
    switch (n) {
    case 1: return p[0];
    case 2: return big ? (uint32_t)p[1] | (uint32_t)p[0] << 8 : (uint32_t)p[0] | (uint32_t)p[1] << 8;
    case 4: return big ? (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24 \
        : (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    default: break;
    }
    for (i = 0; i < n; i++) {
        v |= (uint64_t)p[big ? n - 1 - i : i] << (8 * i);
    }
    return v;
}

${up}UNUSED static ${up}INLINE void ${lo}set(uint8_t *p, unsigned n, int big, uint64_t v)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        p[big ? n - 1 - i : i] = (uint8_t)(v >> (8 * i));
    }
}

/* The low `bits` bits of `v` as a two's complement integer. */
${up}UNUSED static int64_t ${lo}sext(uint64_t v, unsigned bits)
{
    uint64_t sign;
    if (bits >= 64) {
        return (v >> 63) ? -(int64_t)(~v) - 1 : (int64_t)v;
    }
    sign = (uint64_t)1 << (bits - 1);
    v &= (sign << 1) - 1;
    return (v & sign) ? (int64_t)(v - sign) - (int64_t)(sign - 1) - 1 : (int64_t)v;
}

${up}UNUSED static float ${lo}f32(uint64_t raw)
{
    uint32_t b = (uint32_t)raw;
    float f;
    memcpy(&f, &b, sizeof f);
    return f;
}

${up}UNUSED static double ${lo}f64(uint64_t raw)
{
    double f;
    memcpy(&f, &raw, sizeof f);
    return f;
}

${up}UNUSED static uint64_t ${lo}f32_bits(float f)
{
    uint32_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

${up}UNUSED static uint64_t ${lo}f64_bits(double f)
{
    uint64_t b;
    memcpy(&b, &f, sizeof b);
    return b;
}

/* An IEEE 754 half's bits as a float: exact, by the runtime's bit arithmetic. */
${up}UNUSED static float ${lo}f16(uint64_t raw)
{
    uint32_t h = (uint32_t)raw & 0xFFFFu;
    uint32_t sign = (h & 0x8000u) << 16, exp = (h >> 10) & 0x1Fu, man = h & 0x3FFu, b;
    uint32_t shift = 0;
    if (exp == 0 && man == 0) {
        b = sign;
    } else if (exp == 0) {
        /* A subnormal: normalized so that its top bit is the implicit one. */
        while (!(man & 0x400u)) {
            man <<= 1;
            shift++;
        }
        b = sign | ((113u - shift) << 23) | ((man & 0x3FFu) << 13);
    } else if (exp == 0x1Fu) {
        b = sign | 0x7F800000u | (man << 13);
    } else {
        b = sign | ((exp + 112u) << 23) | (man << 13);
    }
    return ${lo}f32(b);
}

/* The bits of the half nearest `f`, ties to even; 0x10000 (no half) when `f` is finite but
 * beyond the largest half. A NaN keeps its sign and the top ten bits of its payload. */
${up}UNUSED static uint64_t ${lo}f16_bits(float f)
{
    uint32_t b = (uint32_t)${lo}f32_bits(f);
    uint32_t sign = (b >> 16) & 0x8000u, exp = (b >> 23) & 0xFFu, man = b & 0x7FFFFFu;
    uint32_t full, drop, kept, rest, half;
    if (exp == 0xFFu) {
        uint32_t nan = man == 0 ? 0 : ((man >> 13) == 0 ? 0x200u : (man >> 13));
        return sign | 0x7C00u | nan;
    }
    if (exp < 102u) return sign;
    if (exp >= 113u) {
        full = man;
        drop = 13;
        kept = ((exp - 112u) << 10) | (man >> 13);
    } else {
        full = man | 0x800000u;
        drop = 126u - exp;
        kept = full >> drop;
    }
    rest = full & ((1u << drop) - 1u);
    half = 1u << (drop - 1u);
    if (rest > half || (rest == half && (kept & 1u))) kept++;
    if (kept >= 0x7C00u) return 0x10000u;
    return sign | kept;
}

${up}UNUSED static int ${lo}take_uint(struct ${lo}rd *r, unsigned n, int big, uint64_t *out)
{
    if (r->len - r->pos < n) return ${up}ERR_PAYLOAD_LENGTH;
    *out = ${lo}get(r->p + r->pos, n, big);
    r->pos += n;
    return 0;
}

${up}UNUSED static int ${lo}skip(struct ${lo}rd *r, size_t n)
{
    if (r->len - r->pos < n) return ${up}ERR_PAYLOAD_LENGTH;
    r->pos += n;
    return 0;
}

${up}UNUSED static int ${lo}put_uint(struct ${lo}wr *w, unsigned n, int big, uint64_t v)
{
    if (w->cap - w->pos < n) return ${up}ERR_SHORT_BUFFER;
    ${lo}set(w->p + w->pos, n, big, v);
    w->pos += n;
    return 0;
}

${up}UNUSED static int ${lo}zero(struct ${lo}wr *w, size_t n)
{
    if (w->cap - w->pos < n) return ${up}ERR_SHORT_BUFFER;
    memset(w->p + w->pos, 0, n);
    w->pos += n;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u8(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 1u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint32_t)p[0];
    r->pos += 1u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u8(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    if (w->cap - w->pos < 1u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[0] = (uint8_t)(v >> 0);
    w->pos += 1u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u16le(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 2u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint32_t)p[0] | (uint32_t)p[1] << 8;
    r->pos += 2u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u16le(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    if (w->cap - w->pos < 2u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[0] = (uint8_t)(v >> 0);
    p[1] = (uint8_t)(v >> 8);
    w->pos += 2u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u16be(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 2u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint32_t)p[1] | (uint32_t)p[0] << 8;
    r->pos += 2u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u16be(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    if (w->cap - w->pos < 2u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[1] = (uint8_t)(v >> 0);
    p[0] = (uint8_t)(v >> 8);
    w->pos += 2u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u32le(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 4u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    r->pos += 4u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u32le(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    if (w->cap - w->pos < 4u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[0] = (uint8_t)(v >> 0);
    p[1] = (uint8_t)(v >> 8);
    p[2] = (uint8_t)(v >> 16);
    p[3] = (uint8_t)(v >> 24);
    w->pos += 4u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u32be(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 4u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24;
    r->pos += 4u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u32be(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    if (w->cap - w->pos < 4u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[3] = (uint8_t)(v >> 0);
    p[2] = (uint8_t)(v >> 8);
    p[1] = (uint8_t)(v >> 16);
    p[0] = (uint8_t)(v >> 24);
    w->pos += 4u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u64le(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 8u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint64_t)((uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24) \
        | (uint64_t)((uint32_t)p[4] | (uint32_t)p[5] << 8 | (uint32_t)p[6] << 16 | (uint32_t)p[7] << 24) << 32;
    r->pos += 8u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u64le(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    uint32_t l = (uint32_t)v, h = (uint32_t)(v >> 32);
    if (w->cap - w->pos < 8u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[0] = (uint8_t)(l >> 0);
    p[1] = (uint8_t)(l >> 8);
    p[2] = (uint8_t)(l >> 16);
    p[3] = (uint8_t)(l >> 24);
    p[4] = (uint8_t)(h >> 0);
    p[5] = (uint8_t)(h >> 8);
    p[6] = (uint8_t)(h >> 16);
    p[7] = (uint8_t)(h >> 24);
    w->pos += 8u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}take_u64be(struct ${lo}rd *r, uint64_t *out)
{
    const uint8_t *p;
    if (r->len - r->pos < 8u) return ${up}ERR_PAYLOAD_LENGTH;
    p = r->p + r->pos;
    *out = (uint64_t)((uint32_t)p[7] | (uint32_t)p[6] << 8 | (uint32_t)p[5] << 16 | (uint32_t)p[4] << 24) \
        | (uint64_t)((uint32_t)p[3] | (uint32_t)p[2] << 8 | (uint32_t)p[1] << 16 | (uint32_t)p[0] << 24) << 32;
    r->pos += 8u;
    return 0;
}

${up}UNUSED static ${up}INLINE int ${lo}put_u64be(struct ${lo}wr *w, uint64_t v)
{
    uint8_t *p;
    uint32_t l = (uint32_t)v, h = (uint32_t)(v >> 32);
    if (w->cap - w->pos < 8u) return ${up}ERR_SHORT_BUFFER;
    p = w->p + w->pos;
    p[7] = (uint8_t)(l >> 0);
    p[6] = (uint8_t)(l >> 8);
    p[5] = (uint8_t)(l >> 16);
    p[4] = (uint8_t)(l >> 24);
    p[3] = (uint8_t)(h >> 0);
    p[2] = (uint8_t)(h >> 8);
    p[1] = (uint8_t)(h >> 16);
    p[0] = (uint8_t)(h >> 24);
    w->pos += 8u;
    return 0;
}

/* A position from the frame's start or back from its end, in a frame of `len` bytes;
 * SIZE_MAX when it falls outside. */
${up}UNUSED static ${up}INLINE size_t ${lo}pos(size_t len, int from_end, size_t n)
{
    if (from_end) return len >= n ? len - n : SIZE_MAX;
    return n <= len ? n : SIZE_MAX;
}

/* A value of `width` bits at bit `shift` of the word of `size` bytes at a position. */
${up}UNUSED static ${up}INLINE int ${lo}field(const uint8_t *f, size_t len, int from_end, size_t at, \
    unsigned size, int big, unsigned shift, unsigned width, uint64_t *out)
{
    size_t o = ${lo}pos(len, from_end, at);
    uint64_t m = width >= 64 ? ~(uint64_t)0 : (((uint64_t)1 << width) - 1);
    if (o == SIZE_MAX || len - o < size) return 0;
    *out = (${lo}get(f + o, size, big) >> shift) & m;
    return 1;
}

${up}UNUSED static ${up}INLINE int ${lo}put_field(uint8_t *f, size_t len, int from_end, size_t at, \
    unsigned size, int big, unsigned shift, unsigned width, uint64_t value)
{
    size_t o = ${lo}pos(len, from_end, at);
    uint64_t m = width >= 64 ? ~(uint64_t)0 : (((uint64_t)1 << width) - 1);
    if (o == SIZE_MAX || len - o < size || value > m) return 0;
    ${lo}set(f + o, size, big, ${lo}get(f + o, size, big) | (value << shift));
    return 1;
}
