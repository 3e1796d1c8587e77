/* light.h: the lighting model — the one place that says how a lit point gets its colour.
 *
 * Every shading mode calls these: Gouraud per vertex (vertex.c), flat once per triangle
 * (pipeline.c), Phong per pixel (shade.h). Directional lights only: dir is the unit vector
 * TOWARD the light, world space; col is linear rgb (1 = white).
 *
 * With N the unit normal, V the unit vector toward the eye and H = normalize(L + V):
 *   D = A(N) + LIGHT_DIFFUSE * sum_l col_l * max(0, N.L)               ("diffuse term")
 *   A(N) = ground + (0.5 + 0.5 * N.y) * (sky - ground)                  (hemisphere ambient)
 *   S = sum_l col_l * max(0, N.H)^ns                                    ("specular term")
 *   c = albedo * D + ks * S, clamped to [0,1] by the framebuffer's quantiser
 * albedo = base colour x texel (texel = 1 without a texture); the base colour is the material's
 * Kd, except for a mesh's implicit material (no material named by the file) without a texture,
 * whose albedo is LIGHT_DEFAULT_ALBEDO — OpenGL's default material diffuse. At 1.0 the
 * highlight saturated a third of an untextured sphere to flat white. ks and ns come from the
 * material (defaults 0.5 and 32). Everything is float, as a GPU shader computes it; x^32 is
 * five squarings, as the reference shader writes it. Normals are never flipped for back faces.
 *
 * Ambient: render_opts' ambient_sky and ambient_ground, both LIGHT_AMBIENT by default — then
 * A(N) is exactly LIGHT_AMBIENT, the conventions' constant (render, dump, the Mesa oracle).
 * The headlight (--light camera, the viewer's default, light_use_camera) is a key light from
 * over the viewer's shoulder, a fill from the other side and a sky/ground hemisphere
 * ambient, as model viewers light a model: every side the camera looks at is lit, none goes
 * black in profile.
 *
 * Names: a function ending in _v is the vector twin of the one without (simd.h: every lane
 * gives exactly the scalar result; the reference kernel uses the scalar ones); _k means it
 * takes k = light_pow_int(ns), computed once for many points; _channels that it computes
 * the first nc colour channels (1 with grey lights) and copies channel 0 to the rest.
 *
 * glTF's colour spaces and materials (the man page's SHADING says it for users): the formula
 * above works on display values (sRGB-encoded), as the conventions' OBJ scenes and the Mesa
 * oracle define it, and OBJ, STL and PLY are drawn exactly so. glTF's colour factors and
 * vertex colours are linear and its colour textures sRGB: gltf.c encodes the factors and
 * vertex colours to display values at load (material_srgb_encode: 0.8 -> 231) and colour
 * textures are used as stored, so albedo = display(factor) x texel. Metallic-roughness and
 * specular-glossiness become Blinn-Phong (material_pbr_highlight): ns = 2 / a^2 - 2 with
 * a = roughness^2; ks = the reflectance f0 (0.04, or _ior/_specular's; a metal's base
 * colour) x (ns + 8) / 8, scaled under 1 and encoded. On the features path (shade.h) a
 * metal's diffuse is multiplied by 1 - metallic, a metal's highlight by max(0, N.L)
 * (light_terms_rich; a dielectric keeps the conventions' highlight, as the oracle's
 * globe.glb is drawn), the ambient by the occlusion texture; the encoded
 * emissive colour is added after. No environment light: a smooth metal shows only its
 * highlight. */
#ifndef RASTTY_LIGHT_H
#define RASTTY_LIGHT_H

#include <math.h>
#include <stdbool.h>

#include "camera.h"
#include "mesh.h"
#include "render_opts.h"
#include "simd.h"

#define LIGHT_AMBIENT 0.1f
#define LIGHT_DIFFUSE 0.9f
#define LIGHT_DEFAULT_ALBEDO 0.8f
/* The headlight: a key light from over the viewer's right shoulder and a weaker fill from
 * low on the left (camera-space directions toward them: right, up, toward the viewer; and
 * their colours), and the hemisphere ambient from above and from below. The fill keeps the
 * surfaces that face away from the key (the left-facing wall of a room, a ceiling) from
 * going black: with the key alone the Cornell box's green wall was at 0.21 ambient only. */
#define LIGHT_HEAD_RIGHT 0.35
#define LIGHT_HEAD_UP 0.5
#define LIGHT_HEAD_BACK 1.0
#define LIGHT_HEAD_COLOR 0.7
#define LIGHT_FILL_RIGHT (-0.6)
#define LIGHT_FILL_UP (-0.4)
#define LIGHT_FILL_BACK 0.6
#define LIGHT_FILL_COLOR 0.3
#define LIGHT_HEAD_SKY 0.35
#define LIGHT_HEAD_GROUND 0.2

/* The frame's lights, normalised and converted once per frame. */
struct light_env {
    int n;
    float dir[RENDER_MAX_LIGHTS][3]; /* unit, toward the light */
    float col[RENDER_MAX_LIGHTS][3];
    float sky[3], ground[3];         /* hemisphere ambient */
    bool grey; /* every light, the sky and the ground are grey (r = g = b; the default light
                  and the headlight): D and S are then the same in every channel, so they are
                  computed once (the same floats) and Gouraud carries one of each */
};

void light_env_init(struct light_env *env, const struct render_opts *o);
/* Replace o's lights by the headlight for camera c (see above). */
void light_use_camera(struct render_opts *o, const struct camera *c);

/* The base colour a texel (and a vertex colour) multiplies: kd_override (a scene's colour)
 * if given, else the material's Kd, else — implicit material, neither textured nor
 * vertex-coloured (`textured` says either) — LIGHT_DEFAULT_ALBEDO. A vertex colour is the
 * model's own diffuse colour, as glColorMaterial makes it. */
void light_base_color(const struct material *m, const float *kd_override, int textured,
                      float base_out[3]);

/* x^n. A whole n from 1 to LIGHT_POW_INT_MAX (every shared model's Ns) by squaring, exactly
 * as the reference shader (32: five squarings); any other n through powf. */
#define LIGHT_POW_INT_MAX 1024

static inline int light_pow_int(float n)
{
    return n >= 1 && n <= LIGHT_POW_INT_MAX && n == (float)(int)n ? (int)n : 0;
}

static inline float light_pow(float x, float n)
{
    int k = light_pow_int(n);
    if (k == 32) { /* the default Ns: five squarings (the loop below's 1 * x is exact) */
        x *= x, x *= x, x *= x, x *= x;
        return x * x;
    }
    if (k) {
        float r = 1;
        for (;;) {
            if (k & 1)
                r *= x;
            if ((k >>= 1) == 0)
                return r;
            x *= x;
        }
    }
    return x > 0 || n <= 0 ? powf(x, n) : 0; /* 0^n = 0 exactly (n > 0): skip the call */
}

/* one light's max(0, N.L) and max(0, N.H)^ns; l, n and v unit length, H = normalize(L+V) */
static inline void light_one(const float l[3], const float n[3], const float v[3], float ns,
                             float *dd, float *ss)
{
    float h[3] = {l[0] + v[0], l[1] + v[1], l[2] + v[2]};
    float hl = sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    float ih = hl > 0 ? 1.0f / hl : 0;
    float ndl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
    float ndh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) * ih;
    *dd = ndl > 0 ? ndl : 0;
    *ss = light_pow(ndh > 0 ? ndh : 0, ns);
}

/* light_terms' sums for the first nc channels (1 with grey lights, else 3); the others
 * copy channel 0 */
static inline void light_terms_channels(const struct light_env *env, const float n[3],
                                        const float v[3], float ns, const int nc,
                                        float d_out[3], float s_out[3])
{
    float d[3] = {0, 0, 0}, s[3] = {0, 0, 0};
    for (int i = 0; i < env->n; i++) {
        const float *col = env->col[i];
        float dd, ss;
        light_one(env->dir[i], n, v, ns, &dd, &ss);
        for (int k = 0; k < nc; k++) {
            d[k] += dd * col[k];
            s[k] += ss * col[k];
        }
    }
    float up = 0.5f + 0.5f * n[1];
    for (int k = 0; k < nc; k++) {
        float sky = env->sky[k], ground = env->ground[k];
        float a = sky == ground ? sky : ground + up * (sky - ground); /* exact when constant */
        d_out[k] = a + LIGHT_DIFFUSE * d[k];
        s_out[k] = s[k];
    }
    for (int k = nc; k < 3; k++)
        d_out[k] = d_out[0], s_out[k] = s_out[0];
}

/* D and S (see above) at one point; n and v unit length. Grey lights: one channel computed
 * (the same floats as the others'). */
static inline void light_terms(const struct light_env *env, const float n[3], const float v[3],
                               float ns, float d_out[3], float s_out[3])
{
    if (env->grey)
        light_terms_channels(env, n, v, ns, 1, d_out, s_out);
    else
        light_terms_channels(env, n, v, ns, 3, d_out, s_out);
}

/* The features path's light sums (phong, shade.h): light_terms over every channel, with
 * the ambient scaled by occ (glTF's occlusion texture) and the direct diffuse by kdiff
 * (1 - metallic: a metal's colour is in its highlight and its surroundings, not in its
 * diffuse). pbr (a glTF metal, metallic > 0): each light's highlight is also weighted by
 * max(0, N.L),
 * as a microfacet BRDF's radiance is (f * N.L): a rough metal's broad lobe (ns 1) would
 * otherwise light faces turned from the light as brightly as those facing it (glTF's
 * default material, metallic 1 and roughness 1, drew a red box at 255 on every face; the
 * sample viewer shows 147, 123 and 70). */
static inline void light_terms_rich(const struct light_env *env, const float n[3],
                                    const float v[3], float ns, float occ, float kdiff,
                                    bool pbr, float d_out[3], float s_out[3])
{
    float d[3] = {0, 0, 0}, s[3] = {0, 0, 0};
    for (int i = 0; i < env->n; i++) {
        const float *col = env->col[i];
        float dd, ss;
        light_one(env->dir[i], n, v, ns, &dd, &ss);
        if (pbr)
            ss *= dd;
        for (int k = 0; k < 3; k++) {
            d[k] += dd * col[k];
            s[k] += ss * col[k];
        }
    }
    float up = 0.5f + 0.5f * n[1];
    for (int k = 0; k < 3; k++) {
        float sky = env->sky[k], ground = env->ground[k];
        float a = sky == ground ? sky : ground + up * (sky - ground);
        d_out[k] = a * occ + LIGHT_DIFFUSE * kdiff * d[k];
        s_out[k] = s[k];
    }
}

/* c = albedo * D + ks * S (unclamped) */
static inline void light_combine(const float albedo[3], const float d[3], const float s[3],
                                 const float ks[3], float rgb_out[3])
{
    for (int k = 0; k < 3; k++)
        rgb_out[k] = albedo[k] * d[k] + ks[k] * s[k];
}

/* v / |v| in float; the zero vector stays zero */
static inline void light_normalize(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    float il = l > 0 ? 1.0f / l : 0;
    v[0] *= il, v[1] *= il, v[2] *= il;
}

/* light_normalize, a vector of vectors at once (v[k] holds component k of each lane's) */
SIMD_INLINE void light_normalize_v(vf v[3])
{
    vf l = vf_sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    vi pos = l > vf_set(0);
    vf il = vf_select(pos, vf_set(1.0f) / vf_select(pos, l, vf_set(1)), vf_set(0));
    v[0] *= il, v[1] *= il, v[2] *= il;
}

/* x^n in each lane, exactly as light_pow; k = light_pow_int(n), which callers compute once
 * for many pixels. A power of two is that many squarings (square-and-multiply would only add
 * a final 1 * x, which is exact). */
static inline vf light_pow_k_v(vf x, int k, float n)
{
    if (k == 32) { /* the default Ns: five squarings, no loop */
        x *= x, x *= x, x *= x, x *= x;
        return x * x;
    }
    if (k && (k & (k - 1)) == 0) {
        for (; k > 1; k >>= 1)
            x *= x;
        return x;
    }
    if (k) {
        vf r = vf_set(1);
        for (;;) {
            if (k & 1)
                r *= x;
            if ((k >>= 1) == 0)
                return r;
            x *= x;
        }
    }
    vf r;
    for (int l = 0; l < SIMD_LANES; l++) /* 0^n = 0 exactly: most lanes face away */
        r[l] = x[l] > 0 || n <= 0 ? powf(x[l], n) : 0;
    return r;
}

static inline vf light_pow_v(vf x, float n)
{
    return light_pow_k_v(x, light_pow_int(n), n);
}

/* One light's diffuse and specular factors for every lane's point: max(0, N.L) and
 * max(0, N.H)^ns with H = normalize(L + V) (pow_k = light_pow_int(ns)) */
SIMD_INLINE void
light_one_v(const float l[3], const vf n[3], const vf v[3], float ns, int pow_k, vf *dd_out,
            vf *ss_out)
{
    vf h[3] = {vf_set(l[0]) + v[0], vf_set(l[1]) + v[1], vf_set(l[2]) + v[2]};
    vf hl = vf_sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    vi pos = hl > vf_set(0);
    vf ih = vf_select(pos, vf_set(1.0f) / vf_select(pos, hl, vf_set(1)), vf_set(0));
    vf ndl = n[0] * vf_set(l[0]) + n[1] * vf_set(l[1]) + n[2] * vf_set(l[2]);
    vf ndh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) * ih;
    *dd_out = vf_max(ndl, vf_set(0));
    *ss_out = light_pow_k_v(vf_max(ndh, vf_set(0)), pow_k, ns);
}

/* the hemisphere ambient of channel k, up = (1 + n.y) / 2 */
static inline vf light_ambient_v(const struct light_env *env, vf up, int k)
{
    float sky = env->sky[k], ground = env->ground[k];
    return sky == ground ? vf_set(sky) : vf_set(ground) + up * vf_set(sky - ground);
}

/* light_terms_k_v's sums for the first nc channels (1 with grey lights, else 3) */
SIMD_INLINE void
light_terms_channels_v(const struct light_env *env, const vf n[3], const vf v[3], float ns,
                       int pow_k, const int nc, vf d_out[3], vf s_out[3])
{
    vf up = vf_set(0.5f) + vf_set(0.5f) * n[1], dd, ss;
    if (env->n == 1) { /* one light (the default): no sums to keep, fewer registers */
        const float *col = env->col[0];
        light_one_v(env->dir[0], n, v, ns, pow_k, &dd, &ss);
        for (int k = 0; k < nc; k++) { /* as below with d = 0 + dd col, s = 0 + ss col */
            d_out[k] = light_ambient_v(env, up, k) + vf_set(LIGHT_DIFFUSE) * (dd * vf_set(col[k]));
            s_out[k] = ss * vf_set(col[k]);
        }
    } else {
        vf d[3] = {vf_set(0), vf_set(0), vf_set(0)}, s[3] = {vf_set(0), vf_set(0), vf_set(0)};
        for (int i = 0; i < env->n; i++) {
            const float *col = env->col[i];
            light_one_v(env->dir[i], n, v, ns, pow_k, &dd, &ss);
            for (int k = 0; k < nc; k++) {
                d[k] += dd * vf_set(col[k]);
                s[k] += ss * vf_set(col[k]);
            }
        }
        for (int k = 0; k < nc; k++) {
            d_out[k] = light_ambient_v(env, up, k) + vf_set(LIGHT_DIFFUSE) * d[k];
            s_out[k] = s[k];
        }
    }
    for (int k = nc; k < 3; k++) /* grey: channel 0's floats are the others' */
        d_out[k] = d_out[0], s_out[k] = s_out[0];
}

/* light_terms for every lane's point (n, v: unit vectors, one component per vector): in
 * every lane exactly what light_terms gives. Grey lights compute one channel (each copy
 * with a loop of known length: the terms stay in registers). */
SIMD_INLINE void
light_terms_k_v(const struct light_env *env, const vf n[3], const vf v[3], float ns, int pow_k,
                vf d_out[3], vf s_out[3])
{
    if (env->grey)
        light_terms_channels_v(env, n, v, ns, pow_k, 1, d_out, s_out);
    else
        light_terms_channels_v(env, n, v, ns, pow_k, 3, d_out, s_out);
}

/* light_terms_k_v with pow_k = light_pow_int(ns) */
static inline void light_terms_v(const struct light_env *env, const vf n[3], const vf v[3],
                                 float ns, vf d_out[3], vf s_out[3])
{
    light_terms_k_v(env, n, v, ns, light_pow_int(ns), d_out, s_out);
}

#endif
