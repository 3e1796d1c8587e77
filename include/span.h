/* span.h: the per-pixel work of the back end — one function for every rasterizer.
 *
 * A rasterizer (raster.h) only finds covered pixels and hands them over as runs: pixels
 * (x0..x1, y) of the current triangle. span_draw() does everything else for the run, pixel by
 * pixel: the depth test, interpolation, shading (shade.h) and the framebuffer write. Each
 * pixel's weights come from its absolute position (x, y) in one fixed order of operations —
 *   l_k = (lam_k + (y - y0) * lam_dy_k) + (x - x0) * lam_dx_k      (setup.h's planes, double)
 * — never from how the run was found, so any rasterizer that finds the same pixels writes
 * the same bytes. Interpolation setup (setup_interp) runs on the first run of a triangle:
 * triangles that cover nothing never pay for it.
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
 *                  screen (grazing surfaces close to the eye); seams where two spans meet.
 *                  surfaces close to the eye). */
#ifndef RASTTY_SPAN_H
#define RASTTY_SPAN_H

#include <stdbool.h>

#include "fb.h"
#include "render.h"
#include "setup.h"
#include "shade.h"
#include "simd.h"

/* One back-end worker's state: the frame's constants and the current triangle. */
struct span_ctx {
    /* per frame */
    struct fb *fb;
    const struct shade_ctx *shade;
    enum shade_mode mode;      /* SHADE_WIRE: depth only */
    enum persp_method persp;
    enum depth_mode depth;
    /* per triangle (span_begin) */
    const struct setup_tri *tri;
    const struct shade_tri *st;
    uint32_t tri_index;        /* its place in the batch */
    struct setup_interp in;
    f4 a_c[VARY_MAX], a_dy[VARY_MAX], a_dx[VARY_MAX]; /* in.a's planes, in every lane */
    bool in_ready;             /* setup_interp done for tri */
    /* results, added to the frame's stats by the caller */
    uint8_t *hit;              /* hit[tri_index] = 1 once a triangle has a run (or NULL) */
    uint64_t tested, shaded;
};

/* Start a triangle: its interpolation setup waits for its first run. */
void span_begin(struct span_ctx *s, const struct setup_tri *t, const struct shade_tri *st,
                uint32_t tri_index);
/* Pixels x0..x1 (inclusive, x0 <= x1, inside the triangle's box) of row y, all covered. */
void span_draw(struct span_ctx *s, int y, int x0, int x1);

/* The instruction set span_draw runs on. On x86-64 the build makes a second copy of this
 * stage for AVX2 (the same C and the same bytes, fewer instructions: blends, rounding,
 * three-operand forms), used when the CPU has it. RASTTY_SIMD=sse2 (or avx2) in the
 * environment chooses at the first frame; span_isa_set chooses now ("auto", "sse2", "avx2";
 * -1 when this build or CPU cannot). span_isa_name: "sse2" or "avx2". */
enum span_isa { SPAN_ISA_SSE2, SPAN_ISA_AVX2 };
int span_isa_set(const char *name);
const char *span_isa_name(void);

#endif
