/* kernel_setup.h: interpolation setup (setup.h, "Back end") — a covered triangle's depth
 * and varying planes, in double from the barycentric planes, rounded to float once —
 * compiled once per instruction set by kernel_*.c (kernel.h): with AVX, four doubles to a
 * register; the same IEEE operations in the same order everywhere, so the same planes (the
 * reference kernel, kernel_ref.c, writes the same sums one lane at a time). */
#ifndef RASTTY_KERNEL_SETUP_H
#define RASTTY_KERNEL_SETUP_H

#include <stdint.h>

#include "setup.h"
#include "viewport.h"

/* a tolerance on barycentrics at the snapped corners (setup.h, "Slivers"): 1/64 and 1/16
 * moved texels on the head scenes of the Mesa oracle (llvmpipe extrapolates its planes);
 * 1/4 matches Mesa on every oracle scene and still bounds the extrapolation */
#define SETUP_SLIVER_EPS (1.0 / 4)

/* Interpolation setup works on the three corners at once: lane k of a d4 holds corner k's
 * (or edge k's, or plane k's) value, lane 3 is zero. Every lane's operations are the scalar
 * formula's, in its order, so the doubles are the same as one corner at a time. */
typedef double d4 __attribute__((vector_size(32)));
typedef int64_t l4 __attribute__((vector_size(32)));

/* lane k <- lane (k + 1) % 3, and lane (k + 2) % 3: the corners edge k runs between; |v| of
 * each lane (the sign bit cleared). Macros: a function returning a d4 would have an
 * AVX-only calling convention in the baseline build. */
#define NEXT1(v) __builtin_shufflevector((v), (v), 1, 2, 0, 3)
#define NEXT2(v) __builtin_shufflevector((v), (v), 2, 0, 1, 3)
#define FABS4(v) ((d4)((l4)(v) & (l4){INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX}))

/* barycentric planes l_k of the triangle (px[k], py[k]) at pixel centre (ox, oy): value and
 * change per pixel in x and y (lane k: l_k); 0 if degenerate */
struct bary {
    d4 l, dx, dy;
};

static int planes(const d4 *pxp, const d4 *pyp, double ox, double oy, struct bary *b)
{
    const d4 px = *pxp, py = *pyp;
    double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (area == 0)
        return 0;
    double inv = 1.0 / area;
    d4 ax = NEXT1(px), ay = NEXT1(py); /* edge k runs from corner k+1 to corner k+2 */
    d4 dx = NEXT2(px) - ax, dy = NEXT2(py) - ay;
    b->l = (dx * (oy - ay) - dy * (ox - ax)) * inv;
    b->dx = -dy * inv;
    b->dy = dx * inv;
    return 1;
}

/* do the planes stay within [-eps, 1+eps] over the snapped triangle (its corners)? */
static int planes_bounded(const struct setup_tri *t, const struct bary *b)
{
    /* at the unsnapped corners l_k is 0 or 1, and snapping moves a corner by at most 1/512
     * px in x and in y: while no plane changes by more than 100 per pixel (a triangle more
     * than ~1/100 px high), l_k at a snapped corner is within 100 / 512 < eps of 0 or 1
     * (the doubles' rounding is ~1e-12 of that) and the test below would pass */
    d4 g = FABS4(b->dx) + FABS4(b->dy);
    if (g[0] <= 100 && g[1] <= 100 && g[2] <= 100)
        return 1;
    for (int j = 0; j < 3; j++) {
        double dx = (double)t->v[j]->fx / VIEWPORT_SUBPIX_ONE - (t->x0 + 0.5);
        double dy = (double)t->v[j]->fy / VIEWPORT_SUBPIX_ONE - (t->y0 + 0.5);
        d4 l = b->l + dx * b->dx + dy * b->dy;
        for (int k = 0; k < 3; k++)
            if (!(l[k] >= -SETUP_SLIVER_EPS && l[k] <= 1 + SETUP_SLIVER_EPS))
                return 0;
    }
    return 1;
}

/* the plane of sum_k l_k f_k (f_k in lane k), rounded to float */
static struct setup_plane combine(const struct bary *b, const d4 *fp)
{
    const d4 f = *fp; /* by pointer: a d4 argument would have an AVX-only convention too */
    d4 c = b->l * f, dx = b->dx * f, dy = b->dy * f;
    return (struct setup_plane){(float)(c[0] + c[1] + c[2]), (float)(dx[0] + dx[1] + dx[2]),
                                (float)(dy[0] + dy[1] + dy[2])};
}

static void setup_interp(const struct setup_tri *t, enum depth_mode depth,
                         const struct fb_depth_proj *proj, int affine, int base, int n_var,
                         struct setup_interp *in)
{
    const struct vertex_out *v0 = t->v[0], *v1 = t->v[1], *v2 = t->v[2];
    const double ox = t->x0 + 0.5, oy = t->y0 + 0.5;
    d4 ux = {v0->win[0], v1->win[0], v2->win[0], 0}, uy = {v0->win[1], v1->win[1], v2->win[1], 0};
    d4 sx = (d4){v0->fx, v1->fx, v2->fx, 0} / VIEWPORT_SUBPIX_ONE;
    d4 sy = (d4){v0->fy, v1->fy, v2->fy, 0} / VIEWPORT_SUBPIX_ONE;
    /* unsnapped planes, unless snapping changed the orientation, made the triangle
     * non-degenerate, or the planes extrapolate over the covered area: then snapped ones */
    double uarea = (ux[1] - ux[0]) * (uy[2] - uy[0]) - (uy[1] - uy[0]) * (ux[2] - ux[0]);
    double sarea_src = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
    struct bary b = {{0}, {0}, {0}}; /* (setup dropped triangles of snapped area 0) */
    if (!(uarea != 0 && (uarea < 0) == (sarea_src < 0) && planes(&ux, &uy, ox, oy, &b) &&
          planes_bounded(t, &b)))
        planes(&sx, &sy, ox, oy, &b);
    const d4 z = {v0->clip[2], v1->clip[2], v2->clip[2], 0};
    const d4 w = {v0->clip[3], v1->clip[3], v2->clip[3], 1};
    const d4 rw = 1.0 / w;
    d4 d;
    switch (depth) {
    case DEPTH_RZ: d = (w - z) / (2 * w); break;
    case DEPTH_W:
        d = proj->ortho ? 0.5 * (z / w * (proj->far - proj->near) + proj->far + proj->near) : w;
        break;
    default: d = 0.5 * z * rw + 0.5; break; /* viewport_window's depth */
    }
    double lo = d[0] < d[1] ? d[0] : d[1], hi = d[0] > d[1] ? d[0] : d[1];
    lo = d[2] < lo ? d[2] : lo;
    hi = d[2] > hi ? d[2] : hi;
    in->z_lo = (float)lo, in->z_hi = (float)hi;
    if (depth == DEPTH_W) { /* e = (sum l e / w) / (sum l / w) */
        const d4 e = d * rw;
        in->z = combine(&b, &e);
        in->zq = combine(&b, &rw);
        in->z_c_lo = 0;
    } else {
        in->z = combine(&b, &d);
        d4 p = b.l * d;
        in->z_c_lo = (float)((p[0] + p[1] + p[2]) - (double)in->z.c);
    }
    in->q = affine ? (struct setup_plane){1, 0, 0} : combine(&b, &rw);
    /* the varyings four (then one) at a time: the same double sums as combine(), with the
     * varyings in lanes */
    typedef float f4v __attribute__((vector_size(16)));
    const float *va[3] = {v0->all + base, v1->all + base, v2->all + base};
    const d4 sc = affine ? (d4){1, 1, 1, 1} : rw;
    int k = 0;
    for (; k + 4 <= n_var; k += 4) {
        d4 fv[3];
        for (int i = 0; i < 3; i++) {
            f4v a;
            __builtin_memcpy(&a, va[i] + k, sizeof a);
            fv[i] = __builtin_convertvector(a, d4) * sc[i];
        }
        d4 c = b.l[0] * fv[0] + b.l[1] * fv[1] + b.l[2] * fv[2];
        d4 dx = b.dx[0] * fv[0] + b.dx[1] * fv[1] + b.dx[2] * fv[2];
        d4 dy = b.dy[0] * fv[0] + b.dy[1] * fv[1] + b.dy[2] * fv[2];
        f4v cf = __builtin_convertvector(c, f4v), dxf = __builtin_convertvector(dx, f4v),
            dyf = __builtin_convertvector(dy, f4v);
        __builtin_memcpy(in->a_c + k, &cf, sizeof cf);
        __builtin_memcpy(in->a_dx + k, &dxf, sizeof dxf);
        __builtin_memcpy(in->a_dy + k, &dyf, sizeof dyf);
    }
    for (; k < n_var; k++) {
        d4 fk = (d4){va[0][k], va[1][k], va[2][k], 0} * sc;
        struct setup_plane p = combine(&b, &fk);
        in->a_c[k] = p.c, in->a_dx[k] = p.dx, in->a_dy[k] = p.dy;
    }
}

#endif
