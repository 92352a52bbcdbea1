/* Stuffs the payload written in `w`: ${insert} after every run of the pattern. */
static int ${lo}stuff(struct ${lo}wr *w)
{
    static const uint8_t pattern[${k}] = {${pattern}};
    size_t i = 0, extra = 0, cur = w->pos;
    while (i + ${k}u <= w->pos) {
        if (memcmp(w->p + i, pattern, ${k}u) == 0) {
            extra++;
            i += ${k}u;
        } else {
            i++;
        }
    }
    if (w->cap - w->pos < extra) return ${up}ERR_SHORT_BUFFER;
    i = 0;
    while (i + ${k}u <= cur) {
        if (memcmp(w->p + i, pattern, ${k}u) == 0) {
            size_t end = i + ${k}u;
            memmove(w->p + end + 1, w->p + end, cur - end);
            w->p[end] = ${insert};
            cur++;
            i = end + 1;
        } else {
            i++;
        }
    }
    w->pos = cur;
    return 0;
}
