/* span.c: depth test, interpolation, shading and the write for a run of pixels (see span.h). */
#include "span.h"

#include <math.h>

void span_begin(struct span_ctx *s, const struct setup_tri *t, const struct shade_tri *st)
{
    s->tri = t;
    s->st = st;
    s->in_ready = false;
}

void span_end(struct span_ctx *s)
{
    s->tris_empty += !s->in_ready;
}

/* Perspective-correct weights at the centre of column x0 + dx of the row whose planes
 * start at r[k] (span ends; always a covered pixel, so inside the triangle). */
static void persp_at(const struct setup_interp *in, const double r[3], double dx, double b_out[3])
{
    double q[3], qs = 0;
    for (int k = 0; k < 3; k++) {
        q[k] = (r[k] + dx * in->lam_dx[k]) * in->rw[k];
        qs += q[k];
    }
    for (int k = 0; k < 3; k++)
        b_out[k] = q[k] / qs;
}

/* floor(a / b), b > 0 */
static inline int64_t floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* The first and last covered column of row y, from the edge functions (the same integers
 * every rasterizer tests): the ends that span methods clamp their spans to. */
static void row_extent(const struct setup_tri *t, int y, int *lo_out, int *hi_out)
{
    int64_t lo = t->x0, hi = t->x1;
    for (int k = 0; k < 3; k++) {
        int64_t a = t->e_dx[k], e = t->e[k] + (int64_t)(y - t->y0) * t->e_dy[k];
        if (a > 0) { /* e + (x - x0) a >= 0  <=>  x >= x0 - floor(e / a) */
            int64_t b = t->x0 - floor_div(e, a);
            lo = b > lo ? b : lo;
        } else if (a < 0) { /* x <= x0 + floor(e / -a) */
            int64_t b = t->x0 + floor_div(e, -a);
            hi = b < hi ? b : hi;
        }
    }
    *lo_out = (int)lo, *hi_out = (int)hi;
}

/* The depth method's value at a pixel with screen-linear weights l (and q = l/w). */
static inline float depth_at(const struct span_ctx *s, const double l[3], const double q[3])
{
    const struct setup_interp *in = &s->in;
    double d;
    if (s->depth == DEPTH_W)
        d = (q[0] * in->d[0] + q[1] * in->d[1] + q[2] * in->d[2]) / (q[0] + q[1] + q[2]);
    else
        d = l[0] * in->d[0] + l[1] * in->d[1] + l[2] * in->d[2];
    d = d < in->d_lo ? in->d_lo : d > in->d_hi ? in->d_hi : d; /* never past the corners */
    if (s->depth == DEPTH_Z16)
        return (float)floor(d * 65535.0 + 0.5);
    return (float)d;
}

/* One run, instantiated per shading mode by span_draw's switch: `mode` is a compile-time
 * constant in each copy, so shade_fragment's switch folds away. */
static inline void run(struct span_ctx *s, int y, int xa, int xb, const enum shade_mode mode)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    struct fb *fb = s->fb;
    const int n_var = mode == SHADE_GOURAUD || mode == SHADE_PHONG ? 8 : 2;
    const enum persp_method persp = s->persp;
    const int span_n = persp == PERSP_SPAN8 ? 8 : persp == PERSP_SPAN16 ? 16 : 32;
    const double dy = y - t->y0;
    const double r[3] = {in->lam[0] + dy * in->lam_dy[0], in->lam[1] + dy * in->lam_dy[1],
                         in->lam[2] + dy * in->lam_dy[2]};
    const size_t row = (size_t)y * (size_t)fb->w;
    /* span methods: the current span's absolute start column and its clamped ends, the
     * weights at its start and their change over it; the row's covered extent */
    int anchor = -1, a0 = 0, row_lo = -1, row_hi = -1;
    double ba[3] = {0}, bd[3] = {0}, inv_len = 0;
    uint64_t shaded = 0;
    for (int x = xa; x <= xb; x++) {
        size_t i = row + (size_t)x;
        double dx = x - t->x0;
        double l[3] = {r[0] + dx * in->lam_dx[0], r[1] + dx * in->lam_dx[1],
                       r[2] + dx * in->lam_dx[2]};
        double q[3] = {l[0] * in->rw[0], l[1] * in->rw[1], l[2] * in->rw[2]};
        float z = depth_at(s, l, q);
        if (fb->overdraw)
            fb->overdraw[i]++;
        if (!fb_depth_passes(s->depth, z, fb->depth[i]))
            continue;
        fb->depth[i] = z;
        shaded++;
        if (mode == SHADE_WIRE)
            continue;
        float b0, b1, b2;
        if (persp == PERSP_CORRECT) {
            double inv = 1.0 / (q[0] + q[1] + q[2]);
            b0 = (float)(q[0] * inv), b1 = (float)(q[1] * inv), b2 = (float)(q[2] * inv);
        } else if (persp == PERSP_AFFINE) {
            b0 = (float)l[0], b1 = (float)l[1], b2 = (float)l[2];
        } else {
            int a = x - x % span_n; /* x >= 0 */
            if (a != anchor) { /* a new span: exact weights at both (clamped) ends */
                if (row_lo < 0)
                    row_extent(t, y, &row_lo, &row_hi);
                double bb[3];
                anchor = a;
                a0 = a > row_lo ? a : row_lo;
                int a1 = a + span_n < row_hi ? a + span_n : row_hi;
                persp_at(in, r, a0 - t->x0, ba);
                persp_at(in, r, a1 - t->x0, bb);
                inv_len = a1 > a0 ? 1.0 / (a1 - a0) : 0;
                for (int k = 0; k < 3; k++)
                    bd[k] = bb[k] - ba[k];
            }
            double f = (x - a0) * inv_len;
            b0 = (float)(ba[0] + f * bd[0]), b1 = (float)(ba[1] + f * bd[1]);
            b2 = (float)(ba[2] + f * bd[2]);
        }
        float var[VARY_MAX], rgb[3];
        const float *v0 = in->var[0], *v1 = in->var[1], *v2 = in->var[2];
        for (int k = 0; k < n_var; k++)
            var[k] = b0 * v0[k] + b1 * v1[k] + b2 * v2[k];
        shade_fragment(s->shade, mode, s->st, var, rgb);
        fb->rgb[3 * i + 0] = fb_quantize(rgb[0]);
        fb->rgb[3 * i + 1] = fb_quantize(rgb[1]);
        fb->rgb[3 * i + 2] = fb_quantize(rgb[2]);
    }
    s->tested += (uint64_t)(xb - xa + 1);
    s->shaded += shaded;
}

void span_draw(struct span_ctx *s, int y, int x0, int x1)
{
    if (!s->in_ready) {
        setup_interp(s->tri, s->depth, &s->fb->proj, &s->in);
        s->in_ready = true;
    }
    switch (s->mode) {
    case SHADE_UNLIT: run(s, y, x0, x1, SHADE_UNLIT); break;
    case SHADE_FLAT: run(s, y, x0, x1, SHADE_FLAT); break;
    case SHADE_GOURAUD: run(s, y, x0, x1, SHADE_GOURAUD); break;
    case SHADE_PHONG: run(s, y, x0, x1, SHADE_PHONG); break;
    default: run(s, y, x0, x1, SHADE_WIRE); break;
    }
}
