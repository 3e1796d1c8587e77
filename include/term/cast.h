/* cast.h: asciicast v2 recordings (https://docs.asciinema.org/manual/asciicast/v2/), the
 * format `asciinema play` and the asciinema web player read.
 *
 * A header line, a JSON object {"version": 2, "width": C, "height": R, "timestamp": T,
 * "title": ..., "env": {"TERM": "xterm-256color"}}, then one line per output event,
 * [seconds, "o", "bytes"], the bytes as a JSON string (", \\ and control bytes escaped as
 * \\", \\\\ and \\u00XX; UTF-8 passed through). Used by `rastty dump --out FILE.cast`. */
#ifndef RASTTY_CAST_H
#define RASTTY_CAST_H

#include <stddef.h>
#include <stdio.h>

/* 0, or -1 when the write failed. */
int cast_header(FILE *f, int cols, int rows, long timestamp, const char *title);
int cast_event(FILE *f, double seconds, const char *bytes, size_t n);

#endif
