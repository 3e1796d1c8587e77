/* cellfit.c: pixels -> cells (see cellfit.h). */
#include "cellfit.h"

/* cellfit_pack() with one 4-byte load; reads one byte past the pixel, so only where one
 * exists. */
static inline uint32_t pack_load4(const uint8_t *px)
{
    uint32_t v;
    memcpy(&v, px, 4);
#if __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    return __builtin_bswap32(v) >> 8;
#else
    return v >> 8;
#endif
}

/* Half blocks: every pixel its own colour (a cell is its top and bottom pixel). */
static void fit_half(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                     const struct encode_opts *o)
{
    bool palette = o->mode == PALETTE_256 || o->mode == PALETTE_16;
    /* In palette modes a pixel equal to last frame's input at the same place keeps last
     * frame's target (still in s->target): static regions cost a compare, not a search. */
    uint32_t tag = palette ? 1u << 27 | (uint32_t)o->dither << 26 | (uint32_t)o->mode << 24 |
                                 cellfit_pack(o->pad_rgb)
                           : 0;
    bool memo_ok = palette && s->memo_tag == tag;
    s->memo_tag = tag;
    for (int r = 0; r < s->rows; r++) {
        const uint8_t *top = rgb + (size_t)(2 * r) * (size_t)w * 3;
        const uint8_t *bot = 2 * r + 1 < h ? top + (size_t)w * 3 : NULL;
        struct encode_cell *t = s->target + (size_t)r * (size_t)s->cols;
        struct encode_cell *m = s->memo + (size_t)r * (size_t)s->cols;
        switch (o->mode) {
        case PALETTE_TRUECOLOR:
            if (bot && 2 * r + 2 < h) { /* a row follows: 4-byte loads stay in the buffer */
                for (int c = 0; c < w; c++) {
                    t[c].top = pack_load4(top + 3 * c);
                    t[c].bot = pack_load4(bot + 3 * c);
                }
                break;
            }
            for (int c = 0; c < w; c++) {
                t[c].top = cellfit_pack(top + 3 * c);
                t[c].bot = cellfit_pack(bot ? bot + 3 * c : o->pad_rgb);
            }
            break;
        case PALETTE_256:
        case PALETTE_16:
            for (int c = 0; c < w; c++) {
                const uint8_t *pb = bot ? bot + 3 * c : o->pad_rgb;
                uint32_t in_top = cellfit_pack(top + 3 * c), in_bot = cellfit_pack(pb);
                if (!memo_ok || m[c].top != in_top)
                    t[c].top = cellfit_quant(s, o->mode, top + 3 * c, c, 2 * r, o->dither);
                if (!memo_ok || m[c].bot != in_bot)
                    t[c].bot = cellfit_quant(s, o->mode, pb, c, 2 * r + 1, o->dither);
                m[c].top = in_top;
                m[c].bot = in_bot;
            }
            break;
        case PALETTE_NONE:
        case PALETTE_MODE_COUNT:
            for (int c = 0; c < w; c++) {
                int luma = palette_luma(top + 3 * c) + palette_luma(bot ? bot + 3 * c : o->pad_rgb);
                int level = palette_ramp_level((luma + 1) / 2);
                uint32_t grey = palette_ramp_grey(level);
                t[c].top = t[c].bot = (uint32_t)level << 24 | grey * 0x010101u;
            }
            break;
        }
        for (int c = 0; c < w; c++)
            t[c].mask = t[c].top != t[c].bot;
    }
}


/* ---- two colours (quadrant, sextant), one colour (braille) ---------------------------- */

/* The pattern and colours that show n pixels with the least squared error: two colours
 * (any partition, the parts' means; bit 0 in the first part, as canonical cells have it), or
 * with fg_only one colour on black (any set of pixels, their mean; the rest black). For a
 * fixed partition the means are optimal, and every partition is tried, exactly in integers:
 * the sums of each subset come from the previous subset's (m & (m - 1)) plus one pixel, and
 * the squared error is total - |S_a|^2 / n_a - |S_b|^2 / n_b (fg_only: total - |S_a|^2 / n_a),
 * so the best partition has the largest rest (ties: the earlier pattern). |S|^2 <= 3 (8 255)^2
 * < 2^24, so the cross-multiplied comparisons fit in 64 bits. */
static unsigned fit_cell(const uint8_t *const *px, int n, bool fg_only, uint8_t a_out[3],
                         uint8_t b_out[3])
{
    const unsigned full = (1u << n) - 1;
    int same = 1;
    for (int i = 1; i < n; i++)
        same &= px[i][0] == px[0][0] && px[i][1] == px[0][1] && px[i][2] == px[0][2];
    if (same) { /* one colour (the common case: a flat sky, the background) */
        bool black = !px[0][0] && !px[0][1] && !px[0][2];
        memcpy(a_out, px[0], 3);
        memcpy(b_out, fg_only ? (const uint8_t[3]){0, 0, 0} : px[0], 3);
        return fg_only ? (black ? 0 : full) : 1; /* 1: canonical makes it one colour */
    }
    /* bits set in 0..255 (a table: no popcount instruction is assumed) */
    static const uint8_t BITS[256] = {
#define B2(k) k, k + 1, k + 1, k + 2
#define B4(k) B2(k), B2(k + 1), B2(k + 1), B2(k + 2)
#define B6(k) B4(k), B4(k + 1), B4(k + 1), B4(k + 2)
        B6(0), B6(1), B6(1), B6(2),
#undef B6
#undef B4
#undef B2
    };
    int32_t sum[256][4];
    sum[0][0] = sum[0][1] = sum[0][2] = 0;
    for (unsigned m = 1; m <= full; m++) {
        const uint8_t *p = px[__builtin_ctz(m)];
        const int32_t *prev = sum[m & (m - 1)];
        sum[m][0] = prev[0] + p[0], sum[m][1] = prev[1] + p[1], sum[m][2] = prev[2] + p[2];
    }
    const int32_t *tot = sum[full];
    unsigned best = 0;
    int64_t best_num = 0, best_den = 1; /* the best rest, as a fraction */
    if (fg_only) {
        for (unsigned m = 1; m <= full; m++) {
            const int32_t *sa = sum[m];
            int64_t num = (int64_t)sa[0] * sa[0] + (int64_t)sa[1] * sa[1] + (int64_t)sa[2] * sa[2];
            int64_t den = BITS[m];
            if (num * best_den > best_num * den)
                best = m, best_num = num, best_den = den;
        }
    } else {
        for (unsigned m = 1; m <= full; m += 2) { /* bit 0 set */
            const int32_t *sa = sum[m];
            int na = BITS[m], nb = n - na;
            int64_t qa = (int64_t)sa[0] * sa[0] + (int64_t)sa[1] * sa[1] + (int64_t)sa[2] * sa[2];
            int64_t num = qa, den = na;
            if (nb) {
                int64_t b0 = tot[0] - sa[0], b1 = tot[1] - sa[1], b2 = tot[2] - sa[2];
                num = qa * nb + (b0 * b0 + b1 * b1 + b2 * b2) * na, den = (int64_t)na * nb;
            }
            if (num * best_den > best_num * den)
                best = m, best_num = num, best_den = den;
        }
    }
    int na = BITS[best], nb = n - na;
    for (int k = 0; k < 3; k++) {
        int sa = best ? sum[best][k] : 0, sb = tot[k] - sa;
        a_out[k] = (uint8_t)(na ? (sa + na / 2) / na : 0);
        b_out[k] = (uint8_t)(fg_only ? 0 : nb ? (sb + nb / 2) / nb : a_out[k]);
    }
    return best;
}

/* ---- monochrome ------------------------------------------------------------------------- */

/* 8x8 ordered-dither (Bayer) rank of pixel (x, y), 0..63: M8 = 16 M2(bit 0) + 4 M2(bit 1) +
 * M2(bit 2) with M2 = [0 2; 3 1], so every 2x2 block holds one rank of each quarter. */
static inline int bayer8(int x, int y)
{
    int v = 0;
    for (int i = 0; i < 3; i++) {
        int xb = x >> i & 1, yb = y >> i & 1;
        v = v * 4 + ((xb ^ yb) << 1 | yb);
    }
    return v;
}

/* How none mode draws luminance: with a coverage, what is covered spans [lo, hi] (its 2nd and
 * 98th percentile) stretched onto [CELLFIT_MONO_FLOOR, 255], and the rest is dimmed. */
struct mono_map {
    const struct fb *cov; /* NULL: the luminance as it is */
    int lo, hi;
};

static struct mono_map mono_map(const struct encode_opts *o, const uint8_t *rgb, int w, int h)
{
    struct mono_map m = {o->cover, 0, 255};
    if (!m.cov || m.cov->w != w || m.cov->h != h) {
        m.cov = NULL;
        return m;
    }
    unsigned hist[256] = {0}, n = 0;
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++)
        if (fb_covered(m.cov, i)) {
            hist[palette_luma(rgb + 3 * i)]++;
            n++;
        }
    unsigned below = 0, lo_at = n / 50, hi_at = n - n / 50;
    m.lo = -1;
    for (int l = 0; l < 256; l++) {
        below += hist[l];
        if (m.lo < 0 && below > lo_at)
            m.lo = l;
        if (below >= hi_at) {
            m.hi = l;
            break;
        }
    }
    m.lo = m.lo < 0 ? 0 : m.lo;
    m.hi = m.hi > m.lo ? m.hi : m.lo + 1;
    return m;
}

/* The luminance pixel (x, y) is drawn with in none mode (see encode.h, "none"). */
static inline int mono_level(const struct mono_map *m, int w, int h, int x, int y,
                             const uint8_t *px)
{
    int l = palette_luma(px);
    if (!m->cov || y >= h)
        return l;
    if (!fb_covered(m->cov, (size_t)y * (size_t)w + (size_t)x))
        return l * CELLFIT_MONO_SKY / 256;
    l = l < m->lo ? m->lo : l > m->hi ? m->hi : l;
    return CELLFIT_MONO_FLOOR + (l - m->lo) * (255 - CELLFIT_MONO_FLOOR) / (m->hi - m->lo);
}

/* none mode, glyph patterns: each pixel is ink (the terminal's fg) where its level beats
 * its ordered-dither threshold; ascii: a ramp character per pixel, dithered between levels. */
static void fit_mono(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                     const struct encode_opts *o)
{
    const struct cell_geom *g = &s->geom;
    const int gw = g->px_w, gh = g->px_h;
    const unsigned full = (1u << cell_px(g)) - 1;
    const struct mono_map map = mono_map(o, rgb, w, h);
    for (int r = 0; r < s->rows; r++)
        for (int c = 0; c < s->cols; c++) {
            struct encode_cell *t = &s->target[(size_t)r * (size_t)s->cols + (size_t)c];
            unsigned ink = 0;
            for (int j = 0; j < gh; j++)
                for (int i = 0; i < gw; i++) {
                    int x = c * gw + i, y = r * gh + j;
                    const uint8_t *px = y < h ? rgb + 3 * ((size_t)y * (size_t)w + (size_t)x)
                                              : o->pad_rgb;
                    int l = mono_level(&map, w, h, x, y, px), rank = 2 * bayer8(x, y) + 1;
                    if (g->glyphs == CELL_ASCII) { /* l * 9/255 + (rank / 128), floored */
                        int level = (l * (PALETTE_RAMP_LEVELS - 1) * 128 + rank * 255) / (255 * 128);
                        level = level < PALETTE_RAMP_LEVELS ? level : PALETTE_RAMP_LEVELS - 1;
                        uint32_t grey = palette_ramp_grey(level);
                        *t = (struct encode_cell){(uint32_t)level << 24 | grey * 0x010101u,
                                                  (uint32_t)level << 24 | grey * 0x010101u, 0};
                        continue;
                    }
                    ink |= (unsigned)(l * 128 > rank * 255) << (j * gw + i);
                }
            if (g->glyphs != CELL_ASCII)
                *t = cellfit_canon((struct encode_cell){CELLFIT_TERM_FG, CELLFIT_TERM_BG, ink},
                                   full, false);
        }
}

/* ---- the frame -------------------------------------------------------------------------- */

/* Glyph sets other than half blocks, in colour: fit each cell, then show its colours as the
 * mode can (palette modes: the nearest colour, dithered at the part's first pixel). */
static void fit_cells(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                      const struct encode_opts *o)
{
    const struct cell_geom *g = &s->geom;
    const int gw = g->px_w, gh = g->px_h, n = cell_px(g);
    const unsigned full = (1u << n) - 1;
    for (int r = 0; r < s->rows; r++)
        for (int c = 0; c < s->cols; c++) {
            const uint8_t *px[CELL_MAX_PX];
            for (int j = 0; j < gh; j++)
                for (int i = 0; i < gw; i++) {
                    int y = r * gh + j;
                    px[j * gw + i] = y < h ? rgb + 3 * ((size_t)y * (size_t)w + (size_t)(c * gw + i))
                                           : o->pad_rgb;
                }
            uint8_t a[3], b[3];
            unsigned m = n == 1 ? 0 : fit_cell(px, n, g->fg_only, a, b);
            if (n == 1)
                memcpy(a, px[0], 3), memcpy(b, px[0], 3);
            unsigned rest = ~m & full;
            int ia = m ? __builtin_ctz(m) : 0, ib = rest ? __builtin_ctz(rest) : 0;
            uint32_t ta, tb;
            if (o->mode == PALETTE_TRUECOLOR) {
                ta = cellfit_pack(a), tb = cellfit_pack(b);
            } else {
                ta = cellfit_quant(s, o->mode, a, c * gw + ia % gw, r * gh + ia / gw, o->dither);
                tb = cellfit_quant(s, o->mode, b, c * gw + ib % gw, r * gh + ib / gw, o->dither);
            }
            if (g->fg_only)
                tb = CELLFIT_TERM_BG, ta = m ? ta : CELLFIT_TERM_BG;
            else if (!m)
                ta = tb;
            s->target[(size_t)r * (size_t)s->cols + (size_t)c] =
                cellfit_canon((struct encode_cell){ta, tb, m}, full, g->fg_only);
        }
}

void cellfit_frame(struct encode_screen *s, const uint8_t *rgb, int w, int h,
                   const struct encode_opts *o)
{
    if (o->mode == PALETTE_NONE || o->mode == PALETTE_MODE_COUNT) {
        s->memo_tag = 0;
        fit_mono(s, rgb, w, h, o);
    } else if (s->geom.glyphs == CELL_HALF) {
        fit_half(s, rgb, w, h, o);
    } else {
        s->memo_tag = 0; /* the memo is half blocks' */
        fit_cells(s, rgb, w, h, o);
    }
}
