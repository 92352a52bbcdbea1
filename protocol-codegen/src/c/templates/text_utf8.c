/* Whether `s[0..n]` is UTF-8 (no overlong form, no surrogate, nothing above U+10FFFF). */
${up}UNUSED static int ${lo}utf8(const uint8_t *s, size_t n)
{
    size_t i = 0, k, more;
    while (i < n) {
        uint8_t c = s[i], lo = 0x80, hi = 0xBF;
        if (c < 0x80) {
            i++;
            continue;
        }
        if (c >= 0xC2 && c <= 0xDF) more = 1;
        else if (c >= 0xE0 && c <= 0xEF) more = 2;
        else if (c >= 0xF0 && c <= 0xF4) more = 3;
        else return 0;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
        if (n - i - 1 < more) return 0;
        for (k = 1; k <= more; k++) {
            if (s[i + k] < (k == 1 ? lo : 0x80) || s[i + k] > (k == 1 ? hi : 0xBF)) return 0;
        }
        i += more + 1;
    }
    return 1;
}

${up}UNUSED static void ${lo}fmt_text(struct ${lo}txt *t, const char *path, const uint8_t *b, size_t n)
{
    size_t len = 0, i;
    int canonical;
    while (len < n && b[len] != 0) len++;
    canonical = ${lo}utf8(b, len);
    for (i = len; i < n; i++) canonical = canonical && b[i] == 0;
    if (canonical) {
        ${lo}emit(t, " %s=", path);
        for (i = 0; i < len; i++) {
            if (b[i] < 0x20 || b[i] == 0x7F || b[i] == '\\') ${lo}emit(t, "\\x%02x", (unsigned)b[i]);
            else ${lo}emit(t, "%c", b[i]);
        }
        return;
    }
    for (i = 0; i < n; i++) ${lo}emit(t, " %s[%u]=%u", path, (unsigned)i, (unsigned)b[i]);
}
