/* setup.h: triangle setup — the last step of the front end, and interpolation setup for the
 * back end.
 *
 * Front end, once per SOURCE triangle: setup_front_facing() decides its facing from clip
 * space and setup_culled() whether culling drops it. This is the only place culling
 * happens, and it happens before clipping, so a clipped piece whose snapped orientation
 * flips is never dropped on its own.
 *
 * Front end, once per triangle that reaches the rasterizer (a source triangle, or a piece of
 * its clipped polygon): setup_triangle() turns three projected corners (vertex.h: window
 * position snapped to 1/256 pixel, see viewport.h) into struct setup_tri — integer edge
 * functions, the tie rule, the pixel box clipped to the framebuffer. It is what every
 * rasterizer (raster.h) reads: coverage only.
 *   Edge functions are exact 64-bit integers: |coordinate| < 2^23 units (guard band + 8192 px
 *   framebuffer), so every product is < 2^47.
 *   Tie rule: a centre exactly on an edge belongs to the triangle when, in image coordinates
 *   (y down), the edge is a LEFT edge (interior to its right) or a BOTTOM edge (horizontal,
 *   interior above). This is GL's top-left rule with y up, as llvmpipe applies it; two triangles
 *   sharing an edge therefore never both draw, and never both miss, a centre on it. The rule is
 *   folded into the edge values: an edge that does not own its centres is biased by -1, so
 *   "inside" is simply e >= 0 for all three edges.
 *   Front face = counter-clockwise as displayed (GL's default, glFrontFace(GL_CCW)); in
 *   y-down image coordinates that is a negative signed area.
 *   Zero-area triangles (after snapping), triangles whose box holds no pixel centre and
 *   triangles whose box is a few pixels (up to 4) none of whose centres they cover produce
 *   nothing (SETUP_EMPTY): at terminal sizes most triangles of a dense mesh are one of these,
 *   and the front end then neither lights their vertices nor records them.
 *
 * Back end, once per triangle that covers at least one pixel (the rasterizer finds out):
 * setup_interp() builds the interpolation planes. A quarter of a typical mesh's triangles
 * reach setup at terminal sizes and cover no pixel centre; they never pay for this.
 *   Barycentrics l_k are the same edge functions on the UNSNAPPED window positions, in double
 *   (as llvmpipe builds its planes from unsnapped positions): near the horizon of a ground
 *   plane one pixel row spans several world units, so a 1/512-pixel snap of a far vertex moved
 *   u by 16 texels when barycentrics came from snapped positions (measured against an exact
 *   ray cast; Mesa stays within 1).
 *   Slivers: a covered pixel centre lies inside the SNAPPED triangle, where the unsnapped
 *   barycentrics may extrapolate — without bound when the unsnapped height is below the snap
 *   error (a sliver with corners at depth 0.90..0.95 wrote depth 0.036 and punched through
 *   nearer surfaces). Since l is affine, its range over the snapped triangle is its range over
 *   the snapped corners: when that leaves [-1/4, 1 + 1/4] the planes come from the snapped
 *   positions instead (which keep every covered centre's l_k in [0,1]). the span kernels also clamp
 *   the depth to the corners' range, so no pixel's depth ever leaves it.
 *   Depth is linear in screen space (sum l_k d_k); varyings are perspective-correct as
 *   a = (sum l_k a_k / w_k) / (sum l_k / w_k): two screen-linear planes and one division per
 *   pixel (span.h has the other methods). */
#ifndef RASTTY_SETUP_H
#define RASTTY_SETUP_H

#include <stdbool.h>
#include <stdint.h>

#include "fb.h"
#include "render_opts.h"
#include "vertex.h"
#include "viewport.h"

/* Everything a rasterizer needs, and what interpolation setup starts from. */
struct setup_tri {
    int x0, y0, x1, y1;       /* pixel box, inclusive, inside the framebuffer */
    int64_t e[3];             /* edge k at the centre of pixel (x0,y0), tie-biased */
    int64_t e_dx[3], e_dy[3]; /* change of e[k] per pixel step in x / in y */
    int64_t X[3], Y[3];       /* snapped corners (1/256 px); edge k runs from corner k+1 to
                                 corner k+2 with the interior on its positive side */
    const struct vertex_out *v[3]; /* the projected corners, in the source order */
    uint32_t shade;           /* index of the source triangle's shading constants (batch.h) */
    uint8_t rich;             /* drawn by the features path (shade.h): set by the front end */
};

/* A quantity that is linear in screen space: its value at the centre of pixel (x, y) is
 * (c + dy * (y - y0)) + dx * (x - x0), evaluated in float in exactly that order (kernel_span.h),
 * relative to the triangle's box origin so the terms stay small. */
struct setup_plane {
    float c, dx, dy;
};

/* Interpolation planes of one triangle (setup_interp), built in double from the barycentric
 * planes l_k and rounded to float once, as llvmpipe's planes are float. */
struct setup_interp {
    struct setup_plane z;   /* depth in the method's measure: z01 (z, z16), (w - z)/2w (rz);
                               for w the numerator sum l_k e_k / w_k of the eye depth e */
    float z_c_lo;           /* z.c's rounding error: depth is evaluated as
                               z.c + ((z_c_lo + dy Y) + dx X), so two nearly coplanar
                               triangles round apart pixel by pixel instead of tying whole */
    struct setup_plane zq;  /* w only: the denominator sum l_k / w_k */
    float z_lo, z_hi;       /* the corners' range of the depth: no pixel leaves it */
    struct setup_plane q;   /* interpolation denominator: sum l_k / w_k (correct, spans),
                               the constant 1 (affine) */
    /* numerators sum l_k a_k / w_k (affine: sum l_k a_k), varying k's plane a_c[k],
     * a_dx[k], a_dy[k] (by coefficient: four varyings' planes are made at once) */
    float a_c[VARY_ALL], a_dx[VARY_ALL], a_dy[VARY_ALL];
};

enum setup_result { SETUP_DRAW, SETUP_EMPTY };

/* Facing of a source triangle from its clip-space corners (valid even when a corner is
 * behind the eye): 1 if front-facing. */
int setup_front_facing(const struct vertex_out *a, const struct vertex_out *b,
                       const struct vertex_out *c);
/* Does `cull` drop a triangle of this facing? */
static inline int setup_culled(enum cull_mode cull, int front)
{
    return (cull == CULL_BACK && !front) || (cull == CULL_FRONT && front);
}

/* The pixel box of three projected corners: the pixels whose centres lie within the
 * corners' snapped bounds, clipped to the framebuffer; false when it holds no pixel centre.
 * Inline: the front end asks it first of every triangle (most triangles of a dense mesh hold
 * no pixel centre), before anything else is read or written. */
static inline bool setup_box_xy(int64_t x0, int64_t y0, int64_t x1, int64_t y1, int64_t x2,
                                int64_t y2, int fb_w, int fb_h, int64_t box[4])
{
    int64_t minx = x0 < x1 ? x0 : x1, maxx = x0 < x1 ? x1 : x0;
    int64_t miny = y0 < y1 ? y0 : y1, maxy = y0 < y1 ? y1 : y0;
    minx = x2 < minx ? x2 : minx, maxx = x2 > maxx ? x2 : maxx;
    miny = y2 < miny ? y2 : miny, maxy = y2 > maxy ? y2 : maxy;
    const int64_t one = VIEWPORT_SUBPIX_ONE, half = one / 2;
    /* first and last centre: floor by arithmetic shift, negatives too */
    int64_t px0 = (minx - half + one - 1) >> VIEWPORT_SUBPIX_BITS, px1 = (maxx - half) >> VIEWPORT_SUBPIX_BITS;
    int64_t py0 = (miny - half + one - 1) >> VIEWPORT_SUBPIX_BITS, py1 = (maxy - half) >> VIEWPORT_SUBPIX_BITS;
    box[0] = px0 < 0 ? 0 : px0;
    box[1] = py0 < 0 ? 0 : py0;
    box[2] = px1 > fb_w - 1 ? fb_w - 1 : px1;
    box[3] = py1 > fb_h - 1 ? fb_h - 1 : py1;
    return box[0] <= box[2] && box[1] <= box[3];
}
static inline bool setup_box(const struct vertex_out *a, const struct vertex_out *b,
                             const struct vertex_out *c, int fb_w, int fb_h, int64_t box[4])
{
    return setup_box_xy(a->fx, a->fy, b->fx, b->fy, c->fx, c->fy, fb_w, fb_h, box);
}

/* Coverage setup of one triangle whose corners are projected (vertex_out.projected). */
enum setup_result setup_triangle(const struct vertex_out *v0, const struct vertex_out *v1,
                                 const struct vertex_out *v2, int fb_w, int fb_h,
                                 struct setup_tri *out);
/* setup_triangle for a triangle whose setup_box (non-empty) the caller already has */
enum setup_result setup_triangle_in_box(const struct vertex_out *v0, const struct vertex_out *v1,
                                        const struct vertex_out *v2, const int64_t box[4],
                                        struct setup_tri *t);

/* Interpolation setup (see above) is a kernel's (kernel.h): setup_interp(t, depth, proj,
 * affine, base, n_var, out) in src/render/kernel/kernel_setup.h builds the planes of the n_var
 * varyings from each vertex's all[base] on (VARY_BASE: var[]; 0: the features path's); proj
 * is the depth method's camera data (fb.h); affine: numerators without the division by w. */

#endif
