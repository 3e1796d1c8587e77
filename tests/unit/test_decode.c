/* test_decode.c: the ANSI decoder — glyphs, SGR forms, cursor moves, frames, tmux captures,
 * and rejecting what it does not understand with the byte offset. */
#include <stdlib.h>
#include <string.h>

#include "decode.h"
#include "palette.h"
#include "test.h"

#define HALF cell_geom(CELL_HALF)

#define UP "\xe2\x96\x80"
#define LO "\xe2\x96\x84"
#define FULL "\xe2\x96\x88"

static const uint8_t *px(const struct decode_state *d, int x, int y)
{
    return d->rgb + 3 * (y * d->cols + x);
}

static int is_rgb(const uint8_t *p, int r, int g, int b)
{
    return p[0] == r && p[1] == g && p[2] == b;
}

static int dec(struct decode_state *d, const char *s, struct err *e)
{
    return decode_apply(d, s, strlen(s), e);
}

TEST(each_glyph_maps_fg_and_bg_to_the_right_halves)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 4, 1, HALF, NULL) == 0);
    REQUIRE(dec(&d, "\x1b[38;2;1;2;3;48;2;4;5;6m" UP LO FULL " ", &e) == 0);
    CHECK(is_rgb(px(&d, 0, 0), 1, 2, 3) && is_rgb(px(&d, 0, 1), 4, 5, 6)); /* upper */
    CHECK(is_rgb(px(&d, 1, 0), 4, 5, 6) && is_rgb(px(&d, 1, 1), 1, 2, 3)); /* lower */
    CHECK(is_rgb(px(&d, 2, 0), 1, 2, 3) && is_rgb(px(&d, 2, 1), 1, 2, 3)); /* full */
    CHECK(is_rgb(px(&d, 3, 0), 4, 5, 6) && is_rgb(px(&d, 3, 1), 4, 5, 6)); /* space */
    CHECK_EQ_INT(d.used_cols, 4);
    decode_free(&d);
}

TEST(sgr_forms_256_16_defaults_and_reset)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 8, 1, HALF, NULL) == 0);
    /* 38;5 / 48;5, 16 colours (normal and bright), 39/49 defaults, 0 and empty reset */
    REQUIRE(dec(&d, "\x1b[38;5;196;48;5;232m" UP "\x1b[31;104m" UP "\x1b[97;40m" UP
                    "\x1b[39m" UP "\x1b[49m" UP "\x1b[38;5;21m\x1b[0m" UP "\x1b[38;5;21m\x1b[m" UP
                    "\x1b[38;5;21;48;5;22;0m" UP, &e) == 0);
    CHECK(is_rgb(px(&d, 0, 0), 255, 0, 0) && is_rgb(px(&d, 0, 1), 8, 8, 8));
    CHECK(is_rgb(px(&d, 1, 0), 205, 0, 0) && is_rgb(px(&d, 1, 1), 92, 92, 255));
    CHECK(is_rgb(px(&d, 2, 0), 255, 255, 255) && is_rgb(px(&d, 2, 1), 0, 0, 0));
    CHECK(is_rgb(px(&d, 3, 0), 229, 229, 229) && is_rgb(px(&d, 3, 1), 0, 0, 0));
    for (int x = 4; x < 8; x++)
        CHECK(is_rgb(px(&d, x, 0), 229, 229, 229) && is_rgb(px(&d, x, 1), 0, 0, 0));
    decode_free(&d);
}

TEST(cursor_moves_cup_cuf_hpa_cr_lf_and_clamping)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 10, 3, HALF, NULL) == 0);
    REQUIRE(dec(&d, "\x1b[48;2;9;9;9m\x1b[2;4H \x1b[3C \x1b[2G \r \n \x1b[3H \x1b[;10H "
                    "\x1b[99;99H\x1b[C\x1b[G", &e) == 0);
    /* row 1: cols 3, 7 (3 + 1 + 3), 1 (HPA 2), 0 (CR); row 2: col 0 (LF = CR LF) and the
     * CUP to row 3 col 1; row 0: col 9. */
    int want[3][10] = {{0, 0, 0, 0, 0, 0, 0, 0, 0, 1},
                       {1, 1, 0, 1, 0, 0, 0, 1, 0, 0},
                       {1, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 10; c++)
            CHECK_EQ_INT(px(&d, c, 2 * r)[0], want[r][c] ? 9 : 0);
    CHECK_EQ_INT(d.row, 2); /* 99;99 clamped, CUF stays in the last column, G -> col 0 */
    CHECK_EQ_INT(d.col, 0);
    decode_free(&d);
}

TEST(last_column_wraps_pending_and_no_scrolling)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 2, 2, HALF, NULL) == 0);
    REQUIRE(dec(&d, "\x1b[48;2;5;5;5m   ", &e) == 0); /* third cell wraps to row 1 */
    CHECK(px(&d, 0, 2)[0] == 5 && px(&d, 1, 2)[0] == 0);
    REQUIRE(dec(&d, "\x1b[1;2H \r\n", &e) == 0); /* LF clears the pending wrap */
    CHECK_EQ_INT(d.row, 1);
    CHECK_EQ_INT(d.col, 0);
    REQUIRE(dec(&d, "\n\n", &e) == 0); /* parks below the grid: fine until something draws */
    CHECK(dec(&d, " ", &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "below the last row");
    decode_free(&d);
}

TEST(clears_and_private_modes)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 3, 1, HALF, NULL) == 0);
    REQUIRE(dec(&d, "\x1b[?25l\x1b[?2026h\x1b[48;2;1;1;1m\x1b[2J\x1b[?2026l\x1b[?25h", &e) == 0);
    for (int i = 0; i < 6; i++)
        CHECK(is_rgb(d.rgb + 3 * i, 1, 1, 1)); /* ED 2 clears with the current bg */
    REQUIRE(dec(&d, "\x1b[?1049h", &e) == 0);
    CHECK(is_rgb(d.rgb, 0, 0, 0));
    REQUIRE(dec(&d, "\x1b[?1049l\x1b[?25;2026h", &e) == 0);
    decode_free(&d);
}

TEST(ramp_characters_decode_to_their_grey)
{
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, PALETTE_RAMP_LEVELS, 1, HALF, NULL) == 0);
    REQUIRE(dec(&d, PALETTE_RAMP, &e) == 0);
    for (int i = 0; i < PALETTE_RAMP_LEVELS; i++) {
        int g = palette_ramp_grey(i);
        CHECK(is_rgb(px(&d, i, 0), g, g, g) && is_rgb(px(&d, i, 1), g, g, g));
    }
    CHECK_EQ_INT(palette_ramp_grey(PALETTE_RAMP_LEVELS - 1), 255);
    decode_free(&d);
}

TEST(rejects_garbage_naming_the_byte_offset)
{
    static const struct {
        const char *in, *msg;
    } cases[] = {
        {"  X", "byte 2: unexpected byte 'X'"},
        {"\x1b[31mq", "byte 5: unexpected byte 'q'"},
        {" \x01", "byte 1: unexpected byte 0x01"},
        {"\x1b]0;title\x07", "byte 0: unsupported escape sequence ESC ']'"},
        {"  \x1b[1m", "byte 2: unsupported SGR parameter 1"},
        {"\x1b[38;2;1;2m", "byte 0: SGR 38;2/48;2 needs three colour values"},
        {"\x1b[38;2;1;2;300m", "byte 0: SGR colour value above 255"},
        {"\x1b[48;5m", "byte 0: SGR 38;5/48;5 needs a colour index"},
        {"\x1b[38;3;1m", "byte 0: SGR 38/48 must be followed by 2 or 5"},
        {"\x1b[38:2:1:2:3m", "byte 0: unsupported control sequence ending in ':'"},
        {" \x1b[5A", "byte 1: unsupported control sequence ending in 'A'"},
        {"\x1b[J", "byte 0: only ESC[2J"},
        {"\x1b[?7h", "byte 0: unsupported private mode"},
        {"\x1b[?25m", "byte 0: unsupported private sequence ending in 'm'"},
        {"\x1b[1;2;3H", "byte 0: CUP takes at most two parameters"},
        {"\x1b[99999999C", "byte 0: control sequence parameter too large"},
        {"  \x1b[3", "byte 2: control sequence cut short"},
        {"\x1b", "byte 0: escape sequence cut short"},
        {"\xe2\x96", "byte 0: malformed UTF-8"},
        {"\xe2\x96\x81", "byte 0: unsupported character U+2581"},
        {"\xc3\xa9", "byte 0: unsupported character U+00E9"},
        {"\xe2(\x80", "byte 0: malformed UTF-8"},
        {"\xff", "byte 0: unexpected byte 0xff"},
        {" \0", "byte 1: unexpected byte 0x00"},
    };
    struct decode_state d;
    REQUIRE(decode_init(&d, 4, 2, HALF, NULL) == 0);
    d.name = "f.ans";
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct err e = {{0}};
        /* strlen stops at the NUL of " \0": count it for that one case */
        size_t n = strlen(cases[i].in) + (strcmp(cases[i].in, " ") == 0);
        decode_reset(&d);
        CHECK(decode_apply(&d, cases[i].in, n, &e) == -1);
        CHECK_STR_CONTAINS(e.msg, cases[i].msg);
        CHECK(strncmp(e.msg, "f.ans: byte ", 12) == 0);
    }
    decode_free(&d);
}

TEST(frames_split_at_bare_cursor_home)
{
    /* three frames; the middle one is an empty marked diff, the last changes one cell */
    static const char s[] = "\x1b[?1049h\x1b[H\x1b[48;2;1;1;1m  \x1b[0m"
                            "\x1b[H"
                            "\x1b[H\x1b[1;1H\x1b[C\x1b[48;2;2;2;2m \x1b[0m";
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, 2, 1, HALF, NULL) == 0);
    for (int k = 0; k < 3; k++) {
        REQUIRE(decode_frame(&d, s, sizeof s - 1, k, &e) == 0);
        CHECK_EQ_INT(px(&d, 0, 0)[0], 1);
        CHECK_EQ_INT(px(&d, 1, 0)[0], k == 2 ? 2 : 1);
    }
    CHECK(decode_frame(&d, s, sizeof s - 1, 3, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "frame 3 does not exist (3 frames)");
    CHECK(decode_frame(&d, s, sizeof s - 1, -1, &e) == -1);
    int cols, rows, frames;
    REQUIRE(decode_measure(s, sizeof s - 1, "x", false, &cols, &rows, &frames, NULL, &e) == 0);
    CHECK_EQ_INT(cols, 2);
    CHECK_EQ_INT(rows, 1);
    CHECK_EQ_INT(frames, 3);
    /* no ESC[H at all: one frame */
    REQUIRE(decode_frame(&d, "\x1b[48;2;3;3;3m ", 14, 0, &e) == 0);
    CHECK_EQ_INT(px(&d, 0, 0)[0], 3);
    CHECK(decode_frame(&d, " ", 1, 1, &e) == -1);
    decode_free(&d);
}

/* What tmux 3.3a's `capture-pane -e -N -p` printed for ORIGINAL cat into an 8x4 pane
 * (`tmux new-session -d -x 8 -y 4 "cat g.ans; sleep 30"`): tmux re-encodes fg and bg as
 * separate SGRs, uses 39/49, prints never-written cells as spaces, ends lines with LF only
 * and carries colours across lines. */
static const char ORIGINAL[] =
    "\x1b[H\x1b[38;2;10;20;30;48;2;40;50;60m" UP UP "\x1b[48;2;1;2;3m " LO
    "\x1b[38;2;200;100;50m" FULL "\x1b[0m\r\n\x1b[38;5;100;48;5;17m" UP "\x1b[91;104m" UP
    "\x1b[0m @#.\x1b[38;2;9;9;9m" LO "\r\n\x1b[3;3H\x1b[48;2;7;7;7m  \x1b[38;5;196m" FULL "\x1b[0m";
static const char TMUX_CAPTURE[] =
    "\x1b[38;2;10;20;30m\x1b[48;2;40;50;60m" UP UP "\x1b[48;2;1;2;3m " LO
    "\x1b[38;2;200;100;50m" FULL "\n\x1b[38;5;100m\x1b[48;5;17m" UP "\x1b[91m\x1b[104m" UP
    "\x1b[39m\x1b[49m @#.\x1b[38;2;9;9;9m" LO "\n\x1b[39m  \x1b[38;2;9;9;9m\x1b[48;2;7;7;7m  "
    "\x1b[38;5;196m" FULL "\n\n";

TEST(tmux_capture_decodes_like_the_original)
{
    struct decode_state a, b;
    struct err e;
    REQUIRE(decode_init(&a, 8, 4, HALF, NULL) == 0);
    REQUIRE(decode_init(&b, 8, 4, HALF, NULL) == 0);
    REQUIRE(decode_frame(&a, ORIGINAL, sizeof ORIGINAL - 1, 0, &e) == 0);
    REQUIRE(decode_frame(&b, TMUX_CAPTURE, sizeof TMUX_CAPTURE - 1, 0, &e) == 0);
    CHECK(memcmp(a.rgb, b.rgb, 8 * 8 * 3) == 0);
    CHECK(is_rgb(px(&b, 3, 0), 1, 2, 3) && is_rgb(px(&b, 3, 1), 10, 20, 30)); /* U+2584 */
    CHECK(is_rgb(px(&b, 1, 2), 255, 0, 0) && is_rgb(px(&b, 1, 3), 92, 92, 255)); /* 91, 104 */
    CHECK(is_rgb(px(&b, 3, 2), 255, 255, 255) && is_rgb(px(&b, 5, 3), 28, 28, 28)); /* @ . */
    CHECK(is_rgb(px(&b, 0, 4), 0, 0, 0) && is_rgb(px(&b, 2, 4), 7, 7, 7));
    decode_free(&a);
    decode_free(&b);
}

/* issue 25 item 8: a tmux capture of the viewer holds its status line (black on grey) and,
 * while open, the help box (text in a frame of box-drawing characters). With .text, such
 * cells are their background colour and the picture's glyphs around them decode as ever;
 * without it they are errors, as before. */
TEST(text_cells_are_their_background_when_allowed)
{
    const char *cap = "\x1b[38;2;1;2;3;48;2;4;5;6m" UP UP "\n"               /* the picture */
                      "\x1b[30m\x1b[47m a.b \x1b[1;4mq\x1b[0m\n"               /* status line */
                      "\x1b[44m\xe2\x94\x82x\x1b[7m:\x1b[27m" UP "\x1b[0m"; /* help box */
    struct decode_state d;
    struct err e = {""};
    int cols, rows, frames;
    struct cell_geom g;
    CHECK(decode_measure(cap, strlen(cap), "cap", false, &cols, &rows, &frames, &g, &e) != 0);
    CHECK(strstr(e.msg, "unexpected byte 'a'") != NULL);
    REQUIRE(decode_measure(cap, strlen(cap), "cap", true, &cols, &rows, &frames, &g, &e) == 0);
    CHECK_EQ_INT(cols, 6);
    CHECK_EQ_INT(rows, 3);
    REQUIRE(decode_init(&d, cols, rows, HALF, NULL) == 0);
    d.text = true;
    REQUIRE(decode_frame(&d, cap, strlen(cap), 0, &e) == 0);
    CHECK(is_rgb(px(&d, 1, 0), 1, 2, 3) && is_rgb(px(&d, 1, 1), 4, 5, 6)); /* glyphs */
    for (int x = 0; x < 6; x++) /* "a.b q": grey 47 (229), '.' no ramp grey, 'q' bold too */
        CHECK(is_rgb(px(&d, x, 2), 229, 229, 229) && is_rgb(px(&d, x, 3), 229, 229, 229));
    CHECK(is_rgb(px(&d, 0, 4), 0, 0, 238) && is_rgb(px(&d, 1, 5), 0, 0, 238)); /* blue box */
    CHECK(is_rgb(px(&d, 2, 4), 229, 229, 229)); /* reverse: ':' shows the fg as its bg */
    CHECK(is_rgb(px(&d, 3, 4), 229, 229, 229) && is_rgb(px(&d, 3, 5), 0, 0, 238)); /* UP */
    CHECK_EQ_INT(d.text_cells, 7); /* a . b q, the box line, x, : (spaces are cells anyway) */
    decode_free(&d);
}
