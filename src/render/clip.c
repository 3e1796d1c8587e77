/* clip.c: Sutherland-Hodgman polygon clipping in homogeneous space (see clip.h). */
#include "clip.h"

#include <string.h>

/* signed distance to a plane; >= 0 is inside */
static double dist(uint32_t plane, const double c[4], double gx, double gy)
{
    switch (plane) {
    case VERTEX_OUT_NEAR: return c[2] + c[3];
    case VERTEX_OUT_FAR: return c[3] - c[2];
    case VERTEX_GUARD_LEFT: return c[0] + gx * c[3];
    case VERTEX_GUARD_RIGHT: return gx * c[3] - c[0];
    case VERTEX_GUARD_BOTTOM: return c[1] + gy * c[3];
    default: return gy * c[3] - c[1]; /* VERTEX_GUARD_TOP */
    }
}

/* out = a + t * (b - a), a being the inside endpoint */
static void lerp(const struct vertex_out *a, const struct vertex_out *b, double t, int n_var,
                 struct vertex_out *out)
{
    float tf = (float)t;
    for (int k = 0; k < 4; k++)
        out->clip[k] = a->clip[k] + t * (b->clip[k] - a->clip[k]);
    for (int k = 0; k < 3; k++)
        out->wpos[k] = a->wpos[k] + tf * (b->wpos[k] - a->wpos[k]);
    if (n_var < 0) { /* the features path: all[3 .. -n_var) too (all[0..2] is wpos) */
        for (int k = 3; k < -n_var; k++)
            out->all[k] = a->all[k] + tf * (b->all[k] - a->all[k]);
        return;
    }
    for (int k = 0; k < n_var; k++)
        out->var[k] = a->var[k] + tf * (b->var[k] - a->var[k]);
}

int clip_triangle(const struct vertex_out *const in[3], uint32_t planes, int n_var, double gx,
                  double gy, struct vertex_out out[CLIP_MAX_VERTS])
{
    static const uint32_t order[] = {VERTEX_OUT_NEAR,    VERTEX_OUT_FAR,      VERTEX_GUARD_LEFT,
                                     VERTEX_GUARD_RIGHT, VERTEX_GUARD_BOTTOM, VERTEX_GUARD_TOP};
    struct vertex_out buf[CLIP_MAX_VERTS];
    struct vertex_out *src = out, *dst = buf;
    int n = 3;
    for (int i = 0; i < 3; i++)
        src[i] = *in[i];
    for (unsigned p = 0; p < sizeof order / sizeof order[0]; p++) {
        uint32_t plane = order[p];
        if (!(planes & plane))
            continue;
        double d[CLIP_MAX_VERTS];
        int n_in = 0;
        for (int i = 0; i < n; i++) {
            d[i] = dist(plane, src[i].clip, gx, gy);
            n_in += d[i] >= 0;
        }
        if (n_in == n)
            continue;
        int m = 0;
        for (int i = 0; i < n; i++) {
            int j = i + 1 == n ? 0 : i + 1;
            int in_i = d[i] >= 0, in_j = d[j] >= 0;
            if (in_i)
                dst[m++] = src[i];
            if (in_i != in_j && m < CLIP_MAX_VERTS) {
                if (in_i)
                    lerp(&src[i], &src[j], d[i] / (d[i] - d[j]), n_var, &dst[m]);
                else
                    lerp(&src[j], &src[i], d[j] / (d[j] - d[i]), n_var, &dst[m]);
                dst[m].outcode = vertex_outcode(dst[m].clip, gx, gy);
                dst[m].projected = 0;
                if (dst[m].outcode & VERTEX_INVALID) /* huge inputs overflowed the lerp */
                    return 0;
                m++;
            }
        }
        n = m;
        struct vertex_out *t = src;
        src = dst;
        dst = t;
        if (n < 3)
            return 0;
    }
    if (src != out)
        memcpy(out, src, (size_t)n * sizeof *out);
    return n;
}
