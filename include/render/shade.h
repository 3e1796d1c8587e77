/* shade.h: fragment shading — the colour of one covered pixel.
 *
 * In:  interpolated varyings (layout in vertex.h), per-frame context (lights, eye, filter),
 *      per-triangle constants (material, texture, flat-shading light sums).
 * Out: linear rgb, clamped to [0,1] later by fb_quantize.
 * The formulas are light.h's. Everything is float, as a GPU would do it.
 * shade_fragment is static inline so the rasterizer's per-mode loops compile it in place:
 * the mode is a constant there and the switch disappears. */
#ifndef RASTTY_SHADE_H
#define RASTTY_SHADE_H

#include <math.h>

#include "light.h"
#include "mesh.h"
#include "render_opts.h"
#include "texture.h"
#include "vertex.h"

struct shade_ctx {
    enum shade_mode shade;
    enum debug_view view;
    enum tex_filter filter;
    int ortho;
    float eye[3];        /* world space */
    float view_back[3];  /* orthographic V */
    struct light_env lights;
};

struct shade_tri {
    const struct material *mat;
    float base[3];             /* light_base_color(): what the texel multiplies */
    const struct texture *tex; /* NULL: albedo = kd */
    float flat_d[3], flat_s[3]; /* flat mode: light.h's D and S for the whole triangle */
    bool vcolor;               /* the albedo is also multiplied by var[VARY_COLOR..+2] */
};

void shade_ctx_init(struct shade_ctx *c, const struct render_opts *o, const float eye[3],
                    int ortho, const float view_back[3]);

static inline void shade_albedo(const struct shade_ctx *c, const struct shade_tri *t,
                                const float *var, float lambda, float albedo_out[3])
{
    const float *kd = t->base;
    if (t->tex) {
        float tx[3];
        texture_sample(t->tex, c->filter, var[0], var[1], lambda, tx);
        albedo_out[0] = kd[0] * tx[0];
        albedo_out[1] = kd[1] * tx[1];
        albedo_out[2] = kd[2] * tx[2];
    } else {
        albedo_out[0] = kd[0], albedo_out[1] = kd[1], albedo_out[2] = kd[2];
    }
    if (t->vcolor)
        for (int k = 0; k < 3; k++)
            albedo_out[k] *= var[VARY_COLOR + k];
}

/* Per-pixel Blinn-Phong (phong mode): var = u v | world pos | world normal. */
static inline void shade_phong(const struct shade_ctx *c, const struct shade_tri *t,
                               const float *var, float d_out[3], float s_out[3])
{
    float n[3] = {var[5], var[6], var[7]}, vv[3];
    if (c->ortho) {
        vv[0] = c->view_back[0], vv[1] = c->view_back[1], vv[2] = c->view_back[2];
    } else {
        vv[0] = c->eye[0] - var[2], vv[1] = c->eye[1] - var[3], vv[2] = c->eye[2] - var[4];
        light_normalize(vv);
    }
    light_normalize(n);
    light_terms(&c->lights, n, vv, t->mat->ns, d_out, s_out);
}

/* One pixel: the colour from its varyings; lambda is its texture level of detail
 * (texture_lod, trilinear only; 0 otherwise). In every lane shade_fragment_v gives exactly
 * this. */
static inline void shade_fragment_lod(const struct shade_ctx *c, enum shade_mode mode,
                                    const struct shade_tri *t, const float *var, float lambda,
                                    float rgb_out[3])
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
    shade_albedo(c, t, var, lambda, albedo);
    switch (mode) {
    case SHADE_FLAT:
        light_combine(albedo, t->flat_d, t->flat_s, t->mat->ks, rgb_out);
        return;
    case SHADE_GOURAUD:
        if (c->lights.grey) { /* one D and one S for the three channels */
            const float dg = var[VARY_GOURAUD_D], sg = var[VARY_GOURAUD_S(true)];
            light_combine(albedo, (const float[3]){dg, dg, dg}, (const float[3]){sg, sg, sg},
                          t->mat->ks, rgb_out);
        } else {
            light_combine(albedo, var + VARY_GOURAUD_D, var + VARY_GOURAUD_S(false), t->mat->ks,
                          rgb_out);
        }
        return;
    case SHADE_PHONG:
        shade_phong(c, t, var, d, s);
        light_combine(albedo, d, s, t->mat->ks, rgb_out);
        return;
    default: /* unlit */
        rgb_out[0] = albedo[0], rgb_out[1] = albedo[1], rgb_out[2] = albedo[2];
        return;
    }
}

/* shade_fragment_lod without a level of detail (level 0) */
static inline void shade_fragment(const struct shade_ctx *c, enum shade_mode mode,
                                  const struct shade_tri *t, const float *var, float rgb_out[3])
{
    shade_fragment_lod(c, mode, t, var, 0, rgb_out);
}

/* A vector of pixels at once (SIMD_LANES; the normals view goes pixel by pixel through
 * shade_fragment): in every lane exactly what shade_fragment gives. var[k] holds varying k of
 * the pixels; lambda
 * their texture level of detail (texture_lod_v; trilinear only); filter is c->filter (an
 * argument so that a caller can make it a constant); pow_k is light_pow_int(t->mat->ns)
 * (phong only: computed once for many pixels). */
SIMD_INLINE void
shade_fragment_v(const struct shade_ctx *c, enum shade_mode mode, enum tex_filter filter,
                 const struct shade_tri *t, int pow_k, const vf *var, vf lambda, vf rgb_out[3])
{
    vf albedo[3];
    if (t->tex) {
        vf tx[3];
        texture_sample_v(t->tex, filter, var[0], var[1], lambda, tx);
        for (int k = 0; k < 3; k++)
            albedo[k] = vf_set(t->base[k]) * tx[k];
    } else {
        for (int k = 0; k < 3; k++)
            albedo[k] = vf_set(t->base[k]);
    }
    if (t->vcolor)
        for (int k = 0; k < 3; k++)
            albedo[k] *= var[VARY_COLOR + k];
    const float *ks = t->mat->ks;
    vf d[3], sp[3];
    if (mode == SHADE_PHONG) { /* as shade_phong */
        vf n[3] = {var[5], var[6], var[7]}, vv[3];
        if (c->ortho) {
            for (int k = 0; k < 3; k++)
                vv[k] = vf_set(c->view_back[k]);
        } else {
            for (int k = 0; k < 3; k++)
                vv[k] = vf_set(c->eye[k]) - var[2 + k];
            light_normalize_v(vv);
        }
        light_normalize_v(n);
        light_terms_k_v(&c->lights, n, vv, t->mat->ns, pow_k, d, sp);
    }
    if (mode == SHADE_GOURAUD && c->lights.grey) { /* the test outside the loop: unrolled */
        const vf dg = var[VARY_GOURAUD_D], sg = var[VARY_GOURAUD_S(true)];
        for (int k = 0; k < 3; k++)
            rgb_out[k] = albedo[k] * dg + vf_set(ks[k]) * sg;
        return;
    }
    for (int k = 0; k < 3; k++) {
        if (mode == SHADE_PHONG)
            rgb_out[k] = albedo[k] * d[k] + vf_set(ks[k]) * sp[k];
        else if (mode == SHADE_FLAT)
            rgb_out[k] = albedo[k] * vf_set(t->flat_d[k]) + vf_set(ks[k]) * vf_set(t->flat_s[k]);
        else if (mode == SHADE_GOURAUD)
            rgb_out[k] = albedo[k] * var[VARY_GOURAUD_D + k] +
                         vf_set(ks[k]) * var[VARY_GOURAUD_S(false) + k];
        else
            rgb_out[k] = albedo[k];
    }
}

#endif
