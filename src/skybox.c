/* skybox.c: cube-map background (see skybox.h). */
#include "skybox.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "simd.h"
#include "span.h"
#include "texture.h"

/* This file is compiled twice on x86-64 (Makefile), as span.c is: the second copy, with
 * -mavx2 -DSIMD_LANES=8 -DSKYBOX_AVX2_COPY, makes only skybox_draw_rows_avx2 (eight lanes,
 * gathers), used when the span stage runs on AVX2 — the same C, so the same bytes. */
void skybox_draw_rows_avx2(const struct skybox *s, const struct camera *cam, struct fb *fb,
                           int y0, int y1);
#ifdef SKYBOX_AVX2_COPY
#define SKYBOX_DRAW_ROWS skybox_draw_rows_avx2
#else
#define SKYBOX_DRAW_ROWS sky_rows_base

/* GL cube-map table: face of the major axis, its sc/tc coordinates */
static int face_of(vec3 d, double *sc, double *tc, double *ma)
{
    double ax = fabs(d.x), ay = fabs(d.y), az = fabs(d.z);
    if (ax >= ay && ax >= az) {
        *ma = ax;
        *tc = -d.y;
        *sc = d.x > 0 ? -d.z : d.z;
        return d.x > 0 ? 0 : 1;
    }
    if (ay >= az) {
        *ma = ay;
        *sc = d.x;
        *tc = d.y > 0 ? d.z : -d.z;
        return d.y > 0 ? 2 : 3;
    }
    *ma = az;
    *tc = -d.y;
    *sc = d.z > 0 ? d.x : -d.x;
    return d.z > 0 ? 4 : 5;
}

/* inverse: the direction of face coordinates (sc, tc in [-1,1], may exceed for borders) */
static vec3 dir_of(int face, double sc, double tc)
{
    switch (face) {
    case 0: return v3(1, -tc, -sc);
    case 1: return v3(-1, -tc, sc);
    case 2: return v3(sc, 1, tc);
    case 3: return v3(sc, -1, -tc);
    case 4: return v3(sc, -tc, 1);
    default: return v3(-sc, -tc, -1);
    }
}

static inline uint8_t *texel(const struct skybox_level *l, int face, int i, int j)
{
    /* i, j in [-1, n]: interior plus border */
    return l->rgb[face] + ((size_t)(j + 1) * (size_t)(l->n + 2) + (size_t)(i + 1)) * 4;
}

/* border texel (i, j) of face f: the nearest interior texel of the neighbouring face in
 * that direction */
static void fill_border_texel(struct skybox_level *l, int f, int i, int j)
{
    int n = l->n;
    vec3 d = dir_of(f, 2.0 * (i + 0.5) / n - 1, 2.0 * (j + 0.5) / n - 1);
    double sc, tc, ma;
    int g = face_of(d, &sc, &tc, &ma);
    int si = (int)floor((sc / ma + 1) * 0.5 * n), sj = (int)floor((tc / ma + 1) * 0.5 * n);
    si = si < 0 ? 0 : si >= n ? n - 1 : si;
    sj = sj < 0 ? 0 : sj >= n ? n - 1 : sj;
    memcpy(texel(l, f, i, j), texel(l, g, si, sj), 4);
}

/* every face's border (its sources are interior texels: any order gives the same bytes) */
static void fill_border(struct skybox_level *l)
{
    int n = l->n;
    for (int f = 0; f < 6; f++) {
        for (int i = -1; i <= n; i++) { /* the rows above and below */
            fill_border_texel(l, f, i, -1);
            fill_border_texel(l, f, i, n);
        }
        for (int j = 0; j < n; j++) { /* the columns left and right */
            fill_border_texel(l, f, -1, j);
            fill_border_texel(l, f, n, j);
        }
    }
}

/* the six faces in one block, one after another (the sky's gathers index all of them from
 * rgb[0]) */
static int alloc_level(struct skybox_level *l, int n)
{
    size_t face = (size_t)(n + 2) * (size_t)(n + 2) * 4;
    l->n = n;
    if (!(l->rgb[0] = calloc(6, face)))
        return -1;
    for (int f = 1; f < 6; f++)
        l->rgb[f] = l->rgb[0] + f * face;
    return 0;
}

/* levels 1.. by 2x2 box filtering; every level gets its border */
static int build_chain(struct skybox *s, struct err *e)
{
    fill_border(&s->level[0]);
    while (s->n_levels < SKYBOX_MAX_LEVELS && s->level[s->n_levels - 1].n >= 2) {
        const struct skybox_level *src = &s->level[s->n_levels - 1];
        struct skybox_level *dst = &s->level[s->n_levels];
        if (alloc_level(dst, src->n / 2))
            return err_set(e, "out of memory for the skybox");
        s->n_levels++;
        for (int f = 0; f < 6; f++)
            for (int j = 0; j < dst->n; j++) /* a row from two (byte 3 too: never read) */
                texture_row_halve(texel(src, f, 0, 2 * j), texel(src, f, 0, 2 * j + 1),
                                  texel(dst, f, 0, j), dst->n);
        fill_border(dst);
    }
    return 0;
}

int skybox_load(struct skybox *s, const char *const paths[6], struct err *e)
{
    memset(s, 0, sizeof *s);
    /* one face at a time, straight into level 0: never six decoded images at once */
    int rc = 0;
    for (int f = 0; f < 6 && rc == 0; f++) {
        struct texture t;
        rc = texture_load_level0(paths[f], SKYBOX_MAX_FACE, &t, NULL, e);
        if (rc)
            break;
        int n = s->n_levels ? s->level[0].n : t.w;
        if (t.w != t.h || t.w != n) {
            char q[200];
            rc = err_set(e, "%s: skybox faces must be square and equal (%dx%d, first face %dx%d)",
                         err_quote(paths[f], strlen(paths[f]), 160, q, sizeof q), t.w, t.h, n,
                         n);
        } else if (!s->n_levels && alloc_level(&s->level[0], n)) {
            rc = err_set(e, "out of memory for the skybox");
        } else {
            s->n_levels = 1;
            for (int j = 0; j < t.h; j++) /* (byte 3 of a texel is never read) */
                memcpy(texel(&s->level[0], f, 0, j), t.rgba + (size_t)j * t.w * 4,
                       (size_t)t.w * 4);
        }
        texture_free(&t);
    }
    if (rc == 0)
        rc = build_chain(s, e);
    if (rc)
        skybox_free(s);
    return rc;
}

/* Default sky: zenith blue to a pale horizon, darker ground below, a sun disc with glow. */
static void sky_color(vec3 d, vec3 sun, float out[3])
{
    d = v3_norm(d);
    double h = d.y;
    double r, g, b;
    if (h >= 0) {
        double k = pow(1 - h, 3); /* 1 at the horizon, 0 at the zenith */
        r = 0.18 + 0.62 * k, g = 0.36 + 0.50 * k, b = 0.78 + 0.17 * k;
    } else {
        double k = pow(1 + h, 8);
        r = 0.22 + 0.45 * k, g = 0.20 + 0.46 * k, b = 0.18 + 0.42 * k;
    }
    double c = v3_dot(d, sun);
    double glow = c > 0 ? 0.35 * pow(c, 64) : 0;
    double disc = c > 0.9993 ? 1 : c > 0.9986 ? (c - 0.9986) / 0.0007 : 0;
    out[0] = (float)(r + glow + disc), out[1] = (float)(g + glow * 0.9 + disc * 0.95);
    out[2] = (float)(b + glow * 0.7 + disc * 0.85);
}

int skybox_procedural(struct skybox *s, vec3 sun_dir, struct err *e)
{
    enum { N = 128, SS = 4 }; /* 4x4 supersampling keeps the sun's edge smooth */
    memset(s, 0, sizeof *s);
    if (alloc_level(&s->level[0], N)) {
        skybox_free(s);
        return err_set(e, "out of memory for the skybox");
    }
    s->n_levels = 1;
    vec3 sun = v3_norm(sun_dir);
    for (int f = 0; f < 6; f++)
        for (int j = 0; j < N; j++)
            for (int i = 0; i < N; i++) {
                float acc[3] = {0, 0, 0}, c[3];
                for (int sj = 0; sj < SS; sj++)
                    for (int si = 0; si < SS; si++) {
                        double sc = 2.0 * (i + (si + 0.5) / SS) / N - 1;
                        double tc = 2.0 * (j + (sj + 0.5) / SS) / N - 1;
                        sky_color(dir_of(f, sc, tc), sun, c);
                        for (int k = 0; k < 3; k++)
                            acc[k] += c[k] / (SS * SS);
                    }
                uint8_t *p = texel(&s->level[0], f, i, j);
                for (int k = 0; k < 3; k++)
                    p[k] = fb_quantize(acc[k]);
            }
    if (build_chain(s, e)) {
        skybox_free(s);
        return -1;
    }
    return 0;
}

void skybox_free(struct skybox *s)
{
    for (int l = 0; l < SKYBOX_MAX_LEVELS; l++)
        free(s->level[l].rgb[0]); /* the block of all six faces */
    memset(s, 0, sizeof *s);
}

/* bilinear sample of face f of level l at face coordinates (sc, tc) / ma in [-1, 1] */
static inline void sample_face(const struct skybox_level *l, int f, double u, double v,
                               float rgb_out[3])
{
    /* texel space: centre of texel i at i + 0.5; border texels at -1 and n cover the edges */
    double x = (u + 1) * 0.5 * l->n - 0.5, y = (v + 1) * 0.5 * l->n - 0.5;
    int i0 = (int)x, j0 = (int)y; /* floor: x, y >= -0.5 here, and finite */
    i0 -= x < i0, j0 -= y < j0;
    i0 = i0 < -1 ? -1 : i0 > l->n - 1 ? l->n - 1 : i0;
    j0 = j0 < -1 ? -1 : j0 > l->n - 1 ? l->n - 1 : j0;
    float ax = (float)(x - i0), ay = (float)(y - j0);
    ax = ax < 0 ? 0 : ax > 1 ? 1 : ax;
    ay = ay < 0 ? 0 : ay > 1 ? 1 : ay;
    const uint8_t *p00 = texel(l, f, i0, j0), *p10 = texel(l, f, i0 + 1, j0);
    const uint8_t *p01 = texel(l, f, i0, j0 + 1), *p11 = texel(l, f, i0 + 1, j0 + 1);
    for (int c = 0; c < 3; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]), b = p01[c] + ax * (p11[c] - p01[c]);
        rgb_out[c] = (a + ay * (b - a)) * (1.0f / 255.0f);
    }
}

void skybox_sample(const struct skybox *s, int level, vec3 d, float rgb_out[3])
{
    double sc, tc, ma;
    int f = face_of(d, &sc, &tc, &ma);
    if (!(ma > 0)) {
        rgb_out[0] = rgb_out[1] = rgb_out[2] = 0;
        return;
    }
    sample_face(&s->level[level], f, sc / ma, tc / ma, rgb_out);
}

#endif /* !SKYBOX_AVX2_COPY */

/* sample_face in float, SIMD_LANES lanes at once, each lane on its own face (the per-pixel
 * loop of skybox_draw_rows; sample_face stays the double-precision reference for
 * skybox_sample): the four texels of each lane gathered from the level's block of faces */
static inline void sample_face_v(const struct skybox_level *l, vi face, vf u, vf v, vf rgb_out[3])
{
    const vf half = vf_set(0.5f * l->n), zero = vf_set(0), one = vf_set(1);
    vf x = (u + one) * half - vf_set(0.5f), y = (v + one) * half - vf_set(0.5f);
    vi i0 = vi_floor(x), j0 = vi_floor(y); /* x, y >= -0.5 here, and finite */
    const vi lo = vi_set(-1), hi = vi_set(l->n - 1);
    i0 = vi_select(i0 < lo, lo, vi_select(i0 > hi, hi, i0));
    j0 = vi_select(j0 < lo, lo, vi_select(j0 > hi, hi, j0));
    vf ax = x - vf_from_vi(i0), ay = y - vf_from_vi(j0);
    ax = vf_select(ax < zero, zero, vf_select(ax > one, one, ax));
    ay = vf_select(ay < zero, zero, vf_select(ay > one, one, ay));
    const int row = l->n + 2; /* texels, r g b 0 in memory order */
    vi at = face * vi_set(row * row) + (j0 + 1) * vi_set(row) + (i0 + 1);
    vi t[4] = {vi_gather(l->rgb[0], at), vi_gather(l->rgb[0], at + 1),
               vi_gather(l->rgb[0], at + row), vi_gather(l->rgb[0], at + row + 1)};
    for (int c = 0; c < 3; c++) {
        vf p00 = vf_from_vi(texel_channel_v(t[0], c)), p10 = vf_from_vi(texel_channel_v(t[1], c));
        vf p01 = vf_from_vi(texel_channel_v(t[2], c)), p11 = vf_from_vi(texel_channel_v(t[3], c));
        vf a = p00 + ax * (p10 - p00), b = p01 + ax * (p11 - p01);
        rgb_out[c] = (a + ay * (b - a)) * vf_set(1.0f / 255.0f);
    }
}

#ifdef SKYBOX_AVX2_COPY
void SKYBOX_DRAW_ROWS(const struct skybox *s, const struct camera *cam, struct fb *fb, int y0,
                      int y1)
#else
static void SKYBOX_DRAW_ROWS(const struct skybox *s, const struct camera *cam, struct fb *fb,
                             int y0, int y1)
#endif
{
    if (s->n_levels == 0)
        return;
    vec3 f = v3_norm(v3_sub(cam->target, cam->eye));
    vec3 r = v3_norm(v3_cross(f, cam->up));
    vec3 u = v3_cross(r, f);
    double fov = cam->fov_deg > 0 ? cam->fov_deg : 50;
    double ty = tan(fov * (M_PI / 360.0)), tx = ty * fb_aspect(fb);
    /* level whose texel matches a pixel: a face spans 2 (in tan units) over n texels */
    double texels_per_px = (2 * ty / fb->h) / (2.0 / s->level[0].n);
    double lod = texels_per_px > 1 ? log2(texels_per_px) : 0;
    int level = (int)floor(lod);
    float frac = (float)(lod - level);
    if (level >= s->n_levels - 1) {
        level = s->n_levels - 1;
        frac = 0;
    }
    const struct skybox_level *l0 = &s->level[level], *l1 = &s->level[level + (frac > 0)];
    y0 = y0 < 0 ? 0 : y0;
    y1 = y1 > fb->h ? fb->h : y1;
    /* per pixel in float, as a GPU would, SIMD_LANES pixels at a time (simd.h): the direction
     * is a row vector plus a step along r, one reciprocal of the major axis gives both face
     * coordinates; face_of's cube-map table as selects, lane by lane */
    const vf rx = vf_set((float)(r.x * tx)), ry = vf_set((float)(r.y * tx)),
             rz = vf_set((float)(r.z * tx));
    const vf sx = vf_set(2.0f / fb->w), zero = vf_set(0), fr = vf_set(frac);
    const vf lane = vf_lanes(), clear = vf_set(fb_depth_clear_value(fb->depth_mode));
    const vi abs_mask = vi_set(0x7fffffff);
    for (int y = y0; y < y1; y++) {
        double ny = 1 - 2 * (y + 0.5) / fb->h;
        vec3 row = v3_add(f, v3_scale(u, ny * ty));
        const vf ox = vf_set((float)row.x), oy = vf_set((float)row.y), oz = vf_set((float)row.z);
        for (int x = 0; x < fb->w; x += SIMD_LANES) {
            size_t i = (size_t)y * fb->w + x;
            int n = fb->w - x < SIMD_LANES ? fb->w - x : SIMD_LANES, todo;
            if (n == SIMD_LANES) { /* the pixels nothing covered: depth still the clear value */
                vf d;
                __builtin_memcpy(&d, fb->depth + i, sizeof d);
                todo = vi_mask(d == clear);
            } else {
                todo = 0;
                for (int k = 0; k < n; k++)
                    todo |= !fb_covered(fb, i + k) << k;
            }
            if (!todo)
                continue;
            vf nx = (vf_from_vi(vi_set(x)) + lane + vf_set(0.5f)) * sx - vf_set(1);
            vf d0 = ox + nx * rx, d1 = oy + nx * ry, d2 = oz + nx * rz;
            vf ax = (vf)((vi)d0 & abs_mask), ay = (vf)((vi)d1 & abs_mask),
               az = (vf)((vi)d2 & abs_mask);
            vi isx = (ax >= ay) & (ax >= az), isy = ~isx & (ay >= az);
            vf ma = vf_select(isx, ax, vf_select(isy, ay, az));
            vf sc = vf_select(isx, vf_select(d0 > zero, -d2, d2),
                              vf_select(isy, d0, vf_select(d2 > zero, d0, -d0)));
            vf tc = vf_select(isy, vf_select(d1 > zero, d2, -d2), -d1);
            vi face = vi_select(isx, vi_select(d0 > zero, vi_set(0), vi_set(1)),
                                vi_select(isy, vi_select(d1 > zero, vi_set(2), vi_set(3)),
                                          vi_select(d2 > zero, vi_set(4), vi_set(5))));
            vi seen = ma > zero; /* else black */
            vf im = vf_set(1.0f) / vf_select(seen, ma, vf_set(1));
            vf fu = vf_select(seen, sc * im, zero), fv = vf_select(seen, tc * im, zero);
            vf c[3];
            sample_face_v(l0, face, fu, fv, c);
            if (frac > 0) { /* trilinear: blend with the next coarser level */
                vf c2[3];
                sample_face_v(l1, face, fu, fv, c2);
                for (int k = 0; k < 3; k++)
                    c[k] += fr * (c2[k] - c[k]);
            }
            vi q[3];
            for (int k = 0; k < 3; k++)
                q[k] = fb_quantize_v(vf_select(seen, c[k], zero));
            const vi px = q[0] | (q[1] << 8) | (q[2] << 16);
            if (todo == (1 << SIMD_LANES) - 1) {
                fb_store_rgb_v(fb->rgb + 3 * i, px);
                continue;
            }
            for (int k = 0; k < n; k++)
                if (todo >> k & 1)
                    fb_store_rgb(fb->rgb + 3 * (i + k), (uint32_t)px[k]);
        }
    }
}

#ifndef SKYBOX_AVX2_COPY
void skybox_draw_rows(const struct skybox *s, const struct camera *cam, struct fb *fb, int y0,
                      int y1)
{
#ifdef RASTTY_SPAN_AVX2
    if (span_isa_get() != SPAN_ISA_SSE2) {
        skybox_draw_rows_avx2(s, cam, fb, y0, y1);
        return;
    }
#endif
    sky_rows_base(s, cam, fb, y0, y1);
}

void skybox_draw(const struct skybox *s, const struct camera *cam, struct fb *fb)
{
    skybox_draw_rows(s, cam, fb, 0, fb->h);
}
#endif /* !SKYBOX_AVX2_COPY */
