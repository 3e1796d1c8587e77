/* kernel_common.h: what the reference kernel and the vector bodies share — the per-row
 * facts of the span methods and the varyings a triangle interpolates. Private to
 * src/render/kernel/ (included by each kernel_*.c). */
#ifndef RASTTY_KERNEL_COMMON_H
#define RASTTY_KERNEL_COMMON_H

#include <stdint.h>

#include "setup.h"
#include "shade.h"
#include "span.h"
#include "vertex.h"

/* floor(a / b), b > 0 */
static inline int64_t kernel_floor_div(int64_t a, int64_t b)
{
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* The first and last covered column of row y, from the edge functions (the same integers
 * every rasterizer tests): the ends that span methods clamp their spans to. */
static inline void kernel_row_extent(const struct setup_tri *t, int y, int *lo_out, int *hi_out)
{
    int64_t lo = t->x0, hi = t->x1;
    for (int k = 0; k < 3; k++) {
        int64_t a = t->e_dx[k], e = t->e[k] + (int64_t)(y - t->y0) * t->e_dy[k];
        if (a > 0) { /* e + (x - x0) a >= 0  <=>  x >= x0 - floor(e / a) */
            int64_t b = t->x0 - kernel_floor_div(e, a);
            lo = b > lo ? b : lo;
        } else if (a < 0) { /* x <= x0 + floor(e / -a) */
            int64_t b = t->x0 + kernel_floor_div(e, -a);
            hi = b < hi ? b : hi;
        }
    }
    *lo_out = (int)lo, *hi_out = (int)hi;
}

/* The varyings exactly (one division) at column offset X of the row whose denominator and
 * numerator bases are qr, ar; qdx, adx their steps per column. */
static inline void kernel_exact_at(float qr, float qdx, const float *ar, const float *adx,
                                   float X, int n_var, float *var_out)
{
    float rq = 1.0f / (qr + qdx * X);
    for (int k = 0; k < n_var; k++)
        var_out[k] = (ar[k] + adx[k] * X) * rq;
}

/* varyings a triangle's pixels interpolate in a shading mode */
static inline int kernel_n_var(const struct span_ctx *s, enum shade_mode mode)
{
    /* (the depth-only pass has no shading record: never look at s->st there) */
    return mode == SHADE_WIRE        ? 0
           : s->tri->rich            ? s->st->rich->lay.n
           : s->st->vcolor           ? VARY_COLOR + 3
           : vertex_varying_count(mode, VIEW_COLOR, s->shade->lights.grey);
}

/* where a triangle's varyings start in its vertices' all[] (vertex.h) */
static inline int kernel_vary_base(const struct span_ctx *s)
{
    return s->tri->rich ? 0 : VARY_BASE;
}

/* ---- one pixel's depth and varyings, as the reference computes them ---- */

/* the depth at (X, Y) from the triangle's origin: the plane (c + its small part), divided by
 * the 1/w plane for w-depth, clamped to the corners' range, rounded to 16 bits for z16 */
static inline float kernel_depth_at(const struct span_ctx *s, float X, float Y)
{
    const struct setup_interp *in = &s->in;
    float z = in->z.c + ((in->z_c_lo + in->z.dy * Y) + in->z.dx * X);
    if (s->depth == DEPTH_W)
        z = z / ((in->zq.c + in->zq.dy * Y) + in->zq.dx * X);
    z = in->z_lo > z ? in->z_lo : z;
    z = in->z_hi < z ? in->z_hi : z;
    if (s->depth == DEPTH_Z16) /* floor(z * 65535 + 0.5); z is in [0, 1] */
        z = (float)(int32_t)(z * 65535.0f + 0.5f);
    return z;
}

/* the n_var varyings of pixel (x, y) (X, Y from the origin) into var, in the perspective
 * method: divided per pixel (correct, affine: the planes say which), or exact at the span's
 * clamped ends and linear between them (span.h); returns 1/q at the pixel */
static inline float kernel_varyings_at(const struct span_ctx *s, int x, int y, float X,
                                       float Y, int n_var, float *var)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    const float qr = in->q.c + in->q.dy * Y, rq = 1.0f / (qr + in->q.dx * X);
    float ar[VARY_ALL];
    for (int k = 0; k < n_var; k++)
        ar[k] = in->a_c[k] + in->a_dy[k] * Y;
    if (s->persp == PERSP_CORRECT || s->persp == PERSP_AFFINE) {
        for (int k = 0; k < n_var; k++)
            var[k] = (ar[k] + in->a_dx[k] * X) * rq;
    } else {
        const int n = s->persp == PERSP_SPAN8 ? 8 : s->persp == PERSP_SPAN16 ? 16 : 32;
        int row_lo, row_hi;
        kernel_row_extent(t, y, &row_lo, &row_hi);
        int a = x - x % n, a0 = a > row_lo ? a : row_lo, a1 = a + n < row_hi ? a + n : row_hi;
        float va[VARY_ALL], vb[VARY_ALL];
        kernel_exact_at(qr, in->q.dx, ar, in->a_dx, (float)(a0 - t->x0), n_var, va);
        kernel_exact_at(qr, in->q.dx, ar, in->a_dx, (float)(a1 - t->x0), n_var, vb);
        float inv_len = a1 > a0 ? 1.0f / (float)(a1 - a0) : 0, f = (float)(x - a0);
        for (int k = 0; k < n_var; k++)
            var[k] = va[k] + f * ((vb[k] - va[k]) * inv_len);
    }
    return rq;
}

/* ---- the features path: one scalar pixel, the same in every kernel ---- */

/* Pixel (x, y) of the current triangle (setup done) by the features path, in any depth and
 * perspective method: depth as the reference kernel computes it, the test, the varyings,
 * shade_rich; a discarded pixel (alpha MASK) writes nothing, a blended one (alpha BLEND)
 * mixes its colour over the framebuffer's, src a + dst (1 - a), and keeps the depth (the
 * blended pass runs after the opaque surfaces, back to front); the rest write depth and
 * colour. Every kernel calls this for these triangles, so they are the same bytes. */
static inline void kernel_rich_pixel(struct span_ctx *s, int x, int y)
{
    const struct setup_interp *in = &s->in;
    const struct setup_tri *t = s->tri;
    struct fb *fb = s->fb;
    const size_t i = (size_t)y * (size_t)fb->w + (size_t)x;
    const float X = (float)(x - t->x0), Y = (float)(y - t->y0);
    const float z = kernel_depth_at(s, X, Y);
    s->tested++;
    if (fb->overdraw)
        fb->overdraw[i]++;
    if (!fb_depth_passes(s->depth, z, fb->depth[i]))
        return;
    const int n_var = s->st->rich->lay.n;
    float var[VARY_ALL] = {0};
    const float rq = kernel_varyings_at(s, x, y, X, Y, n_var, var);
    const struct rich_pixel px = {in->a_dx, in->a_dy, in->q.dx, in->q.dy, rq};
    float c[3], alpha = 1;
    if (!shade_rich(s->shade, s->mode, s->st, var, &px, c, &alpha))
        return;
    uint8_t *p = fb->rgb + 3 * i;
    s->shaded++;
    if (s->st->mat->alpha_mode == MAT_BLEND) {
        for (int k = 0; k < 3; k++)
            p[k] = pixel_quantize(c[k] * alpha + (float)p[k] * (1.0f / 255.0f) * (1 - alpha));
        return;
    }
    fb->depth[i] = z;
    p[0] = pixel_quantize(c[0]), p[1] = pixel_quantize(c[1]), p[2] = pixel_quantize(c[2]);
}

/* ---- the vector bodies' framebuffer writes ---- */

/* pixel_quantize (pixel.h) of every lane (0..255 in each) */
SIMD_INLINE vi kernel_quantize_v(vf c)
{
    c = vf_max(c, vf_set(0)); /* c > 0 ? c : 0 (NaN: 0) */
    c = vf_min(c, vf_set(1)); /* c < 1 ? c : 1 */
    return vi_trunc(c * vf_set(255.0f) + vf_set(0.5f));
}

/* The colours of SIMD_LANES pixels side by side from p on, each lane's r | g << 8 | b << 16
 * (kernel_quantize_v's). AVX2: each 128-bit half's four pixels as 12 bytes side by side (one
 * byte shuffle), stored as 16 bytes whose last 4 the next store overwrites, then 8 + 4;
 * else each lane's 4 bytes in order, each overwriting the byte the one before wrote past
 * its pixel, and the last lane's 3. Never writes past the group's pixels. */
SIMD_INLINE void kernel_store_rgb_v(uint8_t *p, vi px)
{
#ifdef __AVX2__
    typedef char v16c __attribute__((vector_size(16)));
    const v16c pick = {0, 1, 2, 4, 5, 6, 8, 9, 10, 12, 13, 14, -1, -1, -1, -1};
#if SIMD_LANES == 8
    v16c lo = (v16c)__builtin_ia32_pshufb128((v16c)_mm256_castsi256_si128((__m256i)px), pick);
    v16c hi = (v16c)__builtin_ia32_pshufb128((v16c)_mm256_extracti128_si256((__m256i)px, 1),
                                             pick);
    __builtin_memcpy(p, &lo, 16);
    __builtin_memcpy(p + 12, &hi, 8);
    __builtin_memcpy(p + 20, (const char *)&hi + 8, 4);
#else
    v16c lo = (v16c)__builtin_ia32_pshufb128((v16c)px, pick);
    __builtin_memcpy(p, &lo, 8);
    __builtin_memcpy(p + 8, (const char *)&lo + 8, 4);
#endif
#else
    for (int l = 0; l < SIMD_LANES - 1; l++) {
        uint32_t w = (uint32_t)px[l];
        uint8_t le[4] = {(uint8_t)w, (uint8_t)(w >> 8), (uint8_t)(w >> 16), 0};
        __builtin_memcpy(p + 3 * l, le, 4);
    }
    const uint32_t w = (uint32_t)px[SIMD_LANES - 1];
    p[3 * SIMD_LANES - 3] = (uint8_t)w, p[3 * SIMD_LANES - 2] = (uint8_t)(w >> 8),
                      p[3 * SIMD_LANES - 1] = (uint8_t)(w >> 16);
#endif
}

/* One lane's colour (r | g << 8 | b << 16) at p: 2 + 1 bytes */
static inline void kernel_store_rgb(uint8_t *p, uint32_t w)
{
    uint8_t rg[2] = {(uint8_t)w, (uint8_t)(w >> 8)};
    __builtin_memcpy(p, rg, 2);
    p[2] = (uint8_t)(w >> 16);
}

#endif
