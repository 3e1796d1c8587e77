/* setup.h: triangle setup — once per triangle, everything the per-pixel loop needs.
 *
 * In:  3 clip-space vertices with w > 0 (unclipped triangles inside the guard band, or pieces
 *      of a clipped polygon), the framebuffer size, the cull mode.
 * Out: struct setup_tri: integer edge functions stepped per pixel, the pixel bounding box
 *      clipped to the framebuffer, and interpolation planes for depth, 1/w and varyings/w.
 *
 * Conventions:
 *   window x = (x/w + 1) * W/2, window y = (1 - y/w) * H/2 (row 0 at the top), depth =
 *   0.5*z/w + 0.5. Positions snap to 1/256 pixel (SETUP_SUBPIX_BITS) with round-to-nearest-even,
 *   as Mesa's llvmpipe does (FIXED_ORDER 8). Pixel (px,py) has its centre at (px+.5, py+.5).
 *   Edge functions are exact 64-bit integers: |coordinate| < 2^23 units (guard band + 8192 px
 *   framebuffer), so every product is < 2^47.
 *   Tie rule: a centre exactly on an edge belongs to the triangle when, in image coordinates
 *   (y down), the edge is a LEFT edge (interior to its right) or a BOTTOM edge (horizontal,
 *   interior above). This is GL's top-left rule with y up, as llvmpipe applies it; two triangles
 *   sharing an edge therefore never both draw, and never both miss, a centre on it.
 *   Front face = counter-clockwise as displayed (GL's default, glFrontFace(GL_CCW)); in
 *   y-down image coordinates that is a negative signed area.
 *   Zero-area triangles and triangles whose box holds no pixel centre produce nothing.
 *   Attributes: snapping decides coverage only. Barycentrics l_k come from the UNSNAPPED
 *   window positions, in double (as llvmpipe builds its planes from unsnapped positions): near
 *   the horizon of a ground plane one pixel row spans several world units, so a 1/512-pixel
 *   snap of a far vertex moved u by 16 texels when barycentrics came from snapped positions
 *   (measured against an exact ray cast; Mesa stays within 1). Depth is linear in screen
 *   space (z = sum l_k z_k); varyings are perspective-correct through
 *   b_k = (l_k/w_k) / sum_j(l_j/w_j), a = sum b_k a_k, a convex combination with no
 *   cancellation (the plane form a_0 + l_1 (a_1 - a_0) + ... loses digits when one corner
 *   is near the eye). */
#ifndef RASTTY_SETUP_H
#define RASTTY_SETUP_H

#include <stdint.h>

#include "render.h"
#include "vertex.h"

#define SETUP_SUBPIX_BITS 8
#define SETUP_SUBPIX_ONE (1 << SETUP_SUBPIX_BITS)

struct setup_tri {
    int x0, y0, x1, y1;       /* pixel box, inclusive, inside the framebuffer */
    int64_t e[3];             /* edge k (opposite vertex k) at the centre of pixel (x0,y0),
                                 minus 1 when the edge does not own centres on it */
    int64_t e_dx[3], e_dy[3]; /* change of e[k] per pixel step in x / in y */
    double lam[3];            /* barycentric of vertex k at the centre of pixel (x0,y0) */
    double lam_dx[3], lam_dy[3]; /* its change per pixel step in x / in y */
    double z[3];              /* window depth per vertex */
    double rw[3];             /* 1/w per vertex */
    float var[3][VARY_MAX];   /* varyings per vertex (not divided by w) */
    int n_var;
    int front;                /* 1 if front-facing */
};

enum setup_result { SETUP_DRAW, SETUP_CULLED, SETUP_EMPTY };

enum setup_result setup_triangle(const struct vertex_out *v0, const struct vertex_out *v1,
                                 const struct vertex_out *v2, int fb_w, int fb_h,
                                 enum cull_mode cull, int n_var, struct setup_tri *out);

#endif
