/* err.h: the one error record every fallible function fills.
 *
 * Fallible functions return 0 (or a pointer) on success and -1 (or NULL) on failure, after
 * writing one line into a caller-provided `struct err`: "path:line: what is wrong (expected)".
 * Nothing below main() prints or exits; main prints e.msg once and restores the terminal.
 * Messages never contain raw bytes from input files: use err_quote() for anything read. */
#ifndef RASTTY_ERR_H
#define RASTTY_ERR_H

#include <stddef.h>

struct err {
    char msg[320];
};

/* Warnings: things wrong with an input that still draws (a material's missing texture, an
 * unknown map_Kd option, a vt index past the end). Loaders add them; the command prints
 * them ("file:line: warning: ...") and carries on. The first WARN_KEEP are kept, the rest
 * only counted. */
#define WARN_KEEP 16
struct warnings {
    char msg[WARN_KEEP][320];
    int n;       /* kept in msg */
    int dropped; /* more than WARN_KEEP: only counted */
};

/* printf-style; w may be NULL (the warning is dropped). */
void warn_add(struct warnings *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* printf-style; always returns -1 so callers can `return err_set(e, ...)`. e may be NULL. */
int err_set(struct err *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Copy at most `max` bytes of untrusted text into out (size out_size) as printable ASCII:
 * control and non-ASCII bytes become '?', overlong input ends in "...". Returns out. */
const char *err_quote(const char *text, size_t len, size_t max, char *out, size_t out_size);

#endif
