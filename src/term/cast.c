/* cast.c: asciicast v2 writing (see cast.h). */
#include "cast.h"

#include <string.h>

/* s as the inside of a JSON string */
static void json_string(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20 || c == 0x7f)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
}

int cast_header(FILE *f, int cols, int rows, long timestamp, const char *title)
{
    fprintf(f, "{\"version\": 2, \"width\": %d, \"height\": %d, \"timestamp\": %ld, \"title\": \"",
            cols, rows, timestamp);
    json_string(f, title, strlen(title));
    fprintf(f, "\", \"env\": {\"TERM\": \"xterm-256color\"}}\n");
    return ferror(f) ? -1 : 0;
}

int cast_event(FILE *f, double seconds, const char *bytes, size_t n)
{
    fprintf(f, "[%.6f, \"o\", \"", seconds);
    json_string(f, bytes, n);
    fputs("\"]\n", f);
    return ferror(f) ? -1 : 0;
}
