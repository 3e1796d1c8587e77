/* setup.c: facing and culling, edge equations and the tie rule (see setup.h; the
 * interpolation planes are the kernels', src/render/kernel/kernel_setup.h). */
#include "setup.h"

#include <math.h>

#include "viewport.h"

/* boxes of at most this many pixels have their centres tested in setup */
#define SETUP_SMALL_BOX 4

int setup_front_facing(const struct vertex_out *va, const struct vertex_out *vb,
                       const struct vertex_out *vc)
{
    /* det[x y w] has the sign of the window-space area times w0 w1 w2 */
    const double *a = va->clip, *b = vb->clip, *c = vc->clip;
    double det = a[0] * (b[1] * c[3] - c[1] * b[3]) - b[0] * (a[1] * c[3] - c[1] * a[3]) +
                 c[0] * (a[1] * b[3] - b[1] * a[3]);
    return det > 0; /* counter-clockwise in GL window coordinates */
}

enum setup_result setup_triangle(const struct vertex_out *v0, const struct vertex_out *v1,
                                 const struct vertex_out *v2, int fb_w, int fb_h,
                                 struct setup_tri *t)
{
    /* the pixel box first: most triangles of a dense mesh hold no pixel centre */
    int64_t box[4];
    if (!setup_box(v0, v1, v2, fb_w, fb_h, box))
        return SETUP_EMPTY;
    return setup_triangle_in_box(v0, v1, v2, box, t);
}

enum setup_result setup_triangle_in_box(const struct vertex_out *v0, const struct vertex_out *v1,
                                        const struct vertex_out *v2, const int64_t box[4],
                                        struct setup_tri *t)
{
    const struct vertex_out *v[3] = {v0, v1, v2};
    const int64_t px0 = box[0], py0 = box[1], px1 = box[2], py1 = box[3];
    const int64_t one = VIEWPORT_SUBPIX_ONE, half = one / 2;
    int64_t X[3] = {v0->fx, v1->fx, v2->fx}, Y[3] = {v0->fy, v1->fy, v2->fy};
    int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (Y[1] - Y[0]) * (X[2] - X[0]);
    if (area == 0)
        return SETUP_EMPTY;
    for (int i = 0; i < 3; i++)
        t->v[i] = v[i];
    /* edge order: the interior on the positive side of every edge */
    int idx[3] = {0, 1, 2};
    if (area < 0)
        idx[1] = 2, idx[2] = 1;
    t->x0 = (int)px0, t->y0 = (int)py0, t->x1 = (int)px1, t->y1 = (int)py1;
    t->rich = 0; /* (the front end marks the features path's) */

    for (int i = 0; i < 3; i++)
        t->X[i] = X[idx[i]], t->Y[i] = Y[idx[i]];
    int64_t cx = px0 * one + half, cy = py0 * one + half;
    for (int k = 0; k < 3; k++) {
        /* edge k runs from corner k+1 to corner k+2 (so it is opposite corner k) */
        int a = (k + 1) % 3, b = (k + 2) % 3;
        int64_t dx = t->X[b] - t->X[a], dy = t->Y[b] - t->Y[a];
        int owns = dy < 0 || (dy == 0 && dx < 0);
        t->e[k] = dx * (cy - t->Y[a]) - dy * (cx - t->X[a]) - (owns ? 0 : 1);
        t->e_dx[k] = -dy * one;
        t->e_dy[k] = dx * one;
    }
    /* a box of a few pixels (most triangles of a dense mesh at terminal sizes): test its
     * centres now, as every rasterizer would; covering none, the triangle is dropped here and
     * never lit, recorded or rasterized */
    if ((px1 - px0 + 1) * (py1 - py0 + 1) <= SETUP_SMALL_BOX) {
        for (int64_t y = 0; y <= py1 - py0; y++)
            for (int64_t x = 0; x <= px1 - px0; x++)
                if (((t->e[0] + x * t->e_dx[0] + y * t->e_dy[0]) |
                     (t->e[1] + x * t->e_dx[1] + y * t->e_dy[1]) |
                     (t->e[2] + x * t->e_dx[2] + y * t->e_dy[2])) >= 0)
                    return SETUP_DRAW;
        return SETUP_EMPTY;
    }
    return SETUP_DRAW;
}
