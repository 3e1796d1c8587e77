/* test_cast.c: asciicast v2 lines — JSON escaping of terminal bytes. */
#include <stdio.h>
#include <string.h>

#include "cast.h"
#include "test.h"

TEST(cast_lines_are_json_with_terminal_bytes_escaped)
{
    FILE *f = tmpfile();
    REQUIRE(f);
    REQUIRE(cast_header(f, 80, 24, 1700000000, "a \"quoted\" name") == 0);
    static const char bytes[] = "\x1b[H\"\\\x01\x7f\xe2\x96\x80 ok";
    REQUIRE(cast_event(f, 0.5, bytes, sizeof bytes - 1) == 0);
    rewind(f);
    char text[512] = {0};
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    CHECK_STR_CONTAINS(text, "{\"version\": 2, \"width\": 80, \"height\": 24, \"timestamp\": "
                             "1700000000, \"title\": \"a \\\"quoted\\\" name\"");
    CHECK_STR_CONTAINS(text, "\n[0.500000, \"o\", \"\\u001b[H\\\"\\\\\\u0001\\u007f\xe2\x96\x80 ok\"]\n");
}
