/* kernel_sky.h: the sky (scene/skybox.h's cube map) drawn where no surface was —
 * compiled once per instruction set by kernel_*.c (kernel.h, sky_rows): SIMD_LANES pixels at
 * a time, the four texels of each lane gathered. */
#ifndef RASTTY_KERNEL_SKY_H
#define RASTTY_KERNEL_SKY_H

#include <math.h>

#include "camera.h"
#include "fb.h"
#include "kernel_common.h"
#include "skybox.h"
#include "texture.h"

/* sample_face in float, SIMD_LANES lanes at once, each lane on its own face (the per-pixel
 * loop of sky_draw_rows; skybox_sample (skybox.c) stays the double-precision reference): the four texels of each lane gathered from the level's block of faces */
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

/* kernel.h's sky_rows */
static void sky_rows(const struct skybox *s, const struct camera *cam, struct fb *fb, int y0,
                     int y1)
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
                q[k] = kernel_quantize_v(vf_select(seen, c[k], zero));
            const vi px = q[0] | (q[1] << 8) | (q[2] << 16);
            if (todo == (1 << SIMD_LANES) - 1) {
                kernel_store_rgb_v(fb->rgb + 3 * i, px);
                continue;
            }
            for (int k = 0; k < n; k++)
                if (todo >> k & 1)
                    kernel_store_rgb(fb->rgb + 3 * (i + k), (uint32_t)px[k]);
        }
    }
}

#endif
