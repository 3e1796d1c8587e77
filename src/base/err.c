/* err.c: filling the error record (see err.h). */
#include "err.h"

#include <stdarg.h>
#include <stdio.h>

int err_set(struct err *e, const char *fmt, ...)
{
    if (e) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(e->msg, sizeof e->msg, fmt, ap);
        va_end(ap);
    }
    return -1;
}

void warn_add(struct warnings *w, const char *fmt, ...)
{
    if (!w)
        return;
    if (w->n == WARN_KEEP) {
        w->dropped++;
        return;
    }
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->msg[w->n++], sizeof w->msg[0], fmt, ap);
    va_end(ap);
}

const char *err_quote(const char *text, size_t len, size_t max, char *out, size_t out_size)
{
    size_t n = 0;
    if (out_size == 0)
        return out;
    for (size_t i = 0; i < len && i < max && n + 1 < out_size; i++) {
        unsigned char c = (unsigned char)text[i];
        out[n++] = (c >= 0x20 && c < 0x7f) ? (char)c : '?';
    }
    if (len > max && n + 4 < out_size) {
        out[n++] = '.';
        out[n++] = '.';
        out[n++] = '.';
    }
    out[n] = '\0';
    return out;
}
