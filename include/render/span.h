/* span.h: the per-pixel work of the back end — one function for every rasterizer.
 *
 * A rasterizer (raster.h) only finds covered pixels and hands them over as runs: pixels
 * (x0..x1, y) of the current triangle (span_draw). The runs of a triangle are queued and
 * drawn together at span_end (or when the queue fills), which does everything else: the
 * depth test, interpolation, shading (shade.h) and the framebuffer write. Each pixel's
 * weights come from its absolute position (x, y) in one fixed order of operations —
 *   v = (c + (y - y0) * dy) + (x - x0) * dx         (setup.h's planes, float)
 * — never from how the run was found or which pixels it was drawn beside, so any
 * rasterizer that finds the same pixels writes the same bytes. Interpolation setup
 * (setup_interp) runs when a triangle's first runs are drawn: triangles that cover nothing
 * never pay for it.
 *
 * The work is a kernel's (kernel.h: the bodies in src/render/kernel/kernel_span.h, compiled
 * per instruction set; the frame picks the function for its methods once, and each flush
 * the one for the triangle's size class). Pixels go SIMD_LANES at a time (simd.h: four; eight
 * in the AVX2 kernel). Perspective-correct
 * and affine interpolation, in any depth method, go in packs: SIMD_LANES pixels of
 * one run side by side are one group; what is left at a run's end (at terminal sizes most
 * runs are one to three pixels) is packed with the leftovers of the triangle's other rows,
 * so a group's lanes are full whatever the triangle's shape. The span methods, the overdraw
 * count and the normals view go run by run.
 *
 * Per pixel, in order: depth d in the depth method's measure (fb.h) from the screen-linear
 * l_k (DEPTH_W: perspective-correct), clamped to the corners' range; overdraw count; the
 * test against the stored depth, which returns early on failure (hidden fragments cost only
 * this); then the weights b_k of the perspective method, the varyings a = sum b_k a_k, the
 * colour, the 8-bit write. SHADE_WIRE runs draw depth only (the hidden-line pre-pass).
 *
 * Perspective methods (--persp; the viewer's p key):
 *   PERSP_CORRECT  b_k = (l_k/w_k) / sum_j(l_j/w_j) at every pixel (the default; what GL
 *                  does). Cost: one division per pixel. Fails: never.
 *   PERSP_AFFINE   b_k = l_k: screen-space linear, no division (early consoles). Fails:
 *                  any triangle whose corners differ in depth: a texture swims and bends,
 *                  worst on large triangles seen at grazing angles (a ground plane), where
 *                  the error grows without bound as the angle flattens.
 *   PERSP_SPANn    (n = 8, 16, 32) piecewise affine, as in Hecker's perspective texture
 *                  mapping articles: exact b at the span ends, affine in between. Span ends
 *                  sit on absolute columns (multiples of n), clamped to the row's first and
 *                  last covered pixel (computed from the edge functions, not from the run
 *                  the rasterizer handed over), so the picture does not depend on which
 *                  rasterizer found the pixels and no end is ever outside the triangle.
 *                  Cost: two divisions per n pixels of a row, three per row for its ends.
 *                  Fails: far less than affine — the error is the bend of 1/w across n
 *                  pixels, which grows with n and with how fast depth changes across the
 *                  screen (grazing surfaces close to the eye); seams where two spans meet. */
#ifndef RASTTY_SPAN_H
#define RASTTY_SPAN_H

#include <stdbool.h>
#include <stdint.h>

#include "fb.h"
#include "render_opts.h"
#include "setup.h"
#include "shade.h"
#include "simd.h"

/* runs queued per triangle before they are drawn (a triangle with more is drawn in parts) */
#define SPAN_QUEUE 128

struct span_ctx;
/* The per-pixel work of a triangle's queued runs, in one method (kernel.h's tables). */
typedef void (*span_fn)(struct span_ctx *s);

/* The size classes of a triangle's queued runs (kernel.h, struct kernel_set): one pixel, two
 * to four (one group of four lanes), more. */
enum { SPAN_SIZE_ONE, SPAN_SIZE_SMALL, SPAN_SIZE_LARGE, SPAN_SIZES };
static inline int span_size_class(int n_pixels)
{
    return (n_pixels > 1) + (n_pixels > 4);
}

/* One back-end worker's state: the frame's constants and the current triangle. */
struct span_ctx {
    /* per frame (each thread's on cache lines of its own: the pipeline allocates them
     * 64-byte aligned, and the alignment rounds the size up to whole lines) */
    _Alignas(64) struct fb *fb;
    const struct shade_ctx *shade;
    enum shade_mode mode;      /* SHADE_WIRE: depth only */
    enum persp_method persp;
    enum depth_mode depth;
    span_fn flush[SPAN_SIZES]; /* by size class: the kernels' functions for the frame's
                                * methods (kernel_choose_span), for the current triangle's
                                * path: the default's, or the features path's */
    span_fn flush_path[2][SPAN_SIZES]; /* [0] the default path's, [1] the features path's */
    uint8_t path;              /* which of them flush holds */
    /* per triangle (span_begin) */
    const struct setup_tri *tri;
    const struct shade_tri *st;
    uint32_t tri_index;        /* its place in the batch */
    struct setup_interp in;
    bool in_ready;             /* setup_interp done for tri */
    /* results, added to the frame's stats by the caller */
    uint8_t *hit;              /* hit[tri_index] = 1 once a triangle has a run (or NULL) */
    uint64_t tested, shaded;
    /* the current triangle's runs not drawn yet */
    int n_runs, n_pixels;
    struct span_run {
        int16_t y, x0, x1;     /* FB_MAX_DIM fits */
    } runs[SPAN_QUEUE];
};

/* Start a triangle: its interpolation setup waits for its first runs. */
static inline void span_begin(struct span_ctx *s, const struct setup_tri *t,
                              const struct shade_tri *st, uint32_t tri_index)
{
    if (t->rich != s->path) { /* (rare: only a mesh with material features changes it) */
        s->path = t->rich;
        for (int c = 0; c < SPAN_SIZES; c++)
            s->flush[c] = s->flush_path[t->rich][c];
    }
    s->tri = t;
    s->st = st;
    s->tri_index = tri_index;
    s->in_ready = false;
    s->n_runs = 0;
    s->n_pixels = 0;
}
/* Draw the queued runs now (span_draw and span_end call it): the frame's function for their
 * size class. */
static inline void span_flush(struct span_ctx *s)
{
    s->flush[span_size_class(s->n_pixels)](s);
    s->n_runs = s->n_pixels = 0;
}
/* Pixels x0..x1 (inclusive, x0 <= x1, inside the triangle's box) of row y, all covered:
 * queued, drawn by span_end at the latest. */
static inline void span_draw(struct span_ctx *s, int y, int x0, int x1)
{
    if (s->n_runs == SPAN_QUEUE)
        span_flush(s);
    s->runs[s->n_runs++] = (struct span_run){(int16_t)y, (int16_t)x0, (int16_t)x1};
    s->n_pixels += x1 - x0 + 1;
}
/* The triangle's rasterization is done: draw what is queued. */
static inline void span_end(struct span_ctx *s)
{
    if (s->n_runs)
        span_flush(s);
}

#endif
