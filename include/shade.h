/* shade.h: fragment shading — the colour of one covered pixel.
 *
 * In:  interpolated varyings (layout in vertex.h), per-frame context (lights, eye, filter),
 *      per-triangle constants (material, texture, flat-shading light sums).
 * Out: linear rgb, clamped to [0,1] later by fb_quantize.
 * The formulas are the conventions' (render.h). Everything is float, as a GPU would do it.
 * shade_fragment is static inline so the rasterizer's per-mode loops compile it in place:
 * the mode is a constant there and the switch disappears. */
#ifndef RASTTY_SHADE_H
#define RASTTY_SHADE_H

#include <math.h>

#include "mesh.h"
#include "render.h"
#include "texture.h"

struct shade_ctx {
    enum shade_mode shade;
    enum debug_view view;
    enum tex_filter filter;
    int ortho;
    float eye[3];        /* world space */
    float view_back[3];  /* orthographic V */
    int n_lights;
    float light_dir[RENDER_MAX_LIGHTS][3]; /* unit, toward the light */
    float light_col[RENDER_MAX_LIGHTS][3];
};

struct shade_tri {
    const struct material *mat;
    const float *kd;           /* mat->kd, or the draw item's override */
    const struct texture *tex; /* NULL: albedo = kd */
    float flat_d[3], flat_s[3]; /* flat mode: light sums for the whole triangle */
};

void shade_ctx_init(struct shade_ctx *c, const struct render_opts *o, const float eye[3],
                    int ortho, const float view_back[3]);

static inline float shade_pow(float x, float n)
{
    if (n == 32.0f) { /* five squarings, exactly as the reference shader */
        x *= x;
        x *= x;
        x *= x;
        x *= x;
        return x * x;
    }
    return powf(x, n);
}

static inline void shade_albedo(const struct shade_ctx *c, const struct shade_tri *t,
                                const float *var, float albedo_out[3])
{
    const float *kd = t->kd;
    if (t->tex) {
        float tx[3];
        texture_sample(t->tex, c->filter, var[0], var[1], tx);
        albedo_out[0] = kd[0] * tx[0];
        albedo_out[1] = kd[1] * tx[1];
        albedo_out[2] = kd[2] * tx[2];
    } else {
        albedo_out[0] = kd[0], albedo_out[1] = kd[1], albedo_out[2] = kd[2];
    }
}

static inline void shade_combine(const struct shade_tri *t, const float albedo[3], const float d[3],
                                 const float s[3], float rgb_out[3])
{
    const float *ks = t->mat->ks;
    for (int k = 0; k < 3; k++)
        rgb_out[k] = albedo[k] * (0.1f + 0.9f * d[k]) + ks[k] * s[k];
}

/* Per-pixel Blinn-Phong (phong mode): var = u v | world pos | world normal. */
static inline void shade_phong(const struct shade_ctx *c, const struct shade_tri *t,
                               const float *var, float d_out[3], float s_out[3])
{
    float n[3] = {var[5], var[6], var[7]};
    float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    float vv[3];
    if (c->ortho) {
        vv[0] = c->view_back[0], vv[1] = c->view_back[1], vv[2] = c->view_back[2];
    } else {
        vv[0] = c->eye[0] - var[2], vv[1] = c->eye[1] - var[3], vv[2] = c->eye[2] - var[4];
        float vl = sqrtf(vv[0] * vv[0] + vv[1] * vv[1] + vv[2] * vv[2]);
        float iv = vl > 0 ? 1.0f / vl : 0;
        vv[0] *= iv, vv[1] *= iv, vv[2] *= iv;
    }
    float in = nl > 0 ? 1.0f / nl : 0;
    n[0] *= in, n[1] *= in, n[2] *= in;
    d_out[0] = d_out[1] = d_out[2] = 0;
    s_out[0] = s_out[1] = s_out[2] = 0;
    for (int i = 0; i < c->n_lights; i++) {
        const float *l = c->light_dir[i], *col = c->light_col[i];
        float h[3] = {l[0] + vv[0], l[1] + vv[1], l[2] + vv[2]};
        float hl = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
        float ih = hl > 0 ? 1.0f / hl : 0;
        float ndl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
        float ndh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) * ih;
        float dd = ndl > 0 ? ndl : 0;
        float ss = shade_pow(ndh > 0 ? ndh : 0, t->mat->ns);
        for (int k = 0; k < 3; k++) {
            d_out[k] += dd * col[k];
            s_out[k] += ss * col[k];
        }
    }
}

static inline void shade_fragment(const struct shade_ctx *c, enum shade_mode mode,
                                  const struct shade_tri *t, const float *var, float rgb_out[3])
{
    float albedo[3], d[3], s[3];
    if (c->view == VIEW_NORMALS) {
        float n[3] = {var[5], var[6], var[7]};
        float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float in = nl > 0 ? 0.5f / nl : 0;
        for (int k = 0; k < 3; k++)
            rgb_out[k] = n[k] * in + 0.5f;
        return;
    }
    shade_albedo(c, t, var, albedo);
    switch (mode) {
    case SHADE_FLAT:
        shade_combine(t, albedo, t->flat_d, t->flat_s, rgb_out);
        return;
    case SHADE_GOURAUD:
        shade_combine(t, albedo, var + 2, var + 5, rgb_out);
        return;
    case SHADE_PHONG:
        shade_phong(c, t, var, d, s);
        shade_combine(t, albedo, d, s, rgb_out);
        return;
    default: /* unlit */
        rgb_out[0] = albedo[0], rgb_out[1] = albedo[1], rgb_out[2] = albedo[2];
        return;
    }
}

#endif
