/* test_encode.c: half-block encoder — golden bytes, cursor-move choice, diffs, tolerance,
 * colour modes, and the invariant decode(encode(frame)) == frame. */
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "decode.h"
#include "encode.h"
#include "test.h"

#define HALF cell_geom(CELL_HALF)

#define UP "\xe2\x96\x80"
#define LO "\xe2\x96\x84"
#define FULL "\xe2\x96\x88"

static bool contains(const char *hay, size_t n, const char *needle)
{
    size_t m = strlen(needle);
    for (size_t i = 0; i + m <= n; i++)
        if (memcmp(hay + i, needle, m) == 0)
            return true;
    return false;
}

/* Does any SGR in the output set a background (48;..., 40-47, 100-107, 49)? Parameters are
 * walked in order, so a colour channel that happens to be 48 is not taken for one. */
static bool sets_background(const char *out, size_t n)
{
    for (size_t i = 0; i + 1 < n; i++) {
        if (out[i] != '\x1b' || out[i + 1] != '[')
            continue;
        size_t j = i + 2;
        int params[64], np = 0;
        while (j < n && np < 64) {
            int v = 0;
            while (j < n && out[j] >= '0' && out[j] <= '9')
                v = v * 10 + (out[j++] - '0');
            params[np++] = v;
            if (j >= n || out[j] != ';')
                break;
            j++;
        }
        if (j >= n || out[j] != 'm')
            continue;
        for (int k = 0; k < np; k++) {
            int v = params[k];
            if (v == 48 || v == 49 || (v >= 40 && v <= 47) || (v >= 100 && v <= 107))
                return true;
            if (v == 38 && k + 1 < np) /* skip the colour's own parameters */
                k += params[k + 1] == 2 ? 4 : 2;
        }
    }
    return false;
}

static uint32_t rng_next(uint32_t *s) /* xorshift32: deterministic test data */
{
    uint32_t x = *s;
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;
    return *s = x;
}

static void set_px(uint8_t *rgb, int w, int x, int y, uint32_t c)
{
    uint8_t *p = rgb + 3 * (y * w + x);
    p[0] = (uint8_t)(c >> 16);
    p[1] = (uint8_t)(c >> 8);
    p[2] = (uint8_t)c;
}

static const struct encode_opts TRUE_FULL = {.mode = PALETTE_TRUECOLOR};
static const struct encode_opts TRUE_DIFF = {.mode = PALETTE_TRUECOLOR, .diff = true};

/* Encode one frame and compare with golden bytes; prints both escaped on failure. */
static void print_escaped(const char *label, const char *s, size_t n)
{
    fprintf(stderr, "      %s (%zu bytes): \"", label, n);
    for (size_t i = 0; i < n; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == 0x1b)
            fputs("\\e", stderr);
        else if (c < 0x20 || c >= 0x7f)
            fprintf(stderr, "\\x%02x", c);
        else
            fputc(c, stderr);
    }
    fputs("\"\n", stderr);
}

#define CHECK_BYTES(got, n, want)                                                          \
    do {                                                                                   \
        const char *w_ = (want);                                                           \
        if ((n) != strlen(w_) || memcmp((got), w_, (n)) != 0) {                            \
            test_fail(t, __FILE__, __LINE__, "bytes differ from golden");                  \
            print_escaped("got ", (got), (n));                                             \
            print_escaped("want", w_, strlen(w_));                                         \
        }                                                                                  \
    } while (0)

/* Max per-channel difference between the decoded grid and want (w x h); on a mismatch above
 * tol prints a picture: '.' within tol, 'X' beyond. */
static int compare_grid(struct test *t, const struct decode_state *d, const uint8_t *want, int w,
                        int h, int tol, const char *what)
{
    int worst = 0;
    for (int i = 0; i < w * h * 3; i++) {
        int e = abs((int)d->rgb[i] - want[i]);
        if (e > worst)
            worst = e;
    }
    if (worst > tol) {
        test_fail(t, __FILE__, __LINE__, "%s: decoded differs by %d > %d", what, worst, tol);
        for (int y = 0; y < h && y < 40; y++) {
            fputs("      ", stderr);
            for (int x = 0; x < w && x < 100; x++) {
                int e = 0;
                for (int k = 0; k < 3; k++) {
                    int v = abs((int)d->rgb[3 * (y * w + x) + k] - want[3 * (y * w + x) + k]);
                    e = v > e ? v : e;
                }
                fputc(e > tol ? 'X' : '.', stderr);
            }
            fputc('\n', stderr);
        }
    }
    return worst;
}

/* ---- golden bytes: glyph and SGR choice on a 2x2 frame (2 cells) ------------------------ */

/* Truecolor goldens, one row per rule: cells 0 and 1 of a 2x1-cell frame, each given as
 * (top, bottom) pixel colours, and the exact bytes of the full frame. */
static const struct {
    const char *rule;
    uint32_t px[4]; /* cell 0 top, cell 0 bottom, cell 1 top, cell 1 bottom */
    const char *want;
} goldens[] = {
    /* equal pixels: bg + ' '; no colour known yet: U+2580 with fg and bg in one SGR;
     * every frame ends with a reset */
    {"equal pixels emit space, then upper half",
     {0xff0000, 0xff0000, 0x0000ff, 0x00ff00},
     "\x1b[H\x1b[48;2;255;0;0m \x1b[38;2;0;0;255;48;2;0;255;0m" UP "\x1b[0m"},
    /* bg is red after cell 0; red over green: U+2584 needs only fg = green */
    {"lower half saves a colour change",
     {0xff0000, 0xff0000, 0xff0000, 0x00ff00},
     "\x1b[H\x1b[48;2;255;0;0m \x1b[38;2;0;255;0m" LO "\x1b[0m"},
    /* fg is red after cell 0 (red over green); cell 1 all red: a space on a red bg, never
     * U+2588 (xterm and st draw it from the font, and common fonts leave uncovered strips) */
    {"one-colour cell is a space on its bg, never a full block",
     {0xff0000, 0x00ff00, 0xff0000, 0xff0000},
     "\x1b[H\x1b[38;2;255;0;0;48;2;0;255;0m" UP "\x1b[48;2;255;0;0m \x1b[0m"},
    /* identical cells: the second needs no SGR at all */
    {"same colours need no second SGR",
     {0x0a0b0c, 0x010203, 0x0a0b0c, 0x010203},
     "\x1b[H\x1b[38;2;10;11;12;48;2;1;2;3m" UP UP "\x1b[0m"},
};

TEST(golden_truecolor_glyph_and_sgr_choice)
{
    for (unsigned i = 0; i < sizeof goldens / sizeof goldens[0]; i++) {
        uint8_t rgb[2 * 2 * 3];
        for (int k = 0; k < 4; k++)
            set_px(rgb, 2, k / 2, k % 2, goldens[i].px[k]);
        struct encode_screen s;
        REQUIRE(encode_screen_init(&s, 2, 1, NULL) == 0);
        size_t n;
        const char *out = encode_frame(&s, rgb, 2, 2, &TRUE_FULL, &n, NULL);
        if (n != strlen(goldens[i].want) || memcmp(out, goldens[i].want, n) != 0)
            fprintf(stderr, "    rule: %s\n", goldens[i].rule);
        CHECK_BYTES(out, n, goldens[i].want);
        encode_screen_free(&s);
    }
}

TEST(golden_256_16_and_none_modes)
{
    /* Pure red is cube 196 and ANSI 9 (bright red). (0,0,95) is cube 17 but ANSI 0 (black):
     * 95 is nearer 0 than blue's 238. White is cube 231, ANSI 15 (SGR 107 as a bg). */
    uint8_t rgb[12];
    set_px(rgb, 2, 0, 0, 0xff0000);
    set_px(rgb, 2, 0, 1, 0x00005f);
    set_px(rgb, 2, 1, 0, 0xffffff);
    set_px(rgb, 2, 1, 1, 0xffffff);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 2, 1, NULL) == 0);
    size_t n;
    struct encode_opts o = {.mode = PALETTE_256};
    const char *out = encode_frame(&s, rgb, 2, 2, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H\x1b[38;5;196;48;5;17m" UP "\x1b[48;5;231m \x1b[0m");
    o.mode = PALETTE_16;
    out = encode_frame(&s, rgb, 2, 2, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H\x1b[91;40m" UP "\x1b[107m \x1b[0m");
    /* none, half blocks: ink where the luma beats the 8x8 ordered-dither threshold, (2 rank
     * + 1) 255/128: red's 54 beats rank 0's 2 at (0,0), dark blue's 7 not rank 48's 97 at
     * (0,1), white everywhere: U+2580 and U+2588 (ink is the terminal's fg: no SGR) */
    o.mode = PALETTE_NONE;
    out = encode_frame(&s, rgb, 2, 2, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H" UP FULL);
    /* none, ascii (one pixel a cell): a ramp level, luma 9/255 + rank/64 floored: red at
     * (0,0) 1.9 -> '.', white at (1,0) (rank 32) 9.5 -> '@' */
    o.glyphs = CELL_ASCII;
    out = encode_frame(&s, rgb, 2, 1, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H.@");
    encode_screen_free(&s);
}

TEST(unchanged_frame_costs_zero_bytes)
{
    uint8_t rgb[8 * 6 * 3];
    uint32_t seed = 7;
    for (size_t i = 0; i < sizeof rgb; i++)
        rgb[i] = (uint8_t)rng_next(&seed);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 8, 3, NULL) == 0);
    static const enum palette_mode modes[] = {PALETTE_TRUECOLOR, PALETTE_256, PALETTE_16,
                                              PALETTE_NONE};
    for (int m = 0; m < 4; m++) {
        struct encode_opts o = {.mode = modes[m], .diff = true};
        size_t n;
        encode_frame(&s, rgb, 8, 6, &o, &n, NULL);
        CHECK(n > 0);
        encode_frame(&s, rgb, 8, 6, &o, &n, NULL);
        CHECK_EQ_INT(n, 0);
        o.mark_frames = true;
        const char *out = encode_frame(&s, rgb, 8, 6, &o, &n, NULL);
        CHECK_BYTES(out, n, "\x1b[H");
    }
    encode_screen_free(&s);
}

/* ---- cursor moves ---------------------------------------------------------------------- */

/* A 40x3-cell black screen, already drawn; then a diff with the given cells turned white. */
static const char *diff_with_white_cells(struct encode_screen *s, uint8_t *rgb,
                                         const int (*cells)[2], int n_cells, size_t *n)
{
    memset(rgb, 0, 40 * 6 * 3);
    encode_frame(s, rgb, 40, 6, &TRUE_FULL, n, NULL);
    for (int i = 0; i < n_cells; i++) {
        set_px(rgb, 40, cells[i][1], 2 * cells[i][0], 0xffffff);
        set_px(rgb, 40, cells[i][1], 2 * cells[i][0] + 1, 0xffffff);
    }
    return encode_frame(s, rgb, 40, 6, &TRUE_DIFF, n, NULL);
}

#define W "\x1b[48;2;255;255;255m"

TEST(cursor_move_picks_the_shortest)
{
    static uint8_t rgb[40 * 6 * 3];
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 40, 3, NULL) == 0);
    size_t n;
    const char *out;
    /* Unknown cursor: CUP, 1-based, column omitted when it is 1. */
    static const int a[][2] = {{0, 5}};
    out = diff_with_white_cells(&s, rgb, a, 1, &n);
    CHECK_BYTES(out, n, "\x1b[1;6H" W " \x1b[0m");
    static const int b[][2] = {{1, 0}};
    out = diff_with_white_cells(&s, rgb, b, 1, &n);
    CHECK_BYTES(out, n, "\x1b[2H" W " \x1b[0m");
    /* A one-cell gap that is black while the bg is white: rewriting it would need an SGR,
     * so ESC[C (skipped_cells_are_rewritten_when_cheaper covers the other case). */
    static const int c[][2] = {{0, 5}, {0, 7}};
    out = diff_with_white_cells(&s, rgb, c, 2, &n);
    CHECK_BYTES(out, n, "\x1b[1;6H" W " \x1b[C \x1b[0m");
    /* CUF with a count beats HPA (ESC[6C vs ESC[13G). */
    static const int d[][2] = {{0, 5}, {0, 12}};
    out = diff_with_white_cells(&s, rgb, d, 2, &n);
    CHECK_BYTES(out, n, "\x1b[1;6H" W " \x1b[6C \x1b[0m");
    /* Next row, column 0: CR LF (2 bytes) beats ESC[2H (4). */
    static const int e[][2] = {{0, 3}, {1, 0}};
    out = diff_with_white_cells(&s, rgb, e, 2, &n);
    CHECK_BYTES(out, n, "\x1b[1;4H" W " \r\n \x1b[0m");
    /* After the last column the column is unknown: CR LF + ESC[9C (6) beats ESC[2;10H (7). */
    static const int f[][2] = {{0, 39}, {1, 9}};
    out = diff_with_white_cells(&s, rgb, f, 2, &n);
    CHECK_BYTES(out, n, "\x1b[1;40H" W " \r\n\x1b[9C \x1b[0m");
    /* Two rows down and far right: CUP (ESC[3;31H, 7) beats CR LF CR LF ESC[30C (9). */
    static const int g[][2] = {{0, 0}, {2, 30}};
    out = diff_with_white_cells(&s, rgb, g, 2, &n);
    CHECK_BYTES(out, n, "\x1b[H" W " \x1b[3;31H \x1b[0m");
    encode_screen_free(&s);
}

TEST(skipped_cells_are_rewritten_when_cheaper)
{
    /* Row of white cells with two black ones at 2 and 5; both turn grey. Between them cells
     * 3 and 4 are white, and after the first grey cell the bg is grey: rewriting needs an
     * SGR, so CUF. Now make 3..4 grey already: rewriting them costs 2 spaces < ESC[2C. */
    static uint8_t rgb[10 * 2 * 3];
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 10, 1, NULL) == 0);
    for (int x = 0; x < 10; x++)
        for (int y = 0; y < 2; y++)
            set_px(rgb, 10, x, y, x == 2 || x == 5 ? 0x000000 : x == 3 || x == 4 ? 0x808080 : 0xffffff);
    size_t n;
    encode_frame(&s, rgb, 10, 2, &TRUE_FULL, &n, NULL);
    for (int y = 0; y < 2; y++) {
        set_px(rgb, 10, 2, y, 0x808080);
        set_px(rgb, 10, 5, y, 0x808080);
    }
    struct encode_stats st;
    const char *out = encode_frame(&s, rgb, 10, 2, &TRUE_DIFF, &n, &st);
    CHECK_BYTES(out, n, "\x1b[1;3H\x1b[48;2;128;128;128m    \x1b[0m");
    CHECK_EQ_INT(st.cells_drawn, 2);
    CHECK_EQ_INT(st.cells_rewritten, 2);
    encode_screen_free(&s);
}

/* ---- round trips ------------------------------------------------------------------------ */

static void random_frame(uint8_t *rgb, int w, int h, uint32_t *seed, int levels)
{
    for (int i = 0; i < w * h * 3; i++)
        rgb[i] = (uint8_t)(rng_next(seed) % (unsigned)levels * (255 / (levels - 1)));
}

/* Background gradient + n rectangles that move with frame number f. */
static void rect_frame(uint8_t *rgb, int w, int h, int f, uint32_t seed)
{
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++)
            set_px(rgb, w, x, y, (uint32_t)(x * 255 / w) << 16 | (uint32_t)(y * 255 / h) << 8 | 40);
    for (int k = 0; k < 6; k++) {
        uint32_t col = rng_next(&seed) & 0xffffff;
        int rw = 3 + (int)(rng_next(&seed) % 15), rh = 2 + (int)(rng_next(&seed) % 11);
        int x0 = (int)(rng_next(&seed) % (unsigned)w), y0 = (int)(rng_next(&seed) % (unsigned)h);
        int vx = (int)(rng_next(&seed) % 5) - 2, vy = (int)(rng_next(&seed) % 3) - 1;
        x0 = ((x0 + vx * f) % w + w) % w;
        y0 = ((y0 + vy * f) % h + h) % h;
        for (int y = y0; y < y0 + rh && y < h; y++)
            for (int x = x0; x < x0 + rw && x < w; x++)
                set_px(rgb, w, x, y, col);
    }
}

TEST(truecolor_full_frames_decode_exactly)
{
    enum { C = 37, R = 11 };
    static uint8_t rgb[C * 2 * R * 3];
    struct encode_screen s;
    struct decode_state d;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
    uint32_t seed = 12345;
    for (int it = 0; it < 20; it++) {
        if (it % 2)
            random_frame(rgb, C, 2 * R, &seed, it % 4 == 1 ? 2 : 256);
        else
            rect_frame(rgb, C, 2 * R, it, seed);
        size_t n;
        const char *out = encode_frame(&s, rgb, C, 2 * R, &TRUE_FULL, &n, NULL);
        CHECK(n <= ENCODE_BOUND(C, R));
        struct err e;
        e.msg[0] = 0;
        CHECK(decode_frame(&d, out, n, 0, &e) == 0);
        CHECK_EQ_INT(d.used_cols, C);
        CHECK_EQ_INT(d.used_rows, R);
        compare_grid(t, &d, rgb, C, 2 * R, 0, "full frame");
    }
    encode_screen_free(&s);
    decode_free(&d);
}

TEST(truecolor_diff_chain_of_50_decodes_exactly)
{
    /* Frames are concatenated (mark_frames) the way `dump --diff` writes them; every frame
     * is checked both by decoding the stream's frame k and by applying the bytes in turn. */
    enum { C = 48, R = 15, N = 50 };
    static uint8_t rgb[N][C * 2 * R * 3];
    struct encode_screen s;
    struct decode_state inc, byk;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    REQUIRE(decode_init(&inc, C, R, HALF, NULL) == 0);
    REQUIRE(decode_init(&byk, C, R, HALF, NULL) == 0);
    size_t cap = 0, len = 0;
    char *stream = NULL;
    struct encode_opts o = TRUE_DIFF;
    o.mark_frames = true;
    for (int f = 0; f < N; f++) {
        rect_frame(rgb[f], C, 2 * R, f, 99);
        if (f % 17 == 16) { /* an occasional burst of noise in a corner */
            uint32_t seed = (uint32_t)f + 1;
            for (int y = 0; y < 6; y++)
                for (int x = 0; x < 6; x++)
                    set_px(rgb[f], C, x, y, rng_next(&seed) & 0xffffff);
        }
        size_t n;
        const char *out = encode_frame(&s, rgb[f], C, 2 * R, &o, &n, NULL);
        struct err e;
        REQUIRE(decode_apply(&inc, out, n, &e) == 0);
        compare_grid(t, &inc, rgb[f], C, 2 * R, 0, "incremental diff");
        if (len + n > cap) {
            cap = (len + n) * 2;
            stream = realloc(stream, cap);
            REQUIRE(stream);
        }
        memcpy(stream + len, out, n);
        len += n;
    }
    for (int f = 0; f < N; f++) {
        struct err e;
        REQUIRE(decode_frame(&byk, stream, len, f, &e) == 0);
        compare_grid(t, &byk, rgb[f], C, 2 * R, 0, "frame k of the stream");
    }
    struct err e;
    CHECK(decode_frame(&byk, stream, len, N, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "does not exist (50 frames)");
    free(stream);
    encode_screen_free(&s);
    decode_free(&inc);
    decode_free(&byk);
}

/* Reference quantisation for a palette mode, pixel by pixel. */
static void quantise_ref(const uint8_t *in, uint8_t *out, int n, enum palette_mode mode)
{
    for (int i = 0; i < n; i++)
        palette_rgb(mode == PALETTE_256 ? palette_nearest_256(in + 3 * i)
                                         : palette_nearest_16(in + 3 * i),
                    out + 3 * i);
}

TEST(palette_modes_decode_to_the_quantised_frame_within_the_bound)
{
    enum { C = 40, R = 12 };
    static uint8_t rgb[C * 2 * R * 3], q[C * 2 * R * 3];
    struct encode_screen s;
    struct decode_state d;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
    static const enum palette_mode modes[] = {PALETTE_256, PALETTE_16};
    static const int bound[] = {PALETTE_256_MAX_ERR, PALETTE_16_MAX_ERR};
    for (int m = 0; m < 2; m++) {
        struct encode_opts o = {.mode = modes[m], .diff = true};
        for (int f = 0; f < 30; f++) {
            uint32_t seed = (uint32_t)(f + 1);
            if (f % 3 == 2)
                random_frame(rgb, C, 2 * R, &seed, 256);
            else
                rect_frame(rgb, C, 2 * R, f, 5);
            size_t n;
            const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
            struct err e;
            REQUIRE(decode_apply(&d, out, n, &e) == 0);
            quantise_ref(rgb, q, C * 2 * R, modes[m]);
            compare_grid(t, &d, q, C, 2 * R, 0, "decoded == quantised");
            compare_grid(t, &d, rgb, C, 2 * R, bound[m], "decoded ~ true");
        }
    }
    /* Switching modes back and forth must not reuse stale quantisations (the per-pixel memo). */
    static const enum palette_mode seq[] = {PALETTE_256, PALETTE_TRUECOLOR, PALETTE_256,
                                            PALETTE_16, PALETTE_256};
    for (int i = 0; i < 5; i++) {
        struct encode_opts o = {.mode = seq[i], .diff = true};
        uint32_t seed = 1000 + (uint32_t)(i / 2); /* pairs of equal frames */
        random_frame(rgb, C, 2 * R, &seed, 256);
        size_t n;
        const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
        struct err e;
        REQUIRE(decode_apply(&d, out, n, &e) == 0);
        if (seq[i] == PALETTE_TRUECOLOR)
            memcpy(q, rgb, sizeof q);
        else
            quantise_ref(rgb, q, C * 2 * R, seq[i]);
        compare_grid(t, &d, q, C, 2 * R, 0, "after a mode switch");
    }
    /* Dithering stays within the bound of a colour up to PALETTE_DITHER_AMP away. */
    struct encode_opts o = {.mode = PALETTE_256, .dither = true};
    uint32_t seed = 77;
    random_frame(rgb, C, 2 * R, &seed, 256);
    size_t n;
    const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
    struct err e;
    REQUIRE(decode_frame(&d, out, n, 0, &e) == 0);
    compare_grid(t, &d, rgb, C, 2 * R, PALETTE_256_MAX_ERR + PALETTE_DITHER_AMP, "dithered");
    encode_screen_free(&s);
    decode_free(&d);
}

/* The 8x8 ordered-dither rank of pixel (x, y), built the textbook way: M(2n) from M(n) as
 * [4M 4M+2; 4M+3 4M+1] (the encoder computes it from bits). */
static int bayer_ref(int x, int y)
{
    int m[8][8] = {{0}};
    for (int n = 1; n < 8; n *= 2)
        for (int j = n - 1; j >= 0; j--)
            for (int i = n - 1; i >= 0; i--) {
                int v = 4 * m[j][i];
                m[j][i] = v, m[j][i + n] = v + 2, m[j + n][i] = v + 3, m[j + n][i + n] = v + 1;
            }
    return m[y & 7][x & 7];
}

TEST(none_mode_dithers_ink_onto_glyphs_and_the_ramp_for_ascii)
{
    enum { C = 30, R = 7 };
    static uint8_t rgb[C * 2 * R * 4 * 3], want[C * 2 * R * 4 * 3];
    static const enum cell_glyphs sets[] = {CELL_HALF, CELL_QUADRANT, CELL_SEXTANT, CELL_BRAILLE,
                                            CELL_ASCII};
    for (unsigned k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        struct cell_geom g = cell_geom(sets[k]);
        int w = C * g.px_w, h = R * g.px_h;
        uint32_t seed = 4242 + k;
        random_frame(rgb, w, h, &seed, 256);
        for (int y = 0; y < h; y++)
            for (int x = 0; x < w; x++) {
                int l = palette_luma(rgb + 3 * (y * w + x)), rank = bayer_ref(x, y);
                uint8_t v;
                if (sets[k] == CELL_ASCII) { /* the ramp level: l 9/255 + (rank + 1/2)/64, floored */
                    int level = (int)(l * 9.0 / 255 + (rank + 0.5) / 64);
                    v = palette_ramp_grey(level > 9 ? 9 : level);
                } else { /* ink (the decoder's default fg) where l/255 > (rank + 1/2)/64 */
                    v = l / 255.0 > (rank + 0.5) / 64 ? 229 : 0;
                }
                memset(want + 3 * (y * w + x), v, 3);
            }
        struct encode_screen s;
        struct decode_state d;
        REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
        REQUIRE(decode_init(&d, C, R, g, NULL) == 0);
        struct encode_opts o = {.mode = PALETTE_NONE, .glyphs = sets[k]};
        size_t n;
        const char *out = encode_frame(&s, rgb, w, h, &o, &n, NULL);
        for (size_t i = 0; i < n; i++) /* only cursor positioning may be escaped */
            if (out[i] == 0x1b)
                CHECK(out[i + 1] == '[' && (out[i + 2] == 'H' || (out[i + 2] >= '0' && out[i + 2] <= '9')));
        CHECK(!contains(out, n, "m"));
        struct err e;
        REQUIRE(decode_frame(&d, out, n, 0, &e) == 0);
        compare_grid(t, &d, want, w, h, 0, cell_glyphs_name(sets[k]));
        encode_screen_free(&s);
        decode_free(&d);
    }
}

/* ---- tolerance -------------------------------------------------------------------------- */

TEST(tolerance_never_lets_the_screen_drift_beyond_n)
{
    /* Every pixel drifts by +1 per channel per frame (slow fades): comparing with the previous
     * FRAME would skip every change forever and drift without limit; comparing with what the
     * screen shows must redraw a cell once it is N away. */
    enum { C = 32, R = 8, N = 120 };
    static uint8_t rgb[C * 2 * R * 3], base[C * 2 * R * 3];
    uint32_t seed = 31337;
    random_frame(base, C, 2 * R, &seed, 100); /* values 0..198: room to drift */
    static const int tols[] = {1, 4, 9};
    for (int ti = 0; ti < 3; ti++) {
        int tol = tols[ti];
        struct encode_screen s;
        struct decode_state d;
        REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
        REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
        struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .diff = true, .tolerance = tol};
        size_t total = 0, total_exact = 0;
        struct encode_screen exact;
        REQUIRE(encode_screen_init(&exact, C, R, NULL) == 0);
        int worst = 0;
        for (int f = 0; f < N; f++) {
            for (int i = 0; i < C * 2 * R * 3; i++) {
                /* slow drift: each channel moves by one every (1 + i % 3) frames, some down */
                int step = f / (1 + i % 3), v = base[i] + ((i / 3) % 2 ? step / 2 : -step / 3);
                rgb[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
            }
            size_t n;
            const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
            total += n;
            struct err e;
            REQUIRE(decode_apply(&d, out, n, &e) == 0);
            int w = compare_grid(t, &d, rgb, C, 2 * R, tol, "tolerance");
            worst = w > worst ? w : worst;
            encode_frame(&exact, rgb, C, 2 * R, &TRUE_DIFF, &n, NULL);
            total_exact += n;
        }
        CHECK(worst <= tol);
        CHECK(worst == tol); /* the drift really reached the tolerance */
        CHECK(total < total_exact); /* and the tolerance saved bytes */
        encode_screen_free(&s);
        encode_screen_free(&exact);
        decode_free(&d);
    }
}

TEST(tolerance_redraws_reuse_current_colours_within_n)
{
    /* Both cells change; cell 1's pixels are within 3 of cell 0's colours, so with tolerance 3
     * cell 1 is drawn with the current fg/bg (no second SGR) and the screen model records
     * what is really shown: a later frame equal to the truth changes nothing. */
    uint8_t rgb[12] = {0};
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 2, 1, NULL) == 0);
    size_t n;
    encode_frame(&s, rgb, 2, 2, &TRUE_FULL, &n, NULL);
    set_px(rgb, 2, 0, 0, 0x646464);
    set_px(rgb, 2, 0, 1, 0x323232);
    set_px(rgb, 2, 1, 0, 0x666364);
    set_px(rgb, 2, 1, 1, 0x333234);
    struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .diff = true, .tolerance = 3};
    const char *out = encode_frame(&s, rgb, 2, 2, &o, &n, NULL);
    CHECK_BYTES(out, n, "[H[38;2;100;100;100;48;2;50;50;50m" UP UP "[0m");
    CHECK_EQ_INT(s.cells[1].top, 0x646464);
    CHECK_EQ_INT(s.cells[1].bot, 0x323232);
    encode_frame(&s, rgb, 2, 2, &o, &n, NULL);
    CHECK_EQ_INT(n, 0);
    /* the same frame without tolerance redraws cell 1 exactly */
    out = encode_frame(&s, rgb, 2, 2, &TRUE_DIFF, &n, NULL);
    CHECK_BYTES(out, n, "[1;2H[38;2;102;99;100;48;2;51;50;52m" UP "[0m");
    encode_screen_free(&s);
}

TEST(tolerance_in_256_mode_is_bounded_by_the_palette_or_n)
{
    enum { C = 24, R = 6, N = 60, TOL = 6 };
    static uint8_t rgb[C * 2 * R * 3];
    struct encode_screen s;
    struct decode_state d;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
    struct encode_opts o = {.mode = PALETTE_256, .diff = true, .tolerance = TOL};
    for (int f = 0; f < N; f++) {
        for (int i = 0; i < C * 2 * R * 3; i++)
            rgb[i] = (uint8_t)((i * 37 + f * 2) & 255);
        size_t n;
        const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
        struct err e;
        REQUIRE(decode_apply(&d, out, n, &e) == 0);
        compare_grid(t, &d, rgb, C, 2 * R, PALETTE_256_MAX_ERR, "256 + tolerance");
    }
    encode_screen_free(&s);
    decode_free(&d);
}

/* ---- frame structure -------------------------------------------------------------------- */

TEST(large_frames_use_synchronized_output_small_ones_do_not)
{
    enum { C = 80, R = 24 };
    static uint8_t rgb[C * 2 * R * 3];
    uint32_t seed = 3;
    random_frame(rgb, C, 2 * R, &seed, 256);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    size_t n;
    struct encode_stats st;
    const char *out = encode_frame(&s, rgb, C, 2 * R, &TRUE_DIFF, &n, &st);
    CHECK(st.full && st.synced);
    CHECK(n > 11 && memcmp(out, "\x1b[H\x1b[?2026h", 11) == 0);
    CHECK(n > 12 && memcmp(out + n - 12, "\x1b[0m\x1b[?2026l", 12) == 0);
    CHECK(n <= ENCODE_BOUND(C, R));
    set_px(rgb, C, 3, 3, 0x123456);
    out = encode_frame(&s, rgb, C, 2 * R, &TRUE_DIFF, &n, &st);
    CHECK(!st.full && !st.synced && st.cells_drawn == 1);
    CHECK(n < 60 && !contains(out, n, "2026"));
    encode_screen_free(&s);
}

TEST(worst_case_frame_fits_the_documented_bound)
{
    /* Every cell needs a CUP-free but both-colours SGR with 3-digit channels and a 3-byte
     * glyph: alternating distinct colours. Measure the per-cell cost against the bound. */
    enum { C = 50, R = 20 };
    static uint8_t rgb[C * 2 * R * 3];
    for (int y = 0; y < 2 * R; y++)
        for (int x = 0; x < C; x++)
            set_px(rgb, C, x, y, 0xc8c8c8 + (uint32_t)((x + y * 7) % 50) * 0x010101);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    size_t n;
    struct encode_stats st;
    encode_frame(&s, rgb, C, 2 * R, &TRUE_FULL, &n, &st);
    CHECK_EQ_INT(st.sgr, C * R);
    CHECK(n <= ENCODE_BOUND(C, R));
    CHECK(n >= (size_t)C * R * 39); /* 36-byte SGR + 3-byte glyph in every cell */
    encode_screen_free(&s);
}

TEST(odd_height_pads_the_last_bottom_half)
{
    uint8_t rgb[3 * 3 * 3];
    for (int i = 0; i < 27; i++)
        rgb[i] = (uint8_t)(i * 9);
    struct encode_screen s;
    struct decode_state d;
    REQUIRE(encode_screen_init(&s, 3, 2, NULL) == 0);
    REQUIRE(decode_init(&d, 3, 2, HALF, NULL) == 0);
    struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .pad_rgb = {7, 8, 9}};
    size_t n;
    const char *out = encode_frame(&s, rgb, 3, 3, &o, &n, NULL);
    struct err e;
    REQUIRE(decode_frame(&d, out, n, 0, &e) == 0);
    CHECK(memcmp(d.rgb, rgb, 27) == 0);
    for (int x = 0; x < 3; x++)
        CHECK(d.rgb[27 + 3 * x] == 7 && d.rgb[28 + 3 * x] == 8 && d.rgb[29 + 3 * x] == 9);
    encode_screen_free(&s);
    decode_free(&d);
}

TEST(damage_invalidate_and_mode_change_force_redraws)
{
    enum { C = 10, R = 4 };
    static uint8_t rgb[C * 2 * R * 3];
    uint32_t seed = 9;
    random_frame(rgb, C, 2 * R, &seed, 256);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    size_t n;
    struct encode_stats st;
    encode_frame(&s, rgb, C, 2 * R, &TRUE_DIFF, &n, &st);
    CHECK(st.full); /* unknown screen */
    encode_screen_damage(&s, 8, 2, 5, 5); /* clipped to the 2x2 cells in the corner */
    encode_frame(&s, rgb, C, 2 * R, &TRUE_DIFF, &n, &st);
    CHECK(!st.full);
    CHECK_EQ_INT(st.cells_drawn, 4);
    encode_screen_invalidate(&s);
    encode_frame(&s, rgb, C, 2 * R, &TRUE_DIFF, &n, &st);
    CHECK(st.full);
    CHECK_EQ_INT(st.cells_drawn, C * R);
    struct encode_opts o = {.mode = PALETTE_256, .diff = true};
    encode_frame(&s, rgb, C, 2 * R, &o, &n, &st);
    CHECK(st.full);
    encode_screen_free(&s);
    struct err e;
    CHECK(encode_screen_init(&s, 0, 5, &e) == -1);
    CHECK_STR_CONTAINS(e.msg, "out of range");
}

TEST(one_colour_cells_are_spaces_never_full_blocks)
{
    /* Frames of few colours (many cells with equal halves, many fg/bg coincidences), as full
     * frames, diffs and with tolerance, in every colour mode: U+2588 never appears, and every
     * cell whose halves show one colour was drawn as a space. */
    enum { C = 16, R = 6 };
    static uint8_t rgb[C * 2 * R * 3];
    static const uint32_t ink[] = {0xff0000, 0x00ff00, 0x202020, 0xff0101};
    static const enum palette_mode modes[] = {PALETTE_TRUECOLOR, PALETTE_256, PALETTE_16};
    uint32_t seed = 99;
    int spaces = 0;
    for (int m = 0; m < 3; m++)
        for (int tol = 0; tol <= 4; tol += 4) {
            struct encode_screen s;
            REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
            for (int f = 0; f < 20; f++) {
                for (int y = 0; y < 2 * R; y++)
                    for (int x = 0; x < C; x++)
                        set_px(rgb, C, x, y, ink[rng_next(&seed) % 4]);
                struct encode_opts o = {.mode = modes[m], .diff = f > 0, .tolerance = tol};
                size_t n;
                const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
                CHECK(!contains(out, n, FULL));
                for (size_t i = 0; i < n; i++)
                    spaces += out[i] == ' ';
            }
            encode_screen_free(&s);
        }
    CHECK(spaces > 100);
}

/* sum of squared channel errors of the decoded grid against the frame */
static double grid_sq_err(const struct decode_state *d, const uint8_t *want, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++) {
        double e = (double)d->rgb[i] - want[i];
        s += e * e;
    }
    return s;
}

TEST(budgeted_frames_fit_and_a_still_picture_converges_to_exact)
{
    /* A smooth picture with detail, shifted every frame (a pan), then held still. Every
     * budgeted frame fits its budget; the decoded screen always equals the screen model's
     * story (the next unbudgeted diff of the truth repairs exactly the pending cells); once
     * the picture stops, the error falls every frame and reaches zero. */
    enum { C = 40, R = 12, B = 1500 };
    static uint8_t rgb[C * 2 * R * 3];
    static const enum palette_mode modes[] = {PALETTE_TRUECOLOR, PALETTE_256};
    for (int m = 0; m < 2; m++) {
        struct encode_screen s;
        struct decode_state d;
        REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
        REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
        struct encode_opts o = {.mode = modes[m], .diff = true, .budget = B};
        double prev = 1e300;
        int still_frames = 0, limited = 0;
        for (int f = 0; f < 60; f++) {
            int shift = f < 20 ? 3 * f : 60;
            for (int y = 0; y < 2 * R; y++)
                for (int x = 0; x < C; x++) {
                    int u = x + shift;
                    set_px(rgb, C, x, y,
                           (uint32_t)((u * 6) & 255) << 16 | (uint32_t)(y * 10) << 8 |
                               (uint32_t)(((u / 4 + y / 3) % 2) * 200));
                }
            size_t n;
            struct encode_stats st;
            const char *out = encode_frame(&s, rgb, C, 2 * R, &o, &n, &st);
            CHECK(n <= B);
            limited += st.demand > B;
            struct err e;
            REQUIRE(decode_apply(&d, out, n, &e) == 0);
            double err = grid_sq_err(&d, rgb, C * 2 * R * 3);
            if (f >= 20) { /* still: strictly better until exact (palette: until quantised) */
                if (st.cells_pending == 0) {
                    still_frames = f - 19;
                    break;
                }
                CHECK(err < prev);
                prev = err;
            }
        }
        CHECK(limited >= 19); /* the pan really was over budget */
        CHECK(still_frames > 1 && still_frames < 30);
        /* converged: an unbudgeted diff has nothing left to send */
        size_t n;
        struct encode_opts exact = {.mode = modes[m], .diff = true};
        encode_frame(&s, rgb, C, 2 * R, &exact, &n, NULL);
        CHECK_EQ_INT(n, 0);
        if (modes[m] == PALETTE_TRUECOLOR)
            CHECK(grid_sq_err(&d, rgb, C * 2 * R * 3) == 0);
        encode_screen_free(&s);
        decode_free(&d);
    }
}

/* A budgeted still picture in 256 colours whose last changes are cells that show, as they are,
 * as little error as their targets would (approximations an earlier frame drew, the palette's
 * rounding): no price draws them, yet together they pass the budget. They must still be
 * drawn, a budget's worth a frame, until nothing is pending: before, every frame drew
 * nothing and left them pending for ever (the viewer then redrew a still picture at its
 * full frame rate without end). 80x24 grey noise, panned for 20 frames then held. */
TEST(a_budgeted_still_picture_never_stops_short_of_exact)
{
    enum { C = 80, R = 24, B = 1500 };
    static uint8_t rgb[C * 2 * R * 3];
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    struct encode_opts o = {.mode = PALETTE_256, .diff = true, .budget = B};
    int converged = -1, stuck = 0;
    for (int f = 0; f < 400 && converged < 0; f++) {
        int shift = f < 20 ? 3 * f : 60;
        for (int y = 0; y < 2 * R; y++)
            for (int x = 0; x < C; x++) {
                unsigned u = (unsigned)(x + shift), h = u * 73856093u ^ (unsigned)y * 19349663u;
                h ^= h >> 13;
                h *= 0x5bd1e995u;
                h ^= h >> 15;
                set_px(rgb, C, x, y, (h & 0xff) * 0x010101u + ((u * 3) & 0x3f));
            }
        size_t n;
        struct encode_stats st;
        encode_frame(&s, rgb, C, 2 * R, &o, &n, &st);
        CHECK(n <= B);
        if (f >= 20 && st.cells_pending == 0)
            converged = f - 19;
        stuck += f >= 20 && st.cells_pending > 0 && st.cells_drawn == 0;
    }
    CHECK_EQ_INT(stuck, 0);
    CHECK(converged > 0);
    /* and the screen is the picture's targets: an unbudgeted diff has nothing to send */
    size_t n;
    struct encode_opts exact = {.mode = PALETTE_256, .diff = true};
    encode_frame(&s, rgb, C, 2 * R, &exact, &n, NULL);
    CHECK_EQ_INT(n, 0);
    if (t->failures)
        fprintf(stderr, "    converged after %d still frames; %d frames drew nothing\n", converged,
                stuck);
    encode_screen_free(&s);
}

TEST(a_budget_the_frame_fits_changes_nothing)
{
    enum { C = 20, R = 6 };
    static uint8_t rgb[C * 2 * R * 3];
    uint32_t seed = 5;
    struct encode_screen a, b;
    REQUIRE(encode_screen_init(&a, C, R, NULL) == 0);
    REQUIRE(encode_screen_init(&b, C, R, NULL) == 0);
    for (int f = 0; f < 5; f++) {
        random_frame(rgb, C, 2 * R, &seed, f % 2 ? 4 : 256);
        struct encode_opts plain = {.mode = PALETTE_TRUECOLOR, .diff = true, .tolerance = 2};
        struct encode_opts big = plain;
        big.budget = ENCODE_BOUND(C, R);
        size_t na, nb;
        const char *pa = encode_frame(&a, rgb, C, 2 * R, &plain, &na, NULL);
        struct encode_stats st;
        const char *pb = encode_frame(&b, rgb, C, 2 * R, &big, &nb, &st);
        CHECK(na == nb && memcmp(pa, pb, na) == 0);
        CHECK(st.lambda == 0 && st.demand == nb && st.cells_pending == 0);
    }
    encode_screen_free(&a);
    encode_screen_free(&b);
}

TEST(rate_distortion_beats_a_fixed_tolerance_at_equal_bytes)
{
    /* A noisy gradient panned by one pixel a frame: the budgeted encoder, given the bytes a
     * fixed tolerance spends, leaves a smaller error (the rule the viewer relies on). */
    enum { C = 48, R = 12, N = 30 };
    static uint8_t rgb[C * 2 * R * 3];
    struct encode_screen tol_s, rd_s;
    struct decode_state tol_d, rd_d;
    REQUIRE(encode_screen_init(&tol_s, C, R, NULL) == 0);
    REQUIRE(encode_screen_init(&rd_s, C, R, NULL) == 0);
    REQUIRE(decode_init(&tol_d, C, R, HALF, NULL) == 0);
    REQUIRE(decode_init(&rd_d, C, R, HALF, NULL) == 0);
    double e_tol = 0, e_rd = 0;
    size_t b_tol = 0, b_rd = 0;
    for (int f = 0; f < N; f++) {
        uint32_t seed = 1;
        for (int y = 0; y < 2 * R; y++)
            for (int x = 0; x < C; x++) {
                int u = x + f;
                uint32_t noise = rng_next(&seed) % 24;
                set_px(rgb, C, x, y, (uint32_t)((u * 5 + noise) & 255) << 16 |
                                         (uint32_t)(y * 9 + noise) << 8 | (uint32_t)(u * 3 & 255));
            }
        struct encode_opts ot = {.mode = PALETTE_TRUECOLOR, .diff = true, .tolerance = 12};
        size_t n;
        struct err e;
        const char *out = encode_frame(&tol_s, rgb, C, 2 * R, &ot, &n, NULL);
        REQUIRE(decode_apply(&tol_d, out, n, &e) == 0);
        b_tol += n;
        struct encode_opts orr = {.mode = PALETTE_TRUECOLOR, .diff = true, .budget = n ? n : 1};
        out = encode_frame(&rd_s, rgb, C, 2 * R, &orr, &n, NULL);
        REQUIRE(decode_apply(&rd_d, out, n, &e) == 0);
        b_rd += n;
        if (f > 0) {
            e_tol += grid_sq_err(&tol_d, rgb, C * 2 * R * 3);
            e_rd += grid_sq_err(&rd_d, rgb, C * 2 * R * 3);
        }
    }
    CHECK(b_rd <= b_tol);
    CHECK(e_rd < 0.9 * e_tol);
    if (t->failures)
        fprintf(stderr, "    tolerance 12: %zu bytes, sq err %.0f; budgeted: %zu bytes, "
                        "sq err %.0f\n", b_tol, e_tol, b_rd, e_rd);
    encode_screen_free(&tol_s);
    encode_screen_free(&rd_s);
    decode_free(&tol_d);
    decode_free(&rd_d);
}

TEST(held_cells_are_never_written)
{
    /* Cells 3..5 of row 1 are held (an overlay drawn by someone else: ramp '@' here). The
     * frame changes every cell; the cells around the hold have the colours a rewrite would
     * reuse, yet nothing lands in the hold, with or without a budget. */
    enum { C = 10, R = 3 };
    static uint8_t rgb[C * 2 * R * 3];
    for (int budget = 0; budget <= 400; budget += 400) {
        struct encode_screen s;
        struct decode_state d;
        REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
        REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
        memset(rgb, 0, sizeof rgb);
        size_t n;
        struct err e;
        const char *out = encode_frame(&s, rgb, C, 2 * R, &TRUE_FULL, &n, NULL);
        REQUIRE(decode_apply(&d, out, n, &e) == 0);
        REQUIRE(decode_apply(&d, "\x1b[2;4H@@@", 9, &e) == 0); /* the overlay */
        for (int i = 0; i < C * 2 * R; i++)
            set_px(rgb, C, i % C, i / C, 0x808080);
        struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .diff = true, .budget = (size_t)budget,
                                .hold_col = 3, .hold_row = 1, .hold_cols = 3, .hold_rows = 1};
        for (int f = 0; f < 3; f++) {
            out = encode_frame(&s, rgb, C, 2 * R, &o, &n, NULL);
            REQUIRE(decode_apply(&d, out, n, &e) == 0);
        }
        for (int c = 0; c < C; c++)
            for (int r = 0; r < R; r++) {
                bool held = r == 1 && c >= 3 && c < 6;
                const uint8_t *px = d.rgb + 3 * (2 * r * C + c);
                CHECK(held ? px[0] == 255 : px[0] == 128); /* '@' is the ramp's white */
            }
        encode_screen_free(&s);
        decode_free(&d);
    }
}

TEST(lf_newline_frames_use_bare_lf_and_decode_the_same)
{
    /* Files played with `cat` go through a tty that turns LF into CR LF: with lf_newline
     * rows advance with LF alone (no CR anywhere), one byte less per row, same picture. */
    enum { C = 12, R = 5 };
    static uint8_t rgb[C * 2 * R * 3];
    uint32_t seed = 3;
    random_frame(rgb, C, 2 * R, &seed, 256);
    struct encode_screen a, b;
    REQUIRE(encode_screen_init(&a, C, R, NULL) == 0);
    REQUIRE(encode_screen_init(&b, C, R, NULL) == 0);
    struct encode_opts crlf = {.mode = PALETTE_TRUECOLOR, .mark_frames = true};
    struct encode_opts lf = crlf;
    lf.lf_newline = true;
    size_t na, nb;
    const char *pa = encode_frame(&a, rgb, C, 2 * R, &crlf, &na, NULL);
    const char *pb = encode_frame(&b, rgb, C, 2 * R, &lf, &nb, NULL);
    CHECK(contains(pa, na, "\r\n"));
    CHECK(!memchr(pb, '\r', nb));
    CHECK_EQ_INT(na - nb, R - 1);
    struct decode_state d;
    struct err e;
    REQUIRE(decode_init(&d, C, R, HALF, NULL) == 0);
    REQUIRE(decode_apply(&d, pb, nb, &e) == 0);
    compare_grid(t, &d, rgb, C, 2 * R, 0, "lf frame");
    decode_free(&d);
    encode_screen_free(&a);
    encode_screen_free(&b);
}

TEST(a_budget_spends_bytes_on_the_worst_cells_first_wherever_they_are)
{
    /* Every cell fades a little (many cells, one price), and the last cell on the screen
     * turns from black to white. The budget holds a fraction of the fade: the white cell, the
     * most error per byte, is drawn whatever its place in raster order. */
    enum { C = 40, R = 12 };
    static uint8_t rgb[C * 2 * R * 3];
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
    memset(rgb, 40, sizeof rgb);
    for (int i = 0; i < C * 2 * R; i++)
        rgb[3 * i] = (uint8_t)(40 + i % 7 * 9); /* varied: no two neighbours alike */
    set_px(rgb, C, C - 1, 2 * R - 2, 0);
    set_px(rgb, C, C - 1, 2 * R - 1, 0);
    size_t n;
    encode_frame(&s, rgb, C, 2 * R, &TRUE_FULL, &n, NULL);
    for (size_t i = 0; i < sizeof rgb; i++)
        rgb[i] = (uint8_t)(rgb[i] + 6);
    set_px(rgb, C, C - 1, 2 * R - 2, 0xffffff);
    set_px(rgb, C, C - 1, 2 * R - 1, 0xffffff);
    struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .diff = true, .budget = 1500};
    struct encode_stats st;
    encode_frame(&s, rgb, C, 2 * R, &o, &n, &st);
    CHECK(st.demand > 4 * o.budget && n <= o.budget);
    struct encode_cell last = s.cells[C * R - 1];
    CHECK_EQ_INT(last.top, 0xffffff);
    CHECK_EQ_INT(last.bot, 0xffffff);
    encode_screen_free(&s);
}

/* ---- glyph sets (cell.h) ---------------------------------------------------------------- */

#define SEXTANT_1 "\xf0\x9f\xac\x80" /* U+1FB00: the top left sixth */

TEST(golden_sextant_and_braille_bytes)
{
    /* a 2x3 cell whose top left pixel is red and the rest blue: sextant-1, red on blue; then
     * the same in braille (2x4; the bottom row blue too): the mean of the best set of dots,
     * alone on the terminal's background (never an SGR 48): all but the top left, blue */
    uint8_t rgb[2 * 4 * 3];
    for (int i = 0; i < 8; i++)
        set_px(rgb, 2, i % 2, i / 2, i == 0 ? 0xff0000 : 0x0000ff);
    struct encode_screen s;
    REQUIRE(encode_screen_init(&s, 1, 1, NULL) == 0);
    struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .glyphs = CELL_SEXTANT};
    size_t n;
    const char *out = encode_frame(&s, rgb, 2, 3, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H\x1b[38;2;255;0;0;48;2;0;0;255m" SEXTANT_1 "\x1b[0m");
    o.glyphs = CELL_BRAILLE; /* dots 2-8: U+28FE */
    out = encode_frame(&s, rgb, 2, 4, &o, &n, NULL);
    CHECK_BYTES(out, n, "\x1b[H\x1b[38;2;0;0;255m\xe2\xa3\xbe\x1b[0m");
    encode_screen_free(&s);
}

/* The least squared error any cell of glyph set g can have over the n pixels px: every
 * pattern with the means of its parts (braille: one part's mean, the rest black), by brute
 * force (the encoder uses subset sums and integer comparisons). */
static double best_cell_error(const uint8_t *const *px, int n, bool fg_only)
{
    double best = 1e300;
    for (unsigned m = 0; m < 1u << n; m++) {
        double mean[2][3] = {{0}}, count[2] = {0, 0}, e = 0;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 3; k++)
                mean[m >> i & 1][k] += px[i][k] / 1.0, count[m >> i & 1] += k == 0;
        for (int part = 0; part < 2; part++)
            for (int k = 0; k < 3; k++)
                mean[part][k] = fg_only && part == 0 ? 0 : count[part] ? mean[part][k] / count[part] : 0;
        for (int i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                double d = px[i][k] - mean[m >> i & 1][k];
                e += d * d;
            }
        best = e < best ? e : best;
    }
    return best;
}

/* Truecolor frames of noise, flat areas and edges in every glyph set: each decoded cell shows
 * at most two colours (braille one, on black), and its squared error is the least any
 * pattern and colours could have, up to the rounding of the means to integers. */
TEST(every_cell_is_fitted_with_the_least_error)
{
    enum { C = 16, R = 6 };
    static uint8_t rgb[C * 2 * R * 4 * 3];
    static const enum cell_glyphs sets[] = {CELL_QUADRANT, CELL_SEXTANT, CELL_BRAILLE,
                                            CELL_ASCII};
    for (unsigned k = 0; k < sizeof sets / sizeof sets[0]; k++) {
        struct cell_geom g = cell_geom(sets[k]);
        int w = C * g.px_w, h = R * g.px_h, n = cell_px(&g);
        struct encode_screen s;
        struct decode_state d;
        REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
        REQUIRE(decode_init(&d, C, R, g, NULL) == 0);
        struct encode_opts o = {.mode = PALETTE_TRUECOLOR, .glyphs = sets[k]};
        uint32_t seed = 99 + k;
        for (int it = 0; it < 6; it++) {
            if (it % 2)
                random_frame(rgb, w, h, &seed, it == 1 ? 2 : 256);
            else
                rect_frame(rgb, w, h, it, seed);
            size_t len;
            const char *out = encode_frame(&s, rgb, w, h, &o, &len, NULL);
            struct err e;
            REQUIRE(decode_frame(&d, out, len, 0, &e) == 0);
            if (sets[k] == CELL_BRAILLE) /* braille never sets a background */
                CHECK(!sets_background(out, len));
            for (int r = 0; r < R; r++)
                for (int c = 0; c < C; c++) {
                    const uint8_t *px[CELL_MAX_PX];
                    uint32_t shown[CELL_MAX_PX];
                    double err = 0;
                    int colours = 0;
                    for (int i = 0; i < n; i++) {
                        size_t at = 3 * ((size_t)(r * g.px_h + i / g.px_w) * w + c * g.px_w + i % g.px_w);
                        px[i] = rgb + at;
                        shown[i] = (uint32_t)d.rgb[at] << 16 | (uint32_t)d.rgb[at + 1] << 8 | d.rgb[at + 2];
                        for (int q = 0; q < 3; q++)
                            err += (d.rgb[at + q] - rgb[at + q]) * (d.rgb[at + q] - rgb[at + q]);
                        bool seen = false;
                        for (int j = 0; j < i; j++)
                            seen |= shown[j] == shown[i];
                        colours += !seen && !(g.fg_only && shown[i] == 0);
                    }
                    CHECK(colours <= (g.fg_only || n == 1 ? 1 : 2));
                    double best = best_cell_error(px, n, g.fg_only);
                    if (err > best + 0.75 * n * 3) /* rounding: each channel off by <= 1/2 */
                        fprintf(stderr, "    %s cell %d,%d: error %.0f, best %.1f\n",
                                cell_glyphs_name(sets[k]), c, r, err, best);
                    CHECK(err <= best + 0.75 * n * 3);
                }
        }
        encode_screen_free(&s);
        decode_free(&d);
    }
}

/* Diff frames, tolerance, palettes and a byte budget work in every glyph set as with half
 * blocks: a diff chain decodes like each frame drawn alone; an unchanged frame costs nothing;
 * with tolerance N no pixel is further from the truth than N or its cell's fit; a budgeted
 * still picture converges to the fit. */
TEST(glyph_sets_diff_tolerance_palettes_and_budget)
{
    enum { C = 24, R = 8, B = 1200 };
    static uint8_t rgb[C * 2 * R * 4 * 3];
    static const enum cell_glyphs sets[] = {CELL_QUADRANT, CELL_SEXTANT, CELL_BRAILLE,
                                            CELL_ASCII};
    static const enum palette_mode modes[] = {PALETTE_TRUECOLOR, PALETTE_256, PALETTE_16};
    int binding = 0; /* budgeted cases where the budget really binds */
    for (unsigned k = 0; k < sizeof sets / sizeof sets[0]; k++)
        for (unsigned m = 0; m < 3; m++) {
            struct cell_geom g = cell_geom(sets[k]);
            int w = C * g.px_w, h = R * g.px_h;
            size_t npx = (size_t)w * h * 3;
            struct encode_screen s, alone;
            struct decode_state d, da;
            REQUIRE(encode_screen_init(&s, C, R, NULL) == 0);
            REQUIRE(encode_screen_init(&alone, C, R, NULL) == 0);
            REQUIRE(decode_init(&d, C, R, g, NULL) == 0);
            REQUIRE(decode_init(&da, C, R, g, NULL) == 0);
            int tol = m == 0 ? 6 : 0;
            struct encode_opts o = {.mode = modes[m], .diff = true, .tolerance = tol,
                                    .glyphs = sets[k]};
            struct encode_opts full = {.mode = modes[m], .glyphs = sets[k]};
            for (int f = 0; f < 12; f++) {
                rect_frame(rgb, w, h, f, 7 + k);
                size_t n, na;
                struct err e;
                const char *out = encode_frame(&s, rgb, w, h, &o, &n, NULL);
                REQUIRE(decode_apply(&d, out, n, &e) == 0);
                out = encode_frame(&alone, rgb, w, h, &full, &na, NULL);
                REQUIRE(decode_frame(&da, out, na, 0, &e) == 0);
                int worst = 0;
                for (size_t i = 0; i < npx; i++) {
                    int off = abs((int)d.rgb[i] - rgb[i]), fit = abs((int)da.rgb[i] - rgb[i]);
                    if (off > (tol > fit ? tol : fit))
                        worst = off;
                }
                if (worst)
                    fprintf(stderr, "    %s %s frame %d: a pixel %d off\n",
                            cell_glyphs_name(sets[k]), palette_mode_name(modes[m]), f, worst);
                CHECK_EQ_INT(worst, 0);
                if (tol == 0)
                    CHECK(memcmp(d.rgb, da.rgb, npx) == 0);
            }
            size_t n;
            encode_frame(&s, rgb, w, h, &o, &n, NULL);
            CHECK_EQ_INT(n, 0);
            if (modes[m] != PALETTE_16) { /* a budget: a still picture converges to the fit */
                struct encode_opts b = {.mode = modes[m], .diff = true, .budget = B,
                                        .glyphs = sets[k]};
                /* the frame drawn whole, unbudgeted: when it is over the budget, the
                 * budgeted frames must take more than one to converge */
                size_t whole;
                encode_screen_invalidate(&alone);
                encode_frame(&alone, rgb, w, h, &full, &whole, NULL);
                binding += whole > B;
                encode_screen_invalidate(&s);
                decode_reset(&d);
                int f = 0;
                for (; f < 40; f++) {
                    struct encode_stats st;
                    struct err e;
                    const char *out = encode_frame(&s, rgb, w, h, &b, &n, &st);
                    CHECK(n <= B);
                    REQUIRE(decode_apply(&d, out, n, &e) == 0);
                    if (st.cells_pending == 0)
                        break;
                }
                CHECK(f < 40);
                CHECK(whole <= B || f > 0);
                CHECK(memcmp(d.rgb, da.rgb, npx) == 0);
            }
            encode_screen_free(&s);
            encode_screen_free(&alone);
            decode_free(&d);
            decode_free(&da);
        }
    fprintf(stderr, "      the budget binds in %d of 8 budgeted cases\n", binding);
    CHECK(binding >= 6);
}
