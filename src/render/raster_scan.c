/* raster_scan.c: the scanline rasterizer (see raster.h).
 *
 * Corners sorted by y: top, middle, bottom. The long edge joins top and bottom; rows above
 * the middle corner are bounded by it and the upper short edge, rows below by it and the
 * lower short edge. A row whose centre lies exactly at the middle corner's y checks all
 * three edges (there both short edges meet, and the tie rule must decide between them).
 * Away from that row the other short edge's line passes outside the row's run (the triangle
 * is convex), so it cannot remove a pixel: the two active edges give exactly the pixels the
 * edge-function test would.
 *
 * An edge with value E at the box's left column and step A per column (A = e_dx != 0)
 * admits, with q = floor(E / |A|):  A > 0 (a left edge): x >= x0 - q;  A < 0 (right):
 * x <= x0 + q. Row to row E grows by B = e_dy, so q and the remainder are stepped exactly,
 * as a DDA, with no division after a half's first row. */
#include "raster.h"
#include "viewport.h"

/* q = floor(e / d) with remainder r in [0, d), stepped by e += step */
struct dda {
    int64_t q, r, d, bq, br;
};

static inline void floor_divmod(int64_t e, int64_t d, int64_t *q, int64_t *r)
{
    *q = e / d;
    *r = e % d;
    if (*r < 0) {
        *r += d;
        *q -= 1;
    }
}

static void dda_init(struct dda *a, int64_t e, int64_t step, int64_t d)
{
    a->d = d;
    floor_divmod(e, d, &a->q, &a->r);
    floor_divmod(step, d, &a->bq, &a->br);
}

static inline void dda_step(struct dda *a)
{
    a->q += a->bq;
    a->r += a->br;
    if (a->r >= a->d) {
        a->r -= a->d;
        a->q += 1;
    }
}

/* narrow [*lo, *hi] (offsets from the box's left column) by edge k with quotient q */
static inline void narrow(const struct setup_tri *t, int k, int64_t q, int64_t *lo, int64_t *hi)
{
    if (t->e_dx[k] > 0)
        *lo = -q > *lo ? -q : *lo;
    else
        *hi = q < *hi ? q : *hi;
}

static inline int64_t iabs64(int64_t v)
{
    return v < 0 ? -v : v;
}

void raster_scanline(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    struct raster_rect b;
    if (!raster_clip_box(t, r, &b))
        return;
    /* sort corners by y */
    int top = 0, mid = 1, bot = 2, tmp;
    if (t->Y[mid] < t->Y[top])
        tmp = top, top = mid, mid = tmp;
    if (t->Y[bot] < t->Y[mid])
        tmp = mid, mid = bot, bot = tmp;
    if (t->Y[mid] < t->Y[top])
        tmp = top, top = mid, mid = tmp;
    /* edge k is opposite corner k: long edge = mid, upper short = bot, lower short = top */
    const int e_long = mid, e_upper = bot, e_lower = top;
    const int64_t ymid = t->Y[mid];
    const int64_t width = b.x1 - b.x0;
    struct dda dl = {0}, ds = {0};
    int have_long = 0, short_edge = -1;
    for (int y = b.y0; y <= b.y1; y++) {
        int64_t cy = (int64_t)y * VIEWPORT_SUBPIX_ONE + VIEWPORT_SUBPIX_ONE / 2;
        int64_t lo = 0, hi = width;
        if (cy == ymid) { /* both short edges meet on this row: all three decide */
            for (int k = 0; k < 3; k++) {
                int64_t e = raster_edge_at(t, k, b.x0, y), q, rem;
                if (t->e_dx[k] == 0) {
                    if (e < 0)
                        lo = width + 1;
                    continue;
                }
                floor_divmod(e, iabs64(t->e_dx[k]), &q, &rem);
                narrow(t, k, q, &lo, &hi);
            }
        } else {
            int want = cy < ymid ? e_upper : e_lower;
            if (!have_long) {
                dda_init(&dl, raster_edge_at(t, e_long, b.x0, y), t->e_dy[e_long],
                         iabs64(t->e_dx[e_long]));
                have_long = 1;
            }
            if (short_edge != want) { /* entering a half (its short edge is never horizontal) */
                dda_init(&ds, raster_edge_at(t, want, b.x0, y), t->e_dy[want],
                         iabs64(t->e_dx[want]));
                short_edge = want;
            }
            narrow(t, e_long, dl.q, &lo, &hi);
            narrow(t, want, ds.q, &lo, &hi);
        }
        if (lo <= hi)
            span_draw(s, y, b.x0 + (int)lo, b.x0 + (int)hi);
        if (have_long)
            dda_step(&dl);
        if (short_edge >= 0)
            dda_step(&ds);
    }
}
