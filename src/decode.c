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

int decode_init(struct decode_state *d, int cols, int rows, struct err *e)
{
    memset(d, 0, sizeof *d);
    if (cols < 1 || cols > DECODE_MAX_COLS || rows < 1 || rows > DECODE_MAX_ROWS)
        return err_set(e, "decoder: %dx%d cells out of range (1..%d x 1..%d)", cols, rows,
                       DECODE_MAX_COLS, DECODE_MAX_ROWS);
    d->cols = cols;
    d->rows = rows;
    d->rgb = malloc((size_t)cols * (size_t)rows * 6);
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
    size_t n = (size_t)d->cols * (size_t)d->rows * 2;
    for (size_t i = 0; i < n; i++)
        memcpy(d->rgb + 3 * i, rgb, 3);
}

void decode_reset(struct decode_state *d)
{
    fill(d, d->default_bg);
    d->row = d->col = 0;
    d->wrap_pending = false;
    d->fg_default = d->bg_default = true;
    d->frames = d->used_cols = d->used_rows = 0;
}

static const uint8_t *cur_fg(const struct decode_state *d)
{
    return d->fg_default ? d->default_fg : d->fg;
}

static const uint8_t *cur_bg(const struct decode_state *d)
{
    return d->bg_default ? d->default_bg : d->bg;
}

/* Draw one cell at the cursor and advance it. */
static int put_cell(struct decode_state *d, const uint8_t *top, const uint8_t *bot, size_t at,
                    struct err *e)
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
        uint8_t *px = d->rgb + ((size_t)(2 * d->row) * (size_t)d->cols + (size_t)d->col) * 3;
        memcpy(px, top, 3);
        memcpy(px + (size_t)d->cols * 3, bot, 3);
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
        return 0;
    }
    for (int i = 0; i < n; i++) {
        int v = p[i];
        if (v == 0) {
            d->fg_default = d->bg_default = true;
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
            if (put_cell(d, cur_bg(d), cur_bg(d), i, e))
                return -1;
            i++;
        } else if (b == 0xe2) {
            if (i + 2 >= len || s[i + 1] != 0x96 ||
                (s[i + 2] != 0x80 && s[i + 2] != 0x84 && s[i + 2] != 0x88))
                return fail(d, e, i, "unsupported character (only U+2580, U+2584, U+2588)");
            const uint8_t *fg = cur_fg(d), *bg = cur_bg(d);
            int r;
            if (s[i + 2] == 0x80)
                r = put_cell(d, fg, bg, i, e);
            else if (s[i + 2] == 0x84)
                r = put_cell(d, bg, fg, i, e);
            else
                r = put_cell(d, fg, fg, i, e);
            if (r)
                return -1;
            i += 3;
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
                fill(d, cur_bg(d));
            } else {
                return fail_byte(d, e, at, "unsupported control sequence ending in", final);
            }
            i = j + 1;
        } else {
            const char *ramp = b ? strchr(PALETTE_RAMP, b) : NULL;
            if (!ramp)
                return fail_byte(d, e, i, "unexpected byte", b);
            uint8_t g = palette_ramp_grey((int)(ramp - PALETTE_RAMP));
            uint8_t grey[3] = {g, g, g};
            if (put_cell(d, grey, grey, i, e))
                return -1;
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

int decode_measure(const char *buf, size_t len, const char *name, int *cols_out, int *rows_out,
                   int *frames_out, struct err *e)
{
    struct decode_state d;
    memset(&d, 0, sizeof d);
    d.cols = d.rows = MEASURE_DIM;
    d.name = name;
    decode_reset(&d);
    if (decode_apply(&d, buf, len, e))
        return -1;
    *cols_out = d.used_cols;
    *rows_out = d.used_rows;
    *frames_out = d.frames > 0 ? d.frames : 1;
    return 0;
}
