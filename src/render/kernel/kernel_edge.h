/* kernel_edge.h: the edge-function rasterizer (raster.h, RASTER_EDGE) — compiled once per
 * instruction set by kernel_*.c (kernel.h): SIMD_LANES pixel centres of a row a test where
 * the edge values fit 32 bits, the same integers, so the same pixels. */
#ifndef RASTTY_KERNEL_EDGE_H
#define RASTTY_KERNEL_EDGE_H

#include "raster.h"
#include "simd.h"

/* boxes wider than this go SIMD_LANES centres at a time (eight lanes: from four pixels on,
 * head 640x480 1.056 -> 1.016 ms against nine; narrower rows are as quick one by one) */
#if SIMD_LANES == 8
#define RASTER_EDGE_VECTOR_MIN 3
#else
#define RASTER_EDGE_VECTOR_MIN 8
#endif

/* Do edge k's values at every pixel centre of box b fit in 32 bits? (They are linear: the
 * extremes are at the corners.) */
static int edge_fits_32(const struct setup_tri *t, int k, const struct raster_rect *b)
{
    const int64_t lim = INT32_MAX;
    int64_t e = raster_edge_at(t, k, b->x0, b->y0);
    int64_t ax = t->e_dx[k] * (b->x1 - b->x0), ay = t->e_dy[k] * (b->y1 - b->y0);
    int64_t lo = e + (ax < 0 ? ax : 0) + (ay < 0 ? ay : 0);
    int64_t hi = e + (ax > 0 ? ax : 0) + (ay > 0 ? ay : 0);
    return lo >= -lim && hi <= lim && t->e_dx[k] >= -lim && t->e_dx[k] <= lim;
}

/* The same pixels as the loop below, SIMD_LANES centres of a row per test: the edge values
 * in 32-bit lanes (exact inside the box, which edge_fits_32 checked; lanes past the box's
 * right side wrap harmlessly and are masked off), coverage = the sign bits of e0 | e1 | e2. */
static void raster_edge_32(const struct setup_tri *t, const struct raster_rect *b,
                           struct span_ctx *s)
{
    typedef uint32_t vu __attribute__((vector_size(sizeof(vi))));
    vu step[3], adv[3];
    int64_t r[3];
    for (int k = 0; k < 3; k++) {
        r[k] = raster_edge_at(t, k, b->x0, b->y0);
        step[k] = (vu)vi_lanes() * (uint32_t)t->e_dx[k];
        adv[k] = (vu)vi_set(SIMD_LANES) * (uint32_t)t->e_dx[k];
    }
    const int full = (1 << SIMD_LANES) - 1;
    for (int y = b->y0; y <= b->y1; y++) {
        vu e0 = (uint32_t)r[0] + step[0], e1 = (uint32_t)r[1] + step[1],
           e2 = (uint32_t)r[2] + step[2];
        int start = -1, end = -1;
        for (int x = b->x0; x <= b->x1; x += SIMD_LANES) {
            int left = b->x1 - x + 1;
            int valid = left >= SIMD_LANES ? full : (1 << left) - 1;
            int in = ~vi_mask((vi)(e0 | e1 | e2)) & valid; /* sign bit clear: covered */
            if (in) {
                if (start < 0)
                    start = x + __builtin_ctz((unsigned)in);
                end = x + 31 - __builtin_clz((unsigned)in);
                if (!(in & (valid ^ (valid >> 1)))) /* the last lane is out: the run ended */
                    break;
            } else if (start >= 0) {
                break; /* convex: nothing more on this row */
            }
            e0 += adv[0], e1 += adv[1], e2 += adv[2];
        }
        if (start >= 0)
            span_draw(s, y, start, end);
        for (int k = 0; k < 3; k++)
            r[k] += t->e_dy[k];
    }
}

/* raster.h's RASTER_EDGE */
static void raster_edge(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s)
{
    struct raster_rect b;
    if (!raster_clip_box(t, r, &b))
        return;
    /* rows of a few pixels: the loop below is as quick, without the set-up */
    if (b.x1 - b.x0 >= RASTER_EDGE_VECTOR_MIN && edge_fits_32(t, 0, &b) &&
        edge_fits_32(t, 1, &b) && edge_fits_32(t, 2, &b)) {
        raster_edge_32(t, &b, s);
        return;
    }
    int64_t r0 = raster_edge_at(t, 0, b.x0, b.y0), r1 = raster_edge_at(t, 1, b.x0, b.y0),
            r2 = raster_edge_at(t, 2, b.x0, b.y0);
    const int64_t dx0 = t->e_dx[0], dx1 = t->e_dx[1], dx2 = t->e_dx[2];
    for (int y = b.y0; y <= b.y1; y++) {
        int64_t e0 = r0, e1 = r1, e2 = r2;
        int start = -1;
        for (int x = b.x0; x <= b.x1; x++) {
            if ((e0 | e1 | e2) >= 0) {
                if (start < 0)
                    start = x;
            } else if (start >= 0) { /* convex: nothing more on this row */
                span_draw(s, y, start, x - 1);
                start = -1;
                break;
            }
            e0 += dx0, e1 += dx1, e2 += dx2;
        }
        if (start >= 0)
            span_draw(s, y, start, b.x1);
        r0 += t->e_dy[0], r1 += t->e_dy[1], r2 += t->e_dy[2];
    }
}

#endif
