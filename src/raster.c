/* raster.c: the edge-function rasterizer (see raster.h). */
#include "raster.h"

/* One loop, instantiated per shading mode by the switch in raster_triangle: `mode` is a
 * compile-time constant in each copy, so shade_fragment's switch folds away. */
static inline void walk(const struct setup_tri *t, const struct shade_ctx *c,
                        const struct shade_tri *st, struct fb *fb, struct frame_stats *stats,
                        const enum shade_mode mode)
{
    uint64_t tested = 0, shaded = 0;
    const int n_var = t->n_var;
    int64_t r0 = t->e[0], r1 = t->e[1], r2 = t->e[2];
    for (int y = t->y0; y <= t->y1; y++) {
        int64_t e0 = r0, e1 = r1, e2 = r2;
        size_t row = (size_t)y * (size_t)fb->w;
        double dy = y - t->y0;
        for (int x = t->x0; x <= t->x1; x++) {
            if ((e0 | e1 | e2) >= 0) {
                size_t i = row + (size_t)x;
                double dx = x - t->x0;
                double l0 = t->lam[0] + dx * t->lam_dx[0] + dy * t->lam_dy[0];
                double l1 = t->lam[1] + dx * t->lam_dx[1] + dy * t->lam_dy[1];
                double l2 = t->lam[2] + dx * t->lam_dx[2] + dy * t->lam_dy[2];
                float z = (float)(l0 * t->z[0] + l1 * t->z[1] + l2 * t->z[2]);
                tested++;
                if (fb->overdraw)
                    fb->overdraw[i]++;
                if (z < fb->depth[i]) {
                    fb->depth[i] = z;
                    shaded++;
                    if (mode != SHADE_WIRE) {
                        float var[VARY_MAX], rgb[3];
                        double q0 = l0 * t->rw[0], q1 = l1 * t->rw[1], q2 = l2 * t->rw[2];
                        double inv = 1.0 / (q0 + q1 + q2);
                        float b0 = (float)(q0 * inv), b1 = (float)(q1 * inv), b2 = (float)(q2 * inv);
                        for (int k = 0; k < n_var; k++)
                            var[k] = b0 * t->var[0][k] + b1 * t->var[1][k] + b2 * t->var[2][k];
                        shade_fragment(c, mode, st, var, rgb);
                        fb->rgb[3 * i + 0] = fb_quantize(rgb[0]);
                        fb->rgb[3 * i + 1] = fb_quantize(rgb[1]);
                        fb->rgb[3 * i + 2] = fb_quantize(rgb[2]);
                    }
                }
            }
            e0 += t->e_dx[0];
            e1 += t->e_dx[1];
            e2 += t->e_dx[2];
        }
        r0 += t->e_dy[0];
        r1 += t->e_dy[1];
        r2 += t->e_dy[2];
    }
    stats->pixels_tested += tested;
    stats->pixels_shaded += shaded;
}

void raster_triangle(const struct setup_tri *t, const struct shade_ctx *c,
                     const struct shade_tri *st, struct fb *fb, struct frame_stats *stats)
{
    switch (c->view == VIEW_NORMALS ? SHADE_PHONG : c->shade) {
    case SHADE_UNLIT: walk(t, c, st, fb, stats, SHADE_UNLIT); break;
    case SHADE_FLAT: walk(t, c, st, fb, stats, SHADE_FLAT); break;
    case SHADE_GOURAUD: walk(t, c, st, fb, stats, SHADE_GOURAUD); break;
    case SHADE_PHONG: walk(t, c, st, fb, stats, SHADE_PHONG); break;
    default: walk(t, c, st, fb, stats, SHADE_WIRE); break;
    }
}
