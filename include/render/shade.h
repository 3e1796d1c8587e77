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
#include "material.h"
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

/* What the features path needs of a draw item (one per item and pass in the frame: frame.h):
 * its varyings' layout, its normal matrix (object-space normal maps) and its textures. */
struct rich_item {
    struct vary_rich lay;
    float nmat[3][3];                /* object -> world for normals, row-major */
    const struct texture *textures;  /* the mesh's (every slot's index is into them) */
    bool textures_on;                /* --no-texture: none is sampled */
};

struct shade_tri {
    const struct material *mat;
    float base[3];             /* light_base_color(): what the texel multiplies */
    const struct texture *tex; /* NULL: albedo = kd */
    float flat_d[3], flat_s[3]; /* flat mode: light.h's D and S for the whole triangle */
    bool vcolor;               /* the albedo is also multiplied by var[VARY_COLOR..+2] */
    bool back;                 /* the features path: the source triangle faces away */
    const struct rich_item *rich; /* the features path's item (mesh.features), else NULL */
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

/* ---- the features path (mesh.h: materials with features; scalar in every kernel) ---- */

/* A pixel's derivatives: the interpolation planes' steps (setup.h) and 1 / q there, so a
 * texture slot's level of detail follows its own uv set and transform. */
struct rich_pixel {
    const float *a_dx, *a_dy; /* the varyings' planes, all[] order */
    float q_dx, q_dy, rq;
};

/* a slot's uv and its screen derivatives at the pixel (transform applied) */
static inline void shade_slot_uv(const struct tex_slot *sl, const struct vary_rich *L,
                                 const float *all, const struct rich_pixel *px, float uv[2],
                                 float d[4])
{
    int o = sl->uv == 1 && L->uv1 >= 0 ? L->uv1 : L->uv0;
    float u = all[o], v = all[o + 1];
    float dudx = (px->a_dx[o] - u * px->q_dx) * px->rq, dvdx = (px->a_dx[o + 1] - v * px->q_dx) * px->rq;
    float dudy = (px->a_dy[o] - u * px->q_dy) * px->rq, dvdy = (px->a_dy[o + 1] - v * px->q_dy) * px->rq;
    if (sl->xform) {
        const float *x = sl->xf;
        uv[0] = x[0] * u + x[1] * v + x[2];
        uv[1] = x[3] * u + x[4] * v + x[5];
        d[0] = x[0] * dudx + x[1] * dvdx, d[1] = x[3] * dudx + x[4] * dvdx;
        d[2] = x[0] * dudy + x[1] * dvdy, d[3] = x[3] * dudy + x[4] * dvdy;
    } else {
        uv[0] = u, uv[1] = v;
        d[0] = dudx, d[1] = dvdx, d[2] = dudy, d[3] = dvdy;
    }
    if (sl->tile) { /* (the tile's own repeat; its texels per unit scale the derivatives) */
        const float *r = sl->rect;
        uv[0] = r[0] + (uv[0] - floorf(uv[0])) * r[2];
        uv[1] = r[1] + (uv[1] - floorf(uv[1])) * r[3];
        d[0] *= r[2], d[1] *= r[3], d[2] *= r[2], d[3] *= r[3];
    }
}

/* slot sl of texture t sampled at the pixel: rgba */
static inline void shade_slot(const struct shade_ctx *c, const struct texture *t,
                              const struct tex_slot *sl, const struct vary_rich *L,
                              const float *all, const struct rich_pixel *px, float out[4])
{
    float uv[2], d[4], lambda = 0;
    shade_slot_uv(sl, L, all, px, uv, d);
    enum tex_filter f = sl->nearest ? TEX_NEAREST : c->filter;
    if (f == TEX_TRILINEAR)
        lambda = texture_lod(t, d[0], d[1], d[2], d[3]);
    texture_sample_wrap(t, f, sl->wrap[0], sl->wrap[1], uv[0], uv[1], lambda, out);
}

/* the features path's normal at the pixel (world space, unit): the interpolated one (turned
 * for a back face of a two-sided material), bent by the normal map */
static inline void shade_rich_normal(const struct shade_ctx *c, const struct shade_tri *t,
                                     const float *all, const struct rich_pixel *px, float n[3])
{
    const struct material *m = t->mat;
    const struct rich_item *R = t->rich;
    const struct vary_rich *L = &R->lay;
    n[0] = all[L->nrm], n[1] = all[L->nrm + 1], n[2] = all[L->nrm + 2];
    light_normalize(n);
    if (t->back && m->sides == MAT_TWO_SIDED)
        n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
    if (m->normal_map.tex < 0 || !R->textures_on)
        return;
    float tx[4];
    shade_slot(c, &R->textures[m->normal_map.tex], &m->normal_map, L, all, px, tx);
    float x = 2 * tx[0] - 1, y = 2 * tx[1] - 1, z = 2 * tx[2] - 1;
    if (m->normal_space == MAT_NORMAL_OBJECT) {
        const float(*a)[3] = R->nmat;
        float w[3];
        for (int r = 0; r < 3; r++)
            w[r] = a[r][0] * x + a[r][1] * y + a[r][2] * z;
        light_normalize(w);
        if (w[0] != 0 || w[1] != 0 || w[2] != 0)
            n[0] = w[0], n[1] = w[1], n[2] = w[2];
        return;
    }
    if (L->tan < 0)
        return;
    x *= m->normal_scale, y *= m->normal_scale;
    float tg[3] = {all[L->tan], all[L->tan + 1], all[L->tan + 2]};
    float sgn = all[L->tan + 3] < 0 ? -1.0f : 1.0f;
    if (t->back && m->sides == MAT_TWO_SIDED)
        sgn = -sgn; /* (the normal turned: the bitangent keeps its direction) */
    float d = tg[0] * n[0] + tg[1] * n[1] + tg[2] * n[2];
    for (int k = 0; k < 3; k++)
        tg[k] -= n[k] * d;
    light_normalize(tg);
    float b[3] = {sgn * (n[1] * tg[2] - n[2] * tg[1]), sgn * (n[2] * tg[0] - n[0] * tg[2]),
                  sgn * (n[0] * tg[1] - n[1] * tg[0])};
    float w[3];
    for (int k = 0; k < 3; k++)
        w[k] = tg[k] * x + b[k] * y + n[k] * z;
    light_normalize(w);
    if (w[0] != 0 || w[1] != 0 || w[2] != 0)
        n[0] = w[0], n[1] = w[1], n[2] = w[2];
}

/* One pixel of the features path: its colour and alpha from all[] (the interpolated
 * varyings, struct vary_rich) — base colour x texture (its slot's uv set, wrap and
 * transform) x vertex colour, alpha (MASK: 0 below the cutoff, the pixel discarded; BLEND:
 * returned for the blend), unlit, the normal map, occlusion, the per-pixel highlight of a
 * metallic-roughness or specular-glossiness texture, emission. 0: discarded. Every kernel
 * draws these pixels through this one function. */
static inline int shade_rich(const struct shade_ctx *c, enum shade_mode mode,
                             const struct shade_tri *t, const float *all,
                             const struct rich_pixel *px, float rgb_out[3], float *alpha_out)
{
    const struct material *m = t->mat;
    const struct rich_item *R = t->rich;
    const struct vary_rich *L = &R->lay;
    float albedo[3] = {t->base[0], t->base[1], t->base[2]}, alpha = m->alpha, tx[4];
    float texel[3] = {1, 1, 1};
    if (t->tex) {
        shade_slot(c, t->tex, &m->base, L, all, px, tx);
        for (int k = 0; k < 3; k++)
            albedo[k] *= tx[k], texel[k] = tx[k];
        alpha *= tx[3];
    }
    if (L->col >= 0) {
        for (int k = 0; k < 3; k++)
            albedo[k] *= all[L->col + k];
        if (L->col_n == 4)
            alpha *= all[L->col + 3];
    }
    if (m->alpha_map.tex >= 0 && R->textures_on) {
        shade_slot(c, &R->textures[m->alpha_map.tex], &m->alpha_map, L, all, px, tx);
        alpha *= tx[0];
    }
    if (m->alpha_mode == MAT_MASK) {
        if (!(alpha >= m->alpha_cutoff))
            return 0;
        alpha = 1;
    } else if (m->alpha_mode == MAT_BLEND) {
        if (!(alpha > 0))
            return 0;
        alpha = alpha < 1 ? alpha : 1;
    } else {
        alpha = 1;
    }
    *alpha_out = alpha;
    if (c->view == VIEW_NORMALS) {
        float n[3];
        shade_rich_normal(c, t, all, px, n);
        for (int k = 0; k < 3; k++)
            rgb_out[k] = n[k] * 0.5f + 0.5f;
        return 1;
    }
    if (mode == SHADE_UNLIT || m->unlit) {
        rgb_out[0] = albedo[0], rgb_out[1] = albedo[1], rgb_out[2] = albedo[2];
        return 1;
    }
    float e[3] = {m->emissive[0], m->emissive[1], m->emissive[2]};
    if (m->emissive_map.tex >= 0 && R->textures_on) {
        shade_slot(c, &R->textures[m->emissive_map.tex], &m->emissive_map, L, all, px, tx);
        for (int k = 0; k < 3; k++)
            e[k] *= tx[k];
    }
    /* the highlight: the material's, or per pixel when its texture, or the base colour a
     * metal's highlight takes, varies (material_pbr_highlight; light.h) */
    float ks[3] = {m->ks[0], m->ks[1], m->ks[2]}, ns = m->ns;
    float metal = m->pbr && m->metallic > 0 ? m->metallic : 0, rough = m->roughness;
    float f0[3] = {m->spec_lin[0], m->spec_lin[1], m->spec_lin[2]};
    bool per_px = false;
    if (m->spec_map.tex >= 0 && R->textures_on) {
        shade_slot(c, &R->textures[m->spec_map.tex], &m->spec_map, L, all, px, tx);
        if (m->metallic >= 0) { /* metallic-roughness: G roughness, B metallic */
            metal = m->metallic * tx[2];
            rough = m->roughness * tx[1];
        } else { /* specular-glossiness: rgb specular (sRGB), alpha glossiness */
            for (int k = 0; k < 3; k++)
                f0[k] *= material_srgb_decode(tx[k]);
            rough = 1 - (1 - m->roughness) * tx[3];
        }
        per_px = true;
    }
    if (per_px || (metal > 0 && t->tex)) {
        float base[3] = {m->base_lin[0], m->base_lin[1], m->base_lin[2]};
        if (t->tex) /* a metal's highlight is its base colour: the texel's too */
            for (int k = 0; k < 3; k++)
                base[k] *= material_srgb_decode(texel[k]);
        material_pbr_highlight(base, f0, metal, rough, ks, &ns);
    }
    float kdiff = 1 - metal, occ = 1;
    if (m->occlusion_map.tex >= 0 && R->textures_on) {
        shade_slot(c, &R->textures[m->occlusion_map.tex], &m->occlusion_map, L, all, px, tx);
        occ = 1 + m->occlusion_strength * (tx[0] - 1);
    }
    float d[3], s[3];
    if (mode == SHADE_FLAT) {
        for (int k = 0; k < 3; k++)
            d[k] = t->flat_d[k], s[k] = t->flat_s[k];
    } else if (mode == SHADE_GOURAUD) {
        int g = c->lights.grey;
        for (int k = 0; k < 3; k++)
            d[k] = all[L->d + (g ? 0 : k)], s[k] = all[L->s + (g ? 0 : k)];
    } else {
        float n[3], v[3];
        shade_rich_normal(c, t, all, px, n);
        if (c->ortho) {
            v[0] = c->view_back[0], v[1] = c->view_back[1], v[2] = c->view_back[2];
        } else {
            v[0] = c->eye[0] - all[0], v[1] = c->eye[1] - all[1], v[2] = c->eye[2] - all[2];
            light_normalize(v);
        }
        light_terms_rich(&c->lights, n, v, ns, occ, kdiff, metal > 0, d, s);
    }
    for (int k = 0; k < 3; k++)
        rgb_out[k] = albedo[k] * d[k] + ks[k] * s[k] + e[k];
    return 1;
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
