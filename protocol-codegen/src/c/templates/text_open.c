/* ---- Text form ---- */

#ifdef ${up}WITH_FORMAT
#include <stdarg.h>
#include <stdio.h>

struct ${lo}txt { char *p; size_t cap; size_t len; };

static void ${lo}emit(struct ${lo}txt *t, const char *fmt, ...)
{
    va_list ap;
    int n;
    va_start(ap, fmt);
    n = vsnprintf(t->len < t->cap ? t->p + t->len : NULL, t->len < t->cap ? t->cap - t->len : 0, fmt, ap);
    va_end(ap);
    if (n > 0) t->len += (size_t)n;
}

/* The path of a nested value into `sub` (cut short when it does not fit). */
${up}UNUSED static void ${lo}path(char *sub, size_t cap, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(sub, cap, fmt, ap);
    va_end(ap);
}
