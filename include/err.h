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

/* printf-style; always returns -1 so callers can `return err_set(e, ...)`. e may be NULL. */
int err_set(struct err *e, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Copy at most `max` bytes of untrusted text into out (size out_size) as printable ASCII:
 * control and non-ASCII bytes become '?', overlong input ends in "...". Returns out. */
const char *err_quote(const char *text, size_t len, size_t max, char *out, size_t out_size);

#endif
