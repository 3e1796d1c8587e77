/* encode.c: framebuffer -> half-block bytes, diffed against the screen model (see encode.h).
 *
 * Two passes per frame: cellfit.c turns pixels into target cells (colours as the terminal
 * will show them), then the emit pass here walks the cells in raster order, skips those the
 * screen already shows (or shows within the tolerance), moves the cursor the cheapest way and
 * writes SGR + glyph, tracking the current fg/bg/cursor like tmux's tty_colours. */
#include "encode.h"

#include <assert.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cellfit.h"

#define WUR __attribute__((warn_unused_result))
/* The per-cell path is instantiated once per colour mode (emit_rows below), so the mode's
 * switch folds away; these helpers must inline for that to happen. */
#define HOT static inline __attribute__((always_inline))

/* Colour state meaning "default or unknown": equal to no cell colour. */
#define NO_COLOUR ENCODE_CELL_UNKNOWN

/* Room reserved in front of the body for ESC[H and ESC[?2026h (the bound's 3 + 8 bytes):
 * synchronized output is only known to be needed once the body's size is. */
#define PREFIX_BYTES 11

/* "0;" .. "255;": decimal digits followed by ';'. Writers copy all 4 bytes and advance by the
 * real length, so the output buffer keeps 8 bytes of slack (ENCODE_BOUND). */
#define S(x) #x ";"
#define R10(t) S(t##0), S(t##1), S(t##2), S(t##3), S(t##4), S(t##5), S(t##6), S(t##7), S(t##8), S(t##9)
static const char DIGITS[256][5] = {
    S(0), S(1), S(2), S(3), S(4), S(5), S(6), S(7), S(8), S(9),
    R10(1), R10(2), R10(3), R10(4), R10(5), R10(6), R10(7), R10(8), R10(9), R10(10),
    R10(11), R10(12), R10(13), R10(14), R10(15), R10(16), R10(17), R10(18), R10(19), R10(20),
    R10(21), R10(22), R10(23), R10(24), S(250), S(251), S(252), S(253), S(254), S(255),
};
#undef R10
#undef S
_Static_assert(sizeof DIGITS / sizeof DIGITS[0] == 256, "one entry per byte value");

static inline int dec_len(unsigned v) /* digits of v, v < 100000 */
{
    return 1 + (v >= 10) + (v >= 100) + (v >= 1000) + (v >= 10000);
}

/* v and ';' (colour channels and indices, v <= 255). */
HOT WUR char *put_chan(char *p, unsigned v)
{
    memcpy(p, DIGITS[v], 4);
    return p + 2 + (v >= 10) + (v >= 100);
}

/* v without ';' (cursor coordinates, v <= ENCODE_MAX_COLS). */
static WUR char *put_num(char *p, unsigned v)
{
    if (v < 256) {
        memcpy(p, DIGITS[v], 4);
        return p + 1 + (v >= 10) + (v >= 100);
    }
    int n = dec_len(v);
    for (int i = n - 1; i >= 0; i--, v /= 10)
        p[i] = (char)('0' + v % 10);
    return p + n;
}

/* ---- glyphs ---------------------------------------------------------------------------- */

/* No U+2588 full block in colour: a one-colour cell is always a space on that background.
 * xterm and st draw block elements from the font, and with common fonts (Liberation Mono,
 * Noto Sans Mono, DejaVu at 13 or 17 px) U+2588 leaves uncovered strips that show as a grid;
 * the background of a space is painted by the terminal itself, edge to edge, for the same
 * bytes. A glyph is named by the pattern it shows in the current fg (cell.h); NO_GLYPH: the
 * current colours cannot show the cell. */
#define NO_GLYPH (-1)

/* ---- the emitter: output pointer plus what the terminal's SGR and cursor are now ---------- */

struct emitter {
    char *p;
    uint32_t fg, bg; /* packed cell colours, NO_COLOUR = default/unknown */
    int row, col;    /* cursor cell, -1 = unknown */
    int cols;
    enum palette_mode mode;
    struct encode_stats *st;
    int hold0, hold1; /* the held columns [hold0, hold1) of the row being drawn */
    const char *limit; /* budgeted passes: no cell may end beyond this; NULL = no limit */
    int newline;       /* bytes to go down a row and back to column 0: 2 (CR LF) or 1 (LF) */
    bool capped;       /* a cell was left because the limit was reached */
    double lambda2;    /* a second, lower price for cells lambda leaves (0 = none), when the
                        * bytes still owed to lambda's cells (reserve) leave room; < 0: the
                        * cells it leaves are drawn as they come (their targets) */
    long reserve;
    /* the glyph set */
    const struct encode_glyph *glyph; /* UTF-8 per pattern */
    int gw, gh, n_px;  /* pixels per cell */
    unsigned full;     /* the pattern with every pixel set */
    unsigned split;    /* how a one-colour cell may split in two: top/bottom (half), else none */
    bool fg_only;      /* one colour per cell on the terminal's background (braille) */
    bool ramp;         /* none mode with ascii: a ramp character per cell */
};

HOT WUR char *put_glyph(const struct emitter *em, char *p, int g, struct encode_cell c)
{
    if (em->ramp) {
        *p = PALETTE_RAMP[c.top >> 24];
        return p + 1;
    }
    memcpy(p, em->glyph[g].utf8, 4); /* the buffer keeps slack for the 4-byte copy */
    return p + em->glyph[g].len;
}

static inline int glyph_len(const struct emitter *em, int g)
{
    return em->ramp ? 1 : em->glyph[g].len;
}

/* "38;2;R;G;B;" / "48;5;I;" / "9I;" ... for one colour, with a trailing ';'. */
HOT WUR char *put_colour(char *p, enum palette_mode mode, uint32_t c, bool bg)
{
    unsigned idx = c >> 24;
    switch (mode) {
    case PALETTE_TRUECOLOR:
        memcpy(p, bg ? "48;2;" : "38;2;", 5);
        p = put_chan(p + 5, cellfit_chan(c, 0));
        p = put_chan(p, cellfit_chan(c, 1));
        return put_chan(p, cellfit_chan(c, 2));
    case PALETTE_256:
        memcpy(p, bg ? "48;5;" : "38;5;", 5);
        return put_chan(p + 5, idx);
    case PALETTE_16:
        if (idx < 8) {
            p[0] = bg ? '4' : '3';
            p[1] = (char)('0' + idx);
            p[2] = ';';
            return p + 3;
        }
        if (bg) {
            memcpy(p, "10", 2);
            p += 2;
        } else {
            *p++ = '9';
        }
        p[0] = (char)('0' + idx - 8);
        p[1] = ';';
        return p + 2;
    case PALETTE_NONE:
    case PALETTE_MODE_COUNT:
        break;
    }
    return p;
}

/* Set fg and/or bg (NO_COLOUR = leave) in one SGR. */
HOT void set_colours(struct emitter *em, enum palette_mode mode, uint32_t fg, uint32_t bg)
{
    char *p = em->p;
    p[0] = '\x1b';
    p[1] = '[';
    p += 2;
    if (fg != NO_COLOUR) {
        p = put_colour(p, mode, fg, false);
        em->fg = fg;
    }
    if (bg != NO_COLOUR) {
        p = put_colour(p, mode, bg, true);
        em->bg = bg;
    }
    p[-1] = 'm'; /* replaces the last parameter's ';' */
    em->p = p;
    em->st->sgr++;
}

/* none mode: the pattern of the terminal's fg (the ink) in a cell of CELLFIT_TERM_FG and
 * CELLFIT_TERM_BG, whatever the cell's canonical order */
static inline int ink_glyph(const struct emitter *em, struct encode_cell c)
{
    if (em->ramp)
        return 0;
    if (c.mask == 0)
        return c.top == CELLFIT_TERM_FG ? (int)em->full : 0;
    return (int)(c.top == CELLFIT_TERM_FG ? c.mask : c.mask ^ em->full);
}

/* The glyph that shows cell c with the current colours, or NO_GLYPH if an SGR is needed. */
HOT int free_glyph(const struct emitter *em, enum palette_mode mode, struct encode_cell c)
{
    if (mode == PALETTE_NONE)
        return ink_glyph(em, c);
    if (c.mask == 0) /* fg_only: the terminal's own background */
        return em->fg_only || em->bg == c.top ? 0 : NO_GLYPH;
    if (em->fg == c.top && (em->fg_only || em->bg == c.bot))
        return (int)c.mask;
    if (!em->fg_only && em->fg == c.bot && em->bg == c.top)
        return (int)(c.mask ^ em->full);
    return NO_GLYPH;
}

/* Largest channel difference between a shown colour and a true pixel; branch-free because
 * in tolerance mode the outcome is as unpredictable as the image. */
HOT int chan_diff(uint32_t shown, const uint8_t *px)
{
    int d0 = abs((int)cellfit_chan(shown, 0) - px[0]), d1 = abs((int)cellfit_chan(shown, 1) - px[1]);
    int d2 = abs((int)cellfit_chan(shown, 2) - px[2]);
    int m = d0 > d1 ? d0 : d1;
    return m > d2 ? m : d2;
}

/* The colour pixel i of cell c shows. */
static inline uint32_t shown_colour(struct encode_cell c, int i)
{
    return (c.mask >> i & 1) ? c.top : c.bot;
}

/* Largest chan_diff of colour x against the pixels of `set` (0 for an empty set). */
HOT int set_diff(uint32_t x, const uint8_t *const *px, int n, unsigned set)
{
    if (n == 2 && (set == 1 || set == 2)) /* half blocks: one pixel */
        return chan_diff(x, px[set - 1]);
    int m = 0;
    for (int i = 0; i < n; i++)
        if (set >> i & 1) {
            int d = chan_diff(x, px[i]);
            m = d > m ? d : m;
        }
    return m;
}

/* Largest channel difference between what cell c shows and its true pixels. */
HOT int cell_diff(struct encode_cell c, const uint8_t *const *px, int n)
{
    if (n == 2) { /* half blocks: top and bottom pixel (a canonical cell's top and bot) */
        int dt = chan_diff(c.top, px[0]), db = chan_diff(c.bot, px[1]);
        return dt > db ? dt : db;
    }
    int m = 0;
    for (int i = 0; i < n; i++) {
        int d = chan_diff(shown_colour(c, i), px[i]);
        m = d > m ? d : m;
    }
    return m;
}

/* Colour changes (0..2) needed to show cell c, given the current fg/bg. */
HOT int sgr_changes(const struct emitter *em, struct encode_cell c)
{
    if (c.mask == 0)
        return em->fg_only ? 0 : em->bg != c.top;
    if (em->fg_only)
        return em->fg != c.top;
    int upper = (em->fg != c.top) + (em->bg != c.bot);
    int lower = (em->fg != c.bot) + (em->bg != c.top);
    return upper < lower ? upper : lower;
}

/* The cell showing `top` on the pixels of pattern m and `bot` on the rest, canonical. */
static inline struct encode_cell make_cell(const struct emitter *em, uint32_t top, uint32_t bot,
                                           unsigned m)
{
    return cellfit_canon((struct encode_cell){top, bot, m}, em->full, em->fg_only);
}

/* With a tolerance, a redrawn cell may show, instead of its exact colours, any colour within
 * tol of its true pixels px: the current fg or bg (no SGR needed), or the other part's
 * colour (one colour for the whole cell). The two parts are the cell's pattern (a one-colour
 * half-block cell: its top and bottom pixel). Picks a variant with the fewest colour changes,
 * exact first on ties. What is shown stays within tol of the truth, so nothing drifts.
 * (Choosing the midpoint of a run of similar pixels instead of the exact colour was tried:
 * ~5% fewer bytes at equal PSNR, not worth the code.) */
HOT struct encode_cell snap_cell(const struct emitter *em, enum palette_mode mode,
                                 struct encode_cell c, const uint8_t *const *px, int n, int tol)
{
    if (mode == PALETTE_NONE)
        return c;
    int base = sgr_changes(em, c);
    if (base == 0)
        return c;
    bool has_fg = em->fg != NO_COLOUR, has_bg = em->bg != NO_COLOUR;
    const bool half = n == 2; /* top and bottom pixel: the parts are known */
    if (!half && em->fg_only) /* only the dots' colour can change */
        return c.mask && has_fg && set_diff(em->fg, px, n, c.mask) <= tol
                   ? (struct encode_cell){em->fg, c.bot, c.mask}
                   : c;
    if (!half && c.mask == 0 && !em->split) /* one colour that may not split: the current bg */
        return has_bg && set_diff(em->bg, px, n, em->full) <= tol
                   ? (struct encode_cell){em->bg, em->bg, 0}
                   : c;
    unsigned a = half ? 1 : c.mask ? c.mask : em->split, b = half ? 2 : a ^ em->full;
    bool tf = has_fg && set_diff(em->fg, px, n, a) <= tol;
    bool tb = has_bg && set_diff(em->bg, px, n, a) <= tol;
    bool bf = has_fg && set_diff(em->fg, px, n, b) <= tol;
    bool bb = has_bg && set_diff(em->bg, px, n, b) <= tol;
    /* free: both parts take current colours */
    if (tb && bb)
        return make_cell(em, em->bg, em->bg, a);
    if (tf && bb)
        return make_cell(em, em->fg, em->bg, a);
    if (tb && bf)
        return make_cell(em, em->bg, em->fg, a);
    if (base == 1)
        return c;
    /* one change: one part takes a current colour, or the whole cell one new colour */
    if (tf)
        return make_cell(em, em->fg, c.bot, a);
    if (bb)
        return make_cell(em, c.top, em->bg, a);
    if (tb)
        return make_cell(em, em->bg, c.bot, a);
    if (bf)
        return make_cell(em, c.top, em->fg, a);
    if (set_diff(c.top, px, n, b) <= tol)
        return make_cell(em, c.top, c.top, a);
    if (set_diff(c.bot, px, n, a) <= tol)
        return make_cell(em, c.bot, c.bot, a);
    return c;
}

/* Draw cell c at the cursor, choosing the glyph that needs the fewest colour changes. */
HOT void draw_cell(struct emitter *em, enum palette_mode mode, struct encode_cell c)
{
    int g = free_glyph(em, mode, c);
    if (g == NO_GLYPH) {
        if (c.mask == 0) {
            set_colours(em, mode, NO_COLOUR, c.top);
            g = 0;
        } else if (em->fg_only) {
            set_colours(em, mode, c.top, NO_COLOUR);
            g = (int)c.mask;
        } else {
            int upper = (em->fg != c.top) + (em->bg != c.bot);
            int lower = (em->fg != c.bot) + (em->bg != c.top);
            uint32_t fg = lower < upper ? c.bot : c.top, bg = lower < upper ? c.top : c.bot;
            set_colours(em, mode, em->fg == fg ? NO_COLOUR : fg, em->bg == bg ? NO_COLOUR : bg);
            g = (int)(lower < upper ? c.mask ^ em->full : c.mask);
        }
    }
    em->p = put_glyph(em, em->p, g, c);
    em->col = em->col == em->cols - 1 ? -1 : em->col + 1; /* no auto-wrap assumptions */
}

/* ---- cursor movement ------------------------------------------------------------------- */

static inline int cup_len(int r, int c) /* ESC[H, ESC[rH, ESC[r;cH */
{
    if (r == 0 && c == 0)
        return 3;
    return 3 + dec_len((unsigned)r + 1) + (c ? 1 + dec_len((unsigned)c + 1) : 0);
}

static inline int cuf_len(int n) /* ESC[C, ESC[nC */
{
    return 3 + (n > 1 ? dec_len((unsigned)n) : 0);
}

static inline int hpa_len(int c) /* ESC[G, ESC[cG */
{
    return 3 + (c ? dec_len((unsigned)c + 1) : 0);
}

enum colmove { CM_STAY, CM_CUF, CM_HPA, CM_REWRITE };

/* The cell to write when rewriting skipped cell k without an SGR: this frame's target if
 * possible (it is at least as true as what is shown), else what is shown. */
static inline int rewrite_glyph(const struct emitter *em, const struct encode_cell *tgt,
                                const struct encode_cell *scr, int k, bool *use_target)
{
    int g = free_glyph(em, em->mode, tgt[k]);
    *use_target = g != NO_GLYPH;
    if (g != NO_GLYPH)
        return g;
    return scr[k].top == ENCODE_CELL_UNKNOWN ? NO_GLYPH : free_glyph(em, em->mode, scr[k]);
}

/* Bytes to rewrite cells [from, to) of a row, or INT_MAX if one needs an SGR or the cost
 * reaches limit. */
static int rewrite_cost(const struct emitter *em, const struct encode_cell *tgt,
                        const struct encode_cell *scr, int from, int to, int limit)
{
    if (from < em->hold1 && to > em->hold0) /* never write over a held cell */
        return INT_MAX;
    int cost = 0;
    for (int k = from; k < to; k++) {
        bool use_target;
        int g = rewrite_glyph(em, tgt, scr, k, &use_target);
        if (g == NO_GLYPH)
            return INT_MAX;
        cost += glyph_len(em, g);
        if (cost >= limit)
            return INT_MAX;
    }
    return cost;
}

/* Cheapest way along a row from column `from` (-1 = unknown) to `to`. */
static int col_cost(const struct emitter *em, const struct encode_cell *tgt,
                    const struct encode_cell *scr, int from, int to, enum colmove *how)
{
    if (from == to) {
        *how = CM_STAY;
        return 0;
    }
    int best = hpa_len(to);
    *how = CM_HPA;
    if (from >= 0 && from < to) {
        int cuf = cuf_len(to - from);
        if (cuf < best) {
            best = cuf;
            *how = CM_CUF;
        }
        int rw = rewrite_cost(em, tgt, scr, from, to, best);
        if (rw < best) {
            best = rw;
            *how = CM_REWRITE;
        }
    }
    return best;
}

static void do_colmove(struct emitter *em, const struct encode_cell *tgt,
                       struct encode_cell *scr, int to, enum colmove how)
{
    char *p = em->p;
    switch (how) {
    case CM_STAY:
        break;
    case CM_CUF:
        p[0] = '\x1b';
        p[1] = '[';
        p = to - em->col > 1 ? put_num(p + 2, (unsigned)(to - em->col)) : p + 2;
        *p++ = 'C';
        em->st->moves++;
        break;
    case CM_HPA:
        p[0] = '\x1b';
        p[1] = '[';
        p = to > 0 ? put_num(p + 2, (unsigned)to + 1) : p + 2;
        *p++ = 'G';
        em->st->moves++;
        break;
    case CM_REWRITE:
        for (int k = em->col; k < to; k++) {
            bool use_target;
            int g = rewrite_glyph(em, tgt, scr, k, &use_target);
            if (use_target)
                scr[k] = tgt[k];
            p = put_glyph(em, p, g, scr[k]);
            em->st->cells_rewritten++;
        }
        break;
    }
    em->p = p;
    em->col = to;
}

/* Move the cursor to cell (r, c) by the shortest of: CUP; along the row (CUF, HPA, rewrite);
 * CR then along the row; CR LF (k times) then along the row. tgt/scr are row r's cells. */
static void move_to(struct emitter *em, int r, int c, const struct encode_cell *tgt,
                    struct encode_cell *scr)
{
    enum { VIA_CUP, VIA_ROW, VIA_CR, VIA_CRLF } via = VIA_CUP;
    enum colmove how = CM_STAY, h;
    int best = cup_len(r, c), cost, down = 0;
    if (em->row == r) {
        cost = col_cost(em, tgt, scr, em->col, c, &h);
        if (cost < best) {
            best = cost;
            via = VIA_ROW;
            how = h;
        }
        if (1 < best && em->col != 0) {
            cost = 1 + col_cost(em, tgt, scr, 0, c, &h);
            if (cost < best) {
                best = cost;
                via = VIA_CR;
                how = h;
            }
        }
    } else if (em->row >= 0 && r > em->row && em->newline * (r - em->row) < best) {
        down = r - em->row;
        cost = em->newline * down + col_cost(em, tgt, scr, 0, c, &h);
        if (cost < best) {
            best = cost;
            via = VIA_CRLF;
            how = h;
        }
    }

    char *p = em->p;
    switch (via) {
    case VIA_CUP:
        p[0] = '\x1b';
        p[1] = '[';
        p += 2;
        if (r || c)
            p = put_num(p, (unsigned)r + 1);
        if (c) {
            *p++ = ';';
            p = put_num(p, (unsigned)c + 1);
        }
        *p++ = 'H';
        em->st->moves++;
        em->p = p;
        em->row = r;
        em->col = c;
        return;
    case VIA_ROW:
        break;
    case VIA_CR:
        *p++ = '\r';
        em->st->moves++;
        em->col = 0;
        break;
    case VIA_CRLF:
        for (int i = 0; i < down; i++) {
            memcpy(p, &"\r\n"[2 - em->newline], (size_t)em->newline);
            p += em->newline;
        }
        em->st->moves++;
        em->row = r;
        em->col = 0;
        break;
    }
    em->p = p;
    do_colmove(em, tgt, scr, c, how);
}

HOT void goto_cell(struct emitter *em, int r, int c, const struct encode_cell *tgt,
                   struct encode_cell *scr)
{
    if (em->row != r || em->col != c)
        move_to(em, r, c, tgt, scr);
}

/* ---- rate-distortion choice (frames with a byte budget) ------------------------------- */

/* Squared error of a shown colour against a true pixel, summed over the channels. */
HOT int sq_diff(uint32_t shown, const uint8_t *px)
{
    int d0 = (int)cellfit_chan(shown, 0) - px[0], d1 = (int)cellfit_chan(shown, 1) - px[1];
    int d2 = (int)cellfit_chan(shown, 2) - px[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* Squared error of what cell c shows against its true pixels. */
HOT int cell_sq_diff(struct encode_cell c, const uint8_t *const *px, int n)
{
    if (n == 2) /* half blocks, as in cell_diff */
        return sq_diff(c.top, px[0]) + sq_diff(c.bot, px[1]);
    int d = 0;
    for (int i = 0; i < n; i++)
        d += sq_diff(shown_colour(c, i), px[i]);
    return d;
}

/* What a cell the terminal may not show at all "costs" if left alone: four times the worst
 * real error, so such cells go first (they are what a cleared or resized screen shows). */
#define UNKNOWN_SQ(n_px) (4 * 3 * (n_px) * 255 * 255)
#define RD_SLACK 32 /* bytes kept free for the owed cells' cursor moves and colour changes */

/* Bytes of one colour's SGR parameters, trailing ';' included (put_colour's length). */
HOT int colour_len(enum palette_mode mode, uint32_t c, bool bg)
{
    unsigned idx = c >> 24;
    switch (mode) {
    case PALETTE_TRUECOLOR:
        return 8 + dec_len(cellfit_chan(c, 0)) + dec_len(cellfit_chan(c, 1)) + dec_len(cellfit_chan(c, 2));
    case PALETTE_256:
        return 6 + dec_len(idx);
    default:
        return idx < 8 || !bg ? 3 : 4;
    }
}

/* Bytes to draw cell c at the cursor with the current colours: SGR (if any) plus glyph, as
 * draw_cell emits it. */
HOT int draw_len(const struct emitter *em, enum palette_mode mode, struct encode_cell c,
                 bool half)
{
    if (c.mask == 0)
        return 1 + ((!half && em->fg_only) || em->bg == c.top ? 0 : 2 + colour_len(mode, c.top, true));
    if (!half && em->fg_only)
        return em->glyph[c.mask].len + (em->fg == c.top ? 0 : 2 + colour_len(mode, c.top, false));
    uint32_t t = c.top, b = c.bot;
    int upper = (em->fg != t) + (em->bg != b), lower = (em->fg != b) + (em->bg != t);
    uint32_t fg = lower < upper ? b : t, bg = lower < upper ? t : b;
    int n = (em->fg != fg ? colour_len(mode, fg, false) : 0) +
            (em->bg != bg ? colour_len(mode, bg, true) : 0);
    int glyph = half ? 3 : em->glyph[lower < upper ? c.mask ^ em->full : c.mask].len;
    return glyph + (n ? 2 + n : 0);
}

/* Estimated bytes to move the cursor to (r, c): 0 when it is there, else the cheaper of
 * CUF/HPA along the row or CUP (move_to may still find a cheaper rewrite). */
HOT int move_len(const struct emitter *em, int r, int c)
{
    if (em->row == r && em->col == c)
        return 0;
    int best = cup_len(r, c);
    if (em->row == r && em->col >= 0 && em->col < c) {
        int cuf = cuf_len(c - em->col), hpa = hpa_len(c);
        best = cuf < best ? cuf : best;
        best = hpa < best ? hpa : best;
    }
    return best;
}

/* The Lagrangian choice for one changed cell: leave it as it is (error d_skip, no bytes) or
 * draw one of a few variants — its exact target, one colour for the whole cell (the mean: a
 * space), the current fg/bg for one or both parts (as in snap_cell) — minimising
 * error + lambda * bytes with the bytes counted exactly for the current colours. Braille
 * (fg_only): the target, its dots in the current fg, all dots in the mean, or no dots.
 * Returns false to leave the cell. */
HOT bool rd_choose(struct encode_screen *s, const struct emitter *em, enum palette_mode mode,
                   int r, int c, struct encode_cell tgt, int d_skip, const uint8_t *const *px,
                   int n_px, double lambda, struct encode_cell *out)
{
    double move = move_len(em, r, c);
    if (d_skip <= lambda * (move + 1)) /* no variant costs less than one byte */
        return false;
    unsigned sum[3] = {0, 0, 0};
    for (int i = 0; i < n_px; i++)
        for (int k = 0; k < 3; k++)
            sum[k] += px[i][k];
    uint8_t m[3];
    for (int k = 0; k < 3; k++)
        m[k] = (uint8_t)((sum[k] + (unsigned)n_px / 2) / (unsigned)n_px);
    uint32_t mean = mode == PALETTE_TRUECOLOR ? cellfit_pack(m)
                                              : cellfit_quant(s, mode, m, 0, 0, false);
    uint32_t fg = em->fg, bg = em->bg;
    struct encode_cell cand[11];
    int n = 0;
    const bool half = n_px == 2;
    if (!half && em->fg_only) {
        const uint32_t none = CELLFIT_TERM_BG;
        cand[n++] = tgt;
        cand[n++] = make_cell(em, mean, none, em->full);
        cand[n++] = make_cell(em, none, none, 0);
        if (tgt.mask && fg != NO_COLOUR)
            cand[n++] = make_cell(em, fg, none, tgt.mask);
    } else {
        unsigned a = half ? 1 : tgt.mask ? tgt.mask : em->split ? em->split : em->full;
        const uint32_t pairs[][2] = {
            {tgt.top, tgt.bot}, {mean, mean},  {tgt.top, tgt.top}, {tgt.bot, tgt.bot},
            {fg, bg},           {bg, fg},      {bg, bg},           {tgt.top, bg},
            {fg, tgt.bot},      {bg, tgt.bot}, {tgt.top, fg},
        };
        for (unsigned i = 0; i < sizeof pairs / sizeof pairs[0]; i++)
            if (pairs[i][0] != NO_COLOUR && pairs[i][1] != NO_COLOUR)
                cand[n++] = half ? (struct encode_cell){pairs[i][0], pairs[i][1],
                                                        pairs[i][0] != pairs[i][1]}
                                 : make_cell(em, pairs[i][0], pairs[i][1], a);
    }
    double best = d_skip;
    bool draw = false;
    for (int i = 0; i < n; i++) {
        int d = cell_sq_diff(cand[i], px, n_px);
        if (d >= best) /* bytes only add */
            continue;
        double j = d + lambda * (move + draw_len(em, mode, cand[i], half));
        if (j < best) {
            best = j;
            *out = cand[i];
            draw = true;
        }
    }
    return draw;
}

/* ---- frames ---------------------------------------------------------------------------- */

/* Walk the cells in raster order; draw those that changed (all of them when full). With
 * lambda > 0, each changed cell is left, approximated or drawn by rd_choose. Cells in the
 * held rectangle are never touched. Instantiated per colour mode, and for half blocks
 * (half: their 1x2 pixels are constants) apart from the other glyph sets. */
HOT void emit_rows(struct encode_screen *s, struct emitter *em, const uint8_t *rgb, int h,
                   const struct encode_opts *o, int tol, bool full, double lambda,
                   enum palette_mode mode, bool half)
{
    const int w = s->cols, gw = half ? 1 : em->gw, gh = half ? 2 : em->gh;
    const int n_px = half ? 2 : em->n_px;
    const bool judge = tol > 0 || lambda > 0; /* a changed cell's pixels matter */
    const size_t stride = (size_t)w * (size_t)gw * 3;
    for (int r = 0; r < s->rows; r++) {
        const struct encode_cell *tgt = s->target + (size_t)r * (size_t)w;
        struct encode_cell *scr = s->cells + (size_t)r * (size_t)w;
        const uint8_t *row[CELL_MAX_PX]; /* the cell row's pixel rows; NULL below the frame */
        for (int j = 0; j < gh; j++)
            row[j] = r * gh + j < h ? rgb + (size_t)(r * gh + j) * stride : NULL;
        bool held = r >= o->hold_row && r < o->hold_row + o->hold_rows;
        em->hold0 = held ? o->hold_col : 0;
        em->hold1 = held ? o->hold_col + o->hold_cols : 0;
        for (int c = 0; c < w; c++) {
            if (c >= em->hold0 && c < em->hold1)
                continue;
            struct encode_cell shown = tgt[c];
            if (!full && tgt[c].top == scr[c].top && tgt[c].bot == scr[c].bot &&
                tgt[c].mask == scr[c].mask)
                continue;
            const uint8_t *px[CELL_MAX_PX]; /* the cell's true pixels (pad_rgb below the frame) */
            for (int j = 0; j < gh; j++)
                for (int i = 0; i < gw; i++)
                    px[j * gw + i] = row[j] ? row[j] + 3 * (c * gw + i) : o->pad_rgb;
            if (!full) {
                bool unknown = scr[c].top == ENCODE_CELL_UNKNOWN;
                int dmax = unknown || !judge ? 255 : cell_diff(scr[c], px, n_px);
                if (tol > 0 && dmax <= tol && !unknown)
                    continue;
                if (lambda > 0) {
                    int d_skip = unknown ? UNKNOWN_SQ(n_px) : cell_sq_diff(scr[c], px, n_px);
                    bool draw;
                    if (em->lambda2 > 0) {
                        /* lambda's cells, judged as if alone on the screen (cursor unknown,
                         * no colours to reuse): a set the cells drawn around it cannot grow */
                        struct emitter alone = *em;
                        alone.fg = alone.bg = NO_COLOUR;
                        alone.row = alone.col = -1;
                        struct encode_cell unused;
                        draw = rd_choose(s, &alone, mode, r, c, tgt[c], d_skip, px, n_px, lambda,
                                         &unused) &&
                               rd_choose(s, em, mode, r, c, tgt[c], d_skip, px, n_px, lambda, &shown);
                    } else {
                        draw = rd_choose(s, em, mode, r, c, tgt[c], d_skip, px, n_px, lambda, &shown);
                    }
                    bool owed = draw;
                    if (!draw && em->lambda2 < 0) {
                        shown = tgt[c];
                        draw = true;
                    }
                    if (!draw && em->lambda2 > 0 &&
                        rd_choose(s, em, mode, r, c, tgt[c], d_skip, px, n_px, em->lambda2, &shown)) {
                        long cost = move_len(em, r, c) + draw_len(em, mode, shown, half);
                        long owing = em->reserve > 0 ? em->reserve : 0;
                        draw = em->p + cost + owing + RD_SLACK <= em->limit;
                    }
                    if (draw && em->p + move_len(em, r, c) + draw_len(em, mode, shown, half) > em->limit) {
                        draw = false; /* the budget is spent: a later frame draws it */
                        em->capped = true;
                    }
                    if (!draw) {
                        em->st->cells_pending++;
                        em->st->max_err = dmax > em->st->max_err ? dmax : em->st->max_err;
                        continue;
                    }
                    char *before = em->p;
                    goto_cell(em, r, c, tgt, scr);
                    draw_cell(em, mode, shown);
                    em->reserve -= owed ? (long)(em->p - before) : 0;
                    scr[c] = shown;
                    em->st->cells_drawn++;
                    if (shown.top != tgt[c].top || shown.bot != tgt[c].bot ||
                        shown.mask != tgt[c].mask) {
                        int e = cell_diff(shown, px, n_px);
                        em->st->cells_pending += e > tol;
                        em->st->max_err = e > em->st->max_err ? e : em->st->max_err;
                    }
                    continue;
                }
            }
            goto_cell(em, r, c, tgt, scr);
            if (tol > 0)
                shown = snap_cell(em, mode, shown, px, n_px, tol);
            draw_cell(em, mode, shown);
            scr[c] = shown;
            em->st->cells_drawn++;
        }
    }
}

/* One pass over the frame: the body into s->out (after PREFIX_BYTES), the screen model
 * updated, the frame's first byte in *start_out; returns its length. */
static size_t encode_pass(struct encode_screen *s, const uint8_t *rgb, int h,
                          const struct encode_opts *o, int tol, bool full, bool home,
                          double lambda, double lambda2, long reserve,
                          struct encode_stats *st, char **start_out, bool *capped_out)
{
    char *body = s->out + PREFIX_BYTES;
    /* the budget, less what may follow the body (reset, synchronized output) or precede it */
    size_t room = o->budget > ENCODE_FRAME_MAX_BYTES ? o->budget - ENCODE_FRAME_MAX_BYTES : 0;
    const struct cell_geom *g = &s->geom;
    struct emitter em = {.p = body, .fg = NO_COLOUR, .bg = NO_COLOUR, .row = home ? 0 : -1,
                         .col = home ? 0 : -1, .cols = s->cols, .mode = o->mode, .st = st,
                         .limit = lambda > 0 ? body + room : NULL,
                         .newline = o->lf_newline ? 1 : 2, .lambda2 = lambda2,
                         .reserve = reserve, .glyph = s->glyph, .gw = g->px_w, .gh = g->px_h,
                         .n_px = cell_px(g), .full = (1u << cell_px(g)) - 1,
                         .split = g->glyphs == CELL_HALF ? 1 : 0, .fg_only = g->fg_only,
                         .ramp = o->mode == PALETTE_NONE && g->glyphs == CELL_ASCII};
    bool half = g->glyphs == CELL_HALF;
    switch (o->mode) { /* one instantiation of the cell loop per mode, and for half blocks */
    case PALETTE_TRUECOLOR:
        if (half)
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_TRUECOLOR, true);
        else
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_TRUECOLOR, false);
        break;
    case PALETTE_256:
        if (half)
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_256, true);
        else
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_256, false);
        break;
    case PALETTE_16:
        if (half)
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_16, true);
        else
            emit_rows(s, &em, rgb, h, o, tol, full, lambda, PALETTE_16, false);
        break;
    case PALETTE_NONE:
    case PALETTE_MODE_COUNT:
        emit_rows(s, &em, rgb, h, o, tol, full, 0, PALETTE_NONE, false);
        break;
    }
    if (em.fg != NO_COLOUR || em.bg != NO_COLOUR) {
        memcpy(em.p, "\x1b[0m", 4);
        em.p += 4;
    }
    char *start = body, *end = em.p;
    st->synced = o->mode != PALETTE_NONE && (size_t)(end - body) > ENCODE_SYNC_MIN_BYTES;
    if (st->synced) {
        start -= 8;
        memcpy(start, "\x1b[?2026h", 8);
        memcpy(end, "\x1b[?2026l", 8);
        end += 8;
    }
    if (home) {
        start -= 3;
        memcpy(start, "\x1b[H", 3);
    }
    assert((size_t)(end - s->out) + 8 <= s->out_cap); /* ENCODE_BOUND holds */
    *start_out = start;
    if (capped_out)
        *capped_out = em.capped;
    return (size_t)(end - start);
}

/* Passes until the frame fits the budget: lambda = 0 first (every change, as without a
 * budget: its size is the demand); if that is too big, search lambda (from the last frame's)
 * for the frame that spends the budget best, at most RD_PASSES passes. A pass never exceeds
 * the budget: when it would, it leaves the remaining cells ("capped": lambda was too small,
 * and the cells drawn were chosen in raster order, not by value). The answer is hi, the
 * smallest lambda that is not capped, if it fills RD_CLOSE_ENOUGH of the budget; else hi's
 * cells plus, in the bytes hi leaves, cells lo (the largest capped lambda) would draw, in
 * raster order (many cells may share one price — a uniform fade, a cleared screen — and no
 * lambda splits them; hi's cells first, so the raster order never starves the valuable
 * ones at the end of the screen). The screen model is restored from s->saved before each
 * retry. */
#define RD_PASSES 10
#define RD_CLOSE_ENOUGH 0.92
#define RD_FIRST_LAMBDA 64.0

static size_t encode_budget(struct encode_screen *s, const uint8_t *rgb, int h,
                            const struct encode_opts *o, int tol, bool full, bool home,
                            struct encode_stats *st, char **start_out)
{
    size_t n_cells = (size_t)s->cols * (size_t)s->rows;
    memcpy(s->saved, s->cells, n_cells * sizeof *s->cells);
    struct encode_stats first = *st;
    size_t demand = encode_pass(s, rgb, h, o, tol, full, home, 0, 0, 0, st, start_out, NULL);
    st->demand = demand;
    if (demand <= o->budget) {
        s->lambda = 0;
        return demand;
    }
    /* too big: cells may now be left for later frames, so never a "full" frame */
    bool home_rd = o->mark_frames;
    double lambda = s->lambda > 0 ? s->lambda : RD_FIRST_LAMBDA, lo = 0, hi = 0, last = 0;
    size_t n = 0, hi_n = 0;
    for (int pass = 0; pass < RD_PASSES; pass++) {
        memcpy(s->cells, s->saved, n_cells * sizeof *s->cells);
        *st = first;
        bool capped;
        n = encode_pass(s, rgb, h, o, tol, false, home_rd, lambda, 0, 0, st, start_out, &capped);
        last = lambda;
        if (!capped) {
            hi = lambda;
            hi_n = n;
            if ((double)n >= RD_CLOSE_ENOUGH * (double)o->budget)
                break;
        } else {
            lo = lambda;
        }
        double next = hi > 0 ? (lo > 0 ? sqrt(lo * hi) : hi / 4) : lambda * 4;
        if (next == lambda || (hi > 0 && lo > 0 && hi / lo < 1.05))
            break;
        lambda = next;
    }
    bool hi_fills = hi > 0 && (lo == 0 || (double)hi_n >= RD_CLOSE_ENOUGH * (double)o->budget);
    double best = hi > 0 ? hi : lo;
    if (best != last || !hi_fills) {
        memcpy(s->cells, s->saved, n_cells * sizeof *s->cells);
        *st = first;
        n = encode_pass(s, rgb, h, o, tol, false, home_rd, hi > 0 ? hi : HUGE_VAL,
                        hi_fills ? 0 : lo, (long)hi_n, st, start_out, NULL);
    }
    if (st->cells_drawn == 0 && st->cells_pending > 0) {
        /* No price draws a cell: each one left shows, as it is, as little error as its
         * target would (a palette's rounding, an approximation drawn earlier), yet the
         * changes do not fit in one frame. Drawn as they come, to their targets, within the
         * budget: a still picture still becomes exact, in a few frames, instead of never. */
        memcpy(s->cells, s->saved, n_cells * sizeof *s->cells);
        *st = first;
        n = encode_pass(s, rgb, h, o, tol, false, home_rd, HUGE_VAL, -1, 0, st, start_out, NULL);
    }
    st->demand = demand;
    st->lambda = best;
    s->lambda = best;
    return n;
}

const char *encode_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                         const struct encode_opts *o, size_t *len_out,
                         struct encode_stats *stats_out)
{
    assert((unsigned)o->mode < PALETTE_MODE_COUNT && (unsigned)o->glyphs < CELL_GLYPHS_COUNT);
    /* another glyph set: the screen model's cells mean something else, so a full frame */
    if (o->glyphs != s->glyphs) {
        encode_screen_glyphs(s, o->glyphs);
        s->valid = false;
    }
    assert(w == cell_fb_w(&s->geom, s->cols) && h >= 1 && cell_rows(&s->geom, h) == s->rows);
    struct encode_stats st = {0};
    cellfit_frame(s, rgb, w, h, o);
    /* ramp characters are mostly background: from there, only a full frame is known to work */
    if (s->mode == PALETTE_NONE && o->mode != PALETTE_NONE)
        s->valid = false;

    st.full = !o->diff || !s->valid || s->mode != o->mode;
    bool home = st.full || o->mark_frames;
    int tol = st.full ? 0 : o->tolerance < 0 ? 0 : o->tolerance;
    char *start;
    size_t n;
    if (o->budget > 0 && o->mode != PALETTE_NONE) {
        n = encode_budget(s, rgb, h, o, tol, st.full, home, &st, &start);
    } else {
        n = encode_pass(s, rgb, h, o, tol, st.full, home, 0, 0, 0, &st, &start, NULL);
        st.demand = n;
    }
    s->valid = true;
    s->mode = o->mode;
    st.bytes = n;
    if (stats_out)
        *stats_out = st;
    *len_out = n;
    return start;
}
