/* raster.h: rasterizers — which pixels a set-up triangle covers, and nothing else.
 *
 * In:  struct setup_tri (setup.h: integer edge functions with the tie rule folded in, the
 *      pixel box) and a rectangle of the framebuffer to stay inside (the whole framebuffer
 *      with one thread; one 64x64 screen tile of the tiles plan's bins with several,
 *      batch.h).
 * Out: runs of covered pixels, handed to span_draw (span.h), which does the per-pixel work.
 * A pixel (x, y) is covered when all three edge values at its centre are >= 0. Every
 * rasterizer decides this with the same exact 64-bit integers, so all of them find the same
 * pixels, and the span stage turns the same pixels into the same bytes (a test compares them on
 * every oracle scene). They differ in how they search, so in what they cost:
 *   RASTER_EDGE      half-space edge functions over the triangle's bounding box (Pineda;
 *                    llvmpipe and GPUs): three integer adds and a sign test per box pixel.
 *                    Cost: the whole box, so thin diagonal triangles waste most of it.
 *   RASTER_SCANLINE  the triangle split at its middle corner into a flat-bottom and a
 *                    flat-top half; per row the left and right bounds come from the two
 *                    active edges, stepped row to row in the same fixed point (an exact
 *                    quotient/remainder DDA, no division after the first row) and the run
 *                    between them is emitted whole. Cost: per row, not per box pixel — best
 *                    for thin and large triangles; per triangle a little more setup.
 *   RASTER_TILED     8x8 blocks on absolute multiples of 8, each classified from the edge
 *                    values at its corners: empty (skipped), full (8 runs, no per-pixel
 *                    test) or partial (per-pixel tests). Cost: pays off on large triangles
 *                    where most blocks are full.
 * None of them fails on valid input: coverage is exact integer arithmetic. */
#ifndef RASTTY_RASTER_H
#define RASTTY_RASTER_H

#include "render_opts.h"
#include "setup.h"
#include "span.h"

/* A rectangle of pixels, inclusive on all sides. */
struct raster_rect {
    int x0, y0, x1, y1;
};

typedef void (*raster_fn)(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s);

/* RASTER_EDGE is each kernel's own (kernel.h: src/render/kernel/kernel_edge.h); the other
 * two are shared by every kernel but the reference */
void raster_scanline(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s);
void raster_tiled(const struct setup_tri *t, struct raster_rect r, struct span_ctx *s);

/* The triangle's box inside r; 0 if they do not meet. */
static inline int raster_clip_box(const struct setup_tri *t, struct raster_rect r,
                                  struct raster_rect *out)
{
    out->x0 = t->x0 > r.x0 ? t->x0 : r.x0;
    out->y0 = t->y0 > r.y0 ? t->y0 : r.y0;
    out->x1 = t->x1 < r.x1 ? t->x1 : r.x1;
    out->y1 = t->y1 < r.y1 ? t->y1 : r.y1;
    return out->x0 <= out->x1 && out->y0 <= out->y1;
}

/* Edge k's value at the centre of pixel (x, y). */
static inline int64_t raster_edge_at(const struct setup_tri *t, int k, int x, int y)
{
    return t->e[k] + (int64_t)(x - t->x0) * t->e_dx[k] + (int64_t)(y - t->y0) * t->e_dy[k];
}

#endif
