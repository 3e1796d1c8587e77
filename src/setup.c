/* setup.c: facing and culling, edge equations and the tie rule, interpolation planes
 * (see setup.h). */
#include "setup.h"

#include <math.h>

#include "viewport.h"

/* a tolerance on barycentrics at the snapped corners (setup.h, "Slivers"): 1/64 and 1/16
 * moved texels on the head scenes of the Mesa oracle (llvmpipe extrapolates its planes);
 * 1/4 matches Mesa on every oracle scene and still bounds the extrapolation */
#define SETUP_SLIVER_EPS (1.0 / 4)

/* This file is compiled twice on x86-64 (Makefile), as span.c is: the second copy, with
 * -mavx2 -DSETUP_AVX2_COPY, makes only setup_interp_avx2, which the span stage's AVX2 copy
 * calls — the same C, the same IEEE double operations in the same order, so the same
 * planes, with four doubles to a register. */
#ifdef SETUP_AVX2_COPY
#define SETUP_INTERP setup_interp_avx2
#else
#define SETUP_INTERP setup_interp

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

#endif /* !SETUP_AVX2_COPY */

/* barycentric planes l_k of the triangle (px[k], py[k]) at pixel centre (ox, oy): value and
 * change per pixel in x and y; 0 if degenerate */
struct bary {
    double l[3], dx[3], dy[3];
};

static int planes(const double px[3], const double py[3], double ox, double oy, struct bary *b)
{
    double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (area == 0)
        return 0;
    double inv = 1.0 / area;
    for (int k = 0; k < 3; k++) {
        int a = (k + 1) % 3, c = (k + 2) % 3;
        double dx = px[c] - px[a], dy = py[c] - py[a];
        b->l[k] = (dx * (oy - py[a]) - dy * (ox - px[a])) * inv;
        b->dx[k] = -dy * inv;
        b->dy[k] = dx * inv;
    }
    return 1;
}

/* do the planes stay within [-eps, 1+eps] over the snapped triangle (its corners)? */
static int planes_bounded(const struct setup_tri *t, const struct bary *b)
{
    /* at the unsnapped corners l_k is 0 or 1, and snapping moves a corner by at most 1/512
     * px in x and in y: while no plane changes by more than 100 per pixel (a triangle more
     * than ~1/100 px high), l_k at a snapped corner is within 100 / 512 < eps of 0 or 1
     * (the doubles' rounding is ~1e-12 of that) and the test below would pass */
    double g = 0;
    for (int k = 0; k < 3; k++) {
        double gk = fabs(b->dx[k]) + fabs(b->dy[k]);
        g = gk > g ? gk : g;
    }
    if (g <= 100)
        return 1;
    for (int j = 0; j < 3; j++) {
        double dx = (double)t->v[j]->fx / VIEWPORT_SUBPIX_ONE - (t->x0 + 0.5);
        double dy = (double)t->v[j]->fy / VIEWPORT_SUBPIX_ONE - (t->y0 + 0.5);
        for (int k = 0; k < 3; k++) {
            double l = b->l[k] + dx * b->dx[k] + dy * b->dy[k];
            if (!(l >= -SETUP_SLIVER_EPS && l <= 1 + SETUP_SLIVER_EPS))
                return 0;
        }
    }
    return 1;
}

/* the plane of sum_k l_k f_k, rounded to float */
static struct setup_plane combine(const struct bary *b, const double f[3])
{
    struct setup_plane p;
    p.c = (float)(b->l[0] * f[0] + b->l[1] * f[1] + b->l[2] * f[2]);
    p.dx = (float)(b->dx[0] * f[0] + b->dx[1] * f[1] + b->dx[2] * f[2]);
    p.dy = (float)(b->dy[0] * f[0] + b->dy[1] * f[1] + b->dy[2] * f[2]);
    return p;
}

void SETUP_INTERP(const struct setup_tri *t, enum depth_mode depth,
                  const struct fb_depth_proj *proj, int affine, int n_var,
                  struct setup_interp *in)
{
    double ux[3], uy[3], sx[3], sy[3], ox = t->x0 + 0.5, oy = t->y0 + 0.5;
    for (int i = 0; i < 3; i++) {
        ux[i] = t->v[i]->win[0], uy[i] = t->v[i]->win[1];
        sx[i] = (double)t->v[i]->fx / VIEWPORT_SUBPIX_ONE;
        sy[i] = (double)t->v[i]->fy / VIEWPORT_SUBPIX_ONE;
    }
    /* unsnapped planes, unless snapping changed the orientation, made the triangle
     * non-degenerate, or the planes extrapolate over the covered area: then snapped ones */
    double uarea = (ux[1] - ux[0]) * (uy[2] - uy[0]) - (uy[1] - uy[0]) * (ux[2] - ux[0]);
    double sarea_src = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
    struct bary b;
    if (!(uarea != 0 && (uarea < 0) == (sarea_src < 0) && planes(ux, uy, ox, oy, &b) &&
          planes_bounded(t, &b)))
        planes(sx, sy, ox, oy, &b);
    double rw[3], d[3], f[3], lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < 3; i++) {
        const double *c = t->v[i]->clip;
        rw[i] = 1.0 / c[3];
        switch (depth) {
        case DEPTH_RZ: d[i] = (c[3] - c[2]) / (2 * c[3]); break;
        case DEPTH_W:
            d[i] = proj->ortho ? 0.5 * (c[2] / c[3] * (proj->far - proj->near) + proj->far + proj->near)
                               : c[3];
            break;
        default: d[i] = 0.5 * c[2] * rw[i] + 0.5; break; /* viewport_window's depth */
        }
        lo = d[i] < lo ? d[i] : lo;
        hi = d[i] > hi ? d[i] : hi;
    }
    in->z_lo = (float)lo, in->z_hi = (float)hi;
    if (depth == DEPTH_W) { /* e = (sum l e / w) / (sum l / w) */
        for (int i = 0; i < 3; i++)
            f[i] = d[i] * rw[i];
        in->z = combine(&b, f);
        in->zq = combine(&b, rw);
        in->z_c_lo = 0;
    } else {
        in->z = combine(&b, d);
        double c = b.l[0] * d[0] + b.l[1] * d[1] + b.l[2] * d[2];
        in->z_c_lo = (float)(c - (double)in->z.c);
    }
    in->q = affine ? (struct setup_plane){1, 0, 0} : combine(&b, rw);
    /* the varyings four (then two, then one) at a time: the same double sums as combine(),
     * in vector registers */
    typedef double d4 __attribute__((vector_size(32)));
    typedef float f4v __attribute__((vector_size(16)));
    const float *va[3] = {t->v[0]->var, t->v[1]->var, t->v[2]->var};
    double sc[3];
    for (int i = 0; i < 3; i++)
        sc[i] = affine ? 1.0 : rw[i];
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
        double fk[3];
        for (int i = 0; i < 3; i++)
            fk[i] = (double)va[i][k] * sc[i];
        struct setup_plane p = combine(&b, fk);
        in->a_c[k] = p.c, in->a_dx[k] = p.dx, in->a_dy[k] = p.dy;
    }
}
