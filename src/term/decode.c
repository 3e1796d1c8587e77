/* decode.c: a terminal emulator for rastty's own output (see decode.h). */
#include "decode.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "palette.h"

#define DECODE_MAX_COLS 8192
#define DECODE_MAX_ROWS 4096
#define MAX_PARAMS 32
#define MAX_PARAM 65535
/* Grid size while measuring: larger than anything decode_init accepts, small enough that
 * row/col arithmetic cannot overflow. */
#define MEASURE_DIM (1 << 24)

static int fail(const struct decode_state *d, struct err *e, size_t at, const char *what)
{
    return err_set(e, "%s: byte %zu: %s", d->name ? d->name : "input", at, what);
}

static int fail_byte(const struct decode_state *d, struct err *e, size_t at, const char *what,
                     unsigned char b)
{
    char msg[160];
    if (b >= 0x21 && b < 0x7f)
        snprintf(msg, sizeof msg, "%s '%c'", what, b);
    else
        snprintf(msg, sizeof msg, "%s 0x%02x", what, b);
    return fail(d, e, at, msg);
}

/* The grid: px_w x px_h pixels per cell, and the master-grid cells each one covers. */
static void set_grid(struct decode_state *d, int px_w, int px_h)
{
    d->px_w = px_w;
    d->px_h = px_h;
    for (int j = 0; j < px_h; j++)
        for (int i = 0; i < px_w; i++) {
            uint32_t m = 0;
            for (int y = j * CELL_MASTER_H / px_h; y < (j + 1) * CELL_MASTER_H / px_h; y++)
                for (int x = i * CELL_MASTER_W / px_w; x < (i + 1) * CELL_MASTER_W / px_w; x++)
                    m |= 1u << (y * CELL_MASTER_W + x);
            d->region[j * px_w + i] = m;
        }
}

int decode_init(struct decode_state *d, int cols, int rows, struct cell_geom g, struct err *e)
{
    memset(d, 0, sizeof *d);
    if (cols < 1 || cols > DECODE_MAX_COLS || rows < 1 || rows > DECODE_MAX_ROWS)
        return err_set(e, "decoder: %dx%d cells out of range (1..%d x 1..%d)", cols, rows,
                       DECODE_MAX_COLS, DECODE_MAX_ROWS);
    if (g.px_w < 1 || CELL_MASTER_W % g.px_w || g.px_h < 1 || CELL_MASTER_H % g.px_h)
        return err_set(e, "decoder: %dx%d pixels per cell is no grid of cell.h's", g.px_w,
                       g.px_h);
    d->cols = cols;
    d->rows = rows;
    set_grid(d, g.px_w, g.px_h);
    d->rgb = malloc((size_t)cols * (size_t)rows * (size_t)(g.px_w * g.px_h) * 3);
    if (!d->rgb)
        return err_set(e, "decoder: out of memory for %dx%d cells", cols, rows);
    static const uint8_t fg[3] = {229, 229, 229}, bg[3] = {0, 0, 0};
    memcpy(d->default_fg, fg, 3);
    memcpy(d->default_bg, bg, 3);
    decode_reset(d);
    return 0;
}

void decode_free(struct decode_state *d)
{
    free(d->rgb);
    memset(d, 0, sizeof *d);
}

static void fill(struct decode_state *d, const uint8_t rgb[3])
{
    if (!d->rgb)
        return;
    size_t n = (size_t)d->cols * (size_t)d->rows * (size_t)(d->px_w * d->px_h);
    for (size_t i = 0; i < n; i++)
        memcpy(d->rgb + 3 * i, rgb, 3);
}

void decode_reset(struct decode_state *d)
{
    fill(d, d->default_bg);
    d->row = d->col = 0;
    d->wrap_pending = false;
    d->fg_default = d->bg_default = true;
    d->reverse = false;
    d->frames = d->used_cols = d->used_rows = 0;
    d->text_cells = 0;
    d->need_w = d->need_h = 1;
}

static const uint8_t *set_fg(const struct decode_state *d)
{
    return d->fg_default ? d->default_fg : d->fg;
}

static const uint8_t *set_bg(const struct decode_state *d)
{
    return d->bg_default ? d->default_bg : d->bg;
}

/* what glyphs are drawn with: SGR 7 swaps the two */
static const uint8_t *cur_fg(const struct decode_state *d)
{
    return d->reverse ? set_bg(d) : set_fg(d);
}

static const uint8_t *cur_bg(const struct decode_state *d)
{
    return d->reverse ? set_fg(d) : set_bg(d);
}

static int gcd(int a, int b)
{
    return b ? gcd(b, a % b) : a;
}

/* Draw one cell at the cursor, fg where the master-grid shape is set, and advance. */
static int put_cell(struct decode_state *d, uint32_t shape, const uint8_t *fg, const uint8_t *bg,
                    size_t at, struct err *e)
{
    if (d->wrap_pending) {
        d->wrap_pending = false;
        d->col = 0;
        if (d->row < d->rows)
            d->row++;
    }
    if (d->row >= d->rows)
        return fail(d, e, at, "drawing below the last row (the decoder does not scroll)");
    if (d->rgb) {
        const int pw = d->px_w, ph = d->px_h, n = CELL_MASTER_PX / (pw * ph);
        const size_t stride = (size_t)d->cols * (size_t)pw * 3;
        uint8_t *cell = d->rgb + (size_t)d->row * ph * stride + (size_t)d->col * pw * 3;
        for (int j = 0; j < ph; j++)
            for (int i = 0; i < pw; i++) {
                uint8_t *px = cell + (size_t)j * stride + (size_t)i * 3;
                int k = __builtin_popcount(shape & d->region[j * pw + i]);
                if (k == 0 || k == n) {
                    memcpy(px, k ? fg : bg, 3);
                    continue;
                }
                for (int c = 0; c < 3; c++) /* a glyph finer than the grid: its area's mix */
                    px[c] = (uint8_t)((fg[c] * k + bg[c] * (n - k) + n / 2) / n);
            }
    } else if (shape) { /* measuring: the grid it needs */
        int w, h;
        cell_shape_grid(shape, &w, &h);
        d->need_w = w > d->need_w ? w : d->need_w;
        d->need_h = d->need_h / gcd(d->need_h, h) * h;
    }
    if (d->col + 1 > d->used_cols)
        d->used_cols = d->col + 1;
    if (d->row + 1 > d->used_rows)
        d->used_rows = d->row + 1;
    if (d->col == d->cols - 1)
        d->wrap_pending = true;
    else
        d->col++;
    return 0;
}

static int clamp(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

/* SGR parameters p[0..n). */
static int sgr(struct decode_state *d, const int *p, int n, size_t at, struct err *e)
{
    if (n == 0) {
        d->fg_default = d->bg_default = true;
        d->reverse = false;
        return 0;
    }
    for (int i = 0; i < n; i++) {
        int v = p[i];
        if (v == 0) {
            d->fg_default = d->bg_default = true;
            d->reverse = false;
        } else if (v == 7 || v == 27) {
            d->reverse = v == 7;
        } else if (d->text && ((v >= 1 && v <= 5) || (v >= 21 && v <= 25) || v == 8 ||
                               v == 28 || v == 9 || v == 29)) {
            /* text's attributes (bold, dim, italic, underline, blink, hidden, struck): no
             * colour of a glyph cell changes with them */
        } else if (v == 39) {
            d->fg_default = true;
        } else if (v == 49) {
            d->bg_default = true;
        } else if ((v >= 30 && v <= 37) || (v >= 90 && v <= 97)) {
            palette_rgb(v >= 90 ? v - 90 + 8 : v - 30, d->fg);
            d->fg_default = false;
        } else if ((v >= 40 && v <= 47) || (v >= 100 && v <= 107)) {
            palette_rgb(v >= 100 ? v - 100 + 8 : v - 40, d->bg);
            d->bg_default = false;
        } else if (v == 38 || v == 48) {
            uint8_t rgb[3];
            if (i + 1 < n && p[i + 1] == 2) {
                if (i + 4 >= n)
                    return fail(d, e, at, "SGR 38;2/48;2 needs three colour values");
                for (int k = 0; k < 3; k++) {
                    if (p[i + 2 + k] > 255)
                        return fail(d, e, at, "SGR colour value above 255");
                    rgb[k] = (uint8_t)p[i + 2 + k];
                }
                i += 4;
            } else if (i + 1 < n && p[i + 1] == 5) {
                if (i + 2 >= n)
                    return fail(d, e, at, "SGR 38;5/48;5 needs a colour index");
                if (p[i + 2] > 255)
                    return fail(d, e, at, "SGR colour index above 255");
                palette_rgb(p[i + 2], rgb);
                i += 2;
            } else {
                return fail(d, e, at, "SGR 38/48 must be followed by 2 or 5");
            }
            memcpy(v == 38 ? d->fg : d->bg, rgb, 3);
            if (v == 38)
                d->fg_default = false;
            else
                d->bg_default = false;
        } else {
            char msg[64];
            snprintf(msg, sizeof msg, "unsupported SGR parameter %d", v);
            return fail(d, e, at, msg);
        }
    }
    return 0;
}

/* Parse buf until its end or until the bare ESC[H that would start frame `stop_frame`
 * (-1: never stop). *stopped_out = whether it stopped there. */
static int parse(struct decode_state *d, const char *buf, size_t len, int stop_frame,
                 bool *stopped_out, struct err *e)
{
    const unsigned char *s = (const unsigned char *)buf;
    *stopped_out = false;
    size_t i = 0;
    while (i < len) {
        unsigned char b = s[i];
        if (b == ' ') {
            if (put_cell(d, 0, cur_fg(d), cur_bg(d), i, e))
                return -1;
            i++;
        } else if (b >= 0xc2 && b <= 0xf4) {
            /* UTF-8: 2..4 bytes, then a glyph of cell.h's */
            int n = b >= 0xf0 ? 4 : b >= 0xe0 ? 3 : 2;
            uint32_t cp = b & (0x7f >> n);
            for (int k = 1; k < n; k++) {
                if (i + (size_t)k >= len || (s[i + k] & 0xc0) != 0x80)
                    return fail(d, e, i, "malformed UTF-8");
                cp = cp << 6 | (s[i + k] & 0x3f);
            }
            uint32_t shape;
            if (cell_shape(cp, &shape)) {
                if (!d->text) {
                    char msg[120];
                    snprintf(msg, sizeof msg, "unsupported character U+%04X (only block "
                                              "elements, sextants and braille)", (unsigned)cp);
                    return fail(d, e, i, msg);
                }
                shape = 0; /* text (the help box's frame): a cell of its background */
                d->text_cells++;
            }
            if (put_cell(d, shape, cur_fg(d), cur_bg(d), i, e))
                return -1;
            i += (size_t)n;
        } else if (b == '\r') {
            d->col = 0;
            d->wrap_pending = false;
            i++;
        } else if (b == '\n') {
            d->col = 0;
            d->wrap_pending = false;
            if (d->row < d->rows)
                d->row++;
            i++;
        } else if (b == 0x1b) {
            size_t at = i;
            if (i + 1 >= len)
                return fail(d, e, at, "escape sequence cut short");
            if (s[i + 1] != '[')
                return fail_byte(d, e, at, "unsupported escape sequence ESC", s[i + 1]);
            size_t j = i + 2;
            bool priv = j < len && s[j] == '?';
            j += priv;
            int p[MAX_PARAMS], n = 0;
            bool any = false; /* a parameter (even empty) was written */
            int cur = 0;
            while (j < len && ((s[j] >= '0' && s[j] <= '9') || s[j] == ';')) {
                any = true;
                if (s[j] == ';') {
                    if (n == MAX_PARAMS)
                        return fail(d, e, at, "too many parameters in a control sequence");
                    p[n++] = cur; /* empty = 0 (default) */
                    cur = 0;
                } else {
                    cur = cur * 10 + (s[j] - '0');
                    if (cur > MAX_PARAM)
                        return fail(d, e, at, "control sequence parameter too large");
                }
                j++;
            }
            if (any) {
                if (n == MAX_PARAMS)
                    return fail(d, e, at, "too many parameters in a control sequence");
                p[n++] = cur;
            }
            if (j >= len)
                return fail(d, e, at, "control sequence cut short");
            unsigned char final = s[j];
            if (priv) {
                if ((final != 'h' && final != 'l') || n == 0)
                    return fail_byte(d, e, at, "unsupported private sequence ending in", final);
                for (int k = 0; k < n; k++) {
                    if (p[k] == 1049 && final == 'h')
                        fill(d, d->default_bg);
                    else if (p[k] != 25 && p[k] != 1049 && p[k] != 2026)
                        return fail(d, e, at, "unsupported private mode (only 25, 1049, 2026)");
                }
            } else if (final == 'm') {
                if (sgr(d, p, n, at, e))
                    return -1;
            } else if (final == 'H') {
                if (!any) {
                    if (d->frames == stop_frame) {
                        *stopped_out = true;
                        return 0;
                    }
                    d->frames++;
                }
                if (n > 2)
                    return fail(d, e, at, "CUP takes at most two parameters");
                int r = n > 0 && p[0] > 0 ? p[0] : 1, c = n > 1 && p[1] > 0 ? p[1] : 1;
                d->row = clamp(r - 1, 0, d->rows - 1);
                d->col = clamp(c - 1, 0, d->cols - 1);
                d->wrap_pending = false;
            } else if (final == 'C' || final == 'G') {
                if (n > 1)
                    return fail_byte(d, e, at, "too many parameters for", final);
                int v = n > 0 && p[0] > 0 ? p[0] : 1;
                d->col = clamp(final == 'C' ? d->col + v : v - 1, 0, d->cols - 1);
                d->wrap_pending = false;
            } else if (final == 'J') {
                if (n != 1 || p[0] != 2)
                    return fail(d, e, at, "only ESC[2J (clear the screen) is supported");
                fill(d, set_bg(d)); /* erasing ignores reverse video */
            } else {
                return fail_byte(d, e, at, "unsupported control sequence ending in", final);
            }
            i = j + 1;
        } else {
            /* the monochrome ramp is drawn in the terminal's own colours; with colours set
             * (a status line, a help box), or any other printable character, it is text */
            const char *ramp = b ? strchr(PALETTE_RAMP, b) : NULL;
            bool plain = d->fg_default && d->bg_default && !d->reverse;
            if (ramp && (plain || !d->text)) {
                uint8_t g = palette_ramp_grey((int)(ramp - PALETTE_RAMP));
                uint8_t grey[3] = {g, g, g};
                if (put_cell(d, 0, grey, grey, i, e))
                    return -1;
            } else if (d->text && b > 0x20 && b < 0x7f) {
                if (put_cell(d, 0, cur_fg(d), cur_bg(d), i, e))
                    return -1;
                d->text_cells++;
            } else {
                return fail_byte(d, e, i, "unexpected byte", b);
            }
            i++;
        }
    }
    return 0;
}

int decode_apply(struct decode_state *d, const char *buf, size_t len, struct err *e)
{
    bool stopped;
    return parse(d, buf, len, -1, &stopped, e);
}

int decode_frame(struct decode_state *d, const char *buf, size_t len, int k, struct err *e)
{
    bool stopped;
    decode_reset(d);
    if (k < 0)
        return err_set(e, "%s: frame %d does not exist", d->name ? d->name : "input", k);
    if (parse(d, buf, len, k + 1, &stopped, e))
        return -1;
    int frames = d->frames > 0 ? d->frames : 1;
    if (!stopped && k >= frames)
        return err_set(e, "%s: frame %d does not exist (%d frame%s)",
                       d->name ? d->name : "input", k, frames, frames == 1 ? "" : "s");
    return 0;
}

int decode_measure(const char *buf, size_t len, const char *name, bool text, int *cols_out,
                   int *rows_out, int *frames_out, struct cell_geom *grid_out, struct err *e)
{
    struct decode_state d;
    memset(&d, 0, sizeof d);
    d.cols = d.rows = MEASURE_DIM;
    d.name = name;
    d.text = text;
    decode_reset(&d);
    if (decode_apply(&d, buf, len, e))
        return -1;
    *cols_out = d.used_cols;
    *rows_out = d.used_rows;
    *frames_out = d.frames > 0 ? d.frames : 1;
    struct cell_geom grid = {CELL_GLYPHS_COUNT, d.need_w, d.need_h == 1 ? 2 : d.need_h, false};
    for (int g = 0; g < CELL_GLYPHS_COUNT; g++) {
        struct cell_geom k = cell_geom((enum cell_glyphs)g);
        if (k.px_w == grid.px_w && k.px_h == grid.px_h) {
            grid = k;
            break;
        }
    }
    if (grid_out)
        *grid_out = grid;
    return 0;
}
