/* texture.h: decoded images and how the pipeline samples them.
 *
 * Owns: texel storage (RGBA8, row 0 = the image's top row, as the file stores it), and the
 * texture cache a scene loads through. Decoding is imgdec.h's (PNG, JPEG, TGA, BMP, GIF,
 * PSD, PNM, HDR, chosen by content; HDR tone-mapped to 8 bits), files are read by file.h
 * (regular files only, at most FILE_MAX_IMAGE bytes).
 *
 * Memory: a texture is at most TEXTURE_MAX_SIDE texels on a side (larger images are
 * downscaled while decoding, with a warning: at terminal sizes no frame can show more).
 * A texture cache loads each file once (keyed by device and inode, so two spellings of one
 * path share it). Caches share what they load: a file another cache of the process already
 * decoded (the viewer's other scenes; same device, inode, size and modification time) is
 * that cache's texels, counted once, not decoded again. One budget for the whole process:
 * a texture that would take the texel bytes of every cache past TEXTURE_BUDGET is refused
 * (six scenes naming the same six 4096^2 textures hold 537 MB once, not 3.1 GB).
 *
 * Sampling conventions (shared with the reference renderer):
 *   - OBJ v = 1 is the image's top row, v = 0 its bottom edge.
 *   - texel (i, j) (j counted from the BOTTOM row) has its centre at ((i+0.5)/W, (j+0.5)/H).
 *   - wrap = repeat in both directions.
 *   - nearest: texel floor(u*W), floor(v*H); bilinear: the 4 texels around (u*W-0.5, v*H-0.5),
 *     weighted by the fractional parts; trilinear: the two mip levels around the level of
 *     detail (texture_lod), blended.
 *   - results are in [0,1] per channel (texel / 255). */
#ifndef RASTTY_TEXTURE_H
#define RASTTY_TEXTURE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "err.h"
#include "simd.h"

#define TEXTURE_MAX_SIDE 4096
#define TEXTURE_BUDGET ((size_t)512 << 20) /* texel bytes of the whole process */

#define TEXTURE_MAX_LEVELS 16

/* One level of a mip chain: w x h texels, RGBA8, row 0 = top. */
struct texture_level {
    int w, h;
    const uint8_t *rgba;
};

struct texture {
    int w, h;
    uint8_t *rgba; /* w*h*4 bytes, row-major, row 0 = top of the image */
    bool borrowed; /* rgba (and mips) belong to a texture cache: texture_free leaves them */
    /* the mip chain (texture_build_mips): level[0] is (w, h, rgba), each next level half
     * the size (rounded down, at least 1) down to 1x1; n_levels 0 until built */
    int n_levels;
    struct texture_level level[TEXTURE_MAX_LEVELS];
    uint8_t *mip_data; /* levels 1.. in one block */
};

/* Textures loaded once per file; entries never move, so pointers to them stay valid until
 * texture_cache_free. Zero-initialise before use. */
struct texture_cache {
    struct texture_cache_entry {
        unsigned long long dev, ino;
        struct texture tex;      /* borrowed from `shared` when that is set */
        struct texture_shared *shared; /* the process-wide record of a file, or NULL (an
                                          embedded image, or a solo cache's) */
        size_t bytes;            /* texel bytes, mip levels included */
    } **entries;
    int n, cap;
    size_t bytes;  /* texel bytes this cache uses, mip levels included (shared ones too) */
    size_t budget; /* 0 = TEXTURE_BUDGET; compared with the whole process's texel bytes */
    bool solo;     /* neither shares nor is counted in the process's bytes: its textures
                      are handed to a mesh that owns them (model_parse_as without a cache) */
};

/* Texel bytes every cache of the process holds (each shared file once). */
size_t texture_process_bytes(void);

/* Filters (--filter; the viewer's f key):
 *   TEX_NEAREST    the texel under the sample point, level 0. Cost: one fetch. Fails:
 *                  minified textures alias and shimmer (12 texels per pixel on a head at
 *                  terminal sizes): each pixel shows one texel of the 144 under it.
 *   TEX_BILINEAR   the 4 texels around it, weighted, level 0. Cost: 4 fetches. Fails the
 *                  same way once a pixel covers more than 2 texels.
 *   TEX_TRILINEAR  bilinear on the two mip levels around the pixel's footprint, blended
 *                  (GL_LINEAR_MIPMAP_LINEAR). Cost: 8 fetches and the footprint's size per
 *                  pixel. Fails: blurs surfaces seen at grazing angles (the footprint is
 *                  long and thin and the level follows its long side). */
enum tex_filter { TEX_NEAREST, TEX_BILINEAR, TEX_TRILINEAR, TEX_FILTER_COUNT };

/* The mip chain of t (box filter: each texel of a level is the area-weighted average of the
 * texels of the level above that it covers — for even sizes the mean of a 2x2 block, as
 * GL's glGenerateMipmap computes it, so Mesa's chain and ours agree). Returns the bytes the
 * levels below level 0 use, or -1 (out of memory, e set). */
long texture_build_mips(struct texture *t, struct err *e);
/* One row of a level of even size from the two rows above it: texel x of d (4 bytes) is the
 * rounded mean (a+b+c+d+2)/4 of texels 2x, 2x+1 of r0 and of r1, each channel (the mip chain's
 * and the sky's 2x2 step). */
void texture_row_halve(const uint8_t *r0, const uint8_t *r1, uint8_t *d, int dw);

/* Decode an image file (owned by out); on failure fills e with "path: reason" and returns -1.
 * Larger than max_side (TEXTURE_MAX_SIDE for ordinary textures) on a side: downscaled, with
 * a warning added to w (may be NULL). */
int texture_load(const char *path, int max_side, struct texture *out, struct warnings *w,
                 struct err *e);
/* texture_load without the mip chain (one level: the sky builds its own chain) */
int texture_load_level0(const char *path, int max_side, struct texture *out,
                        struct warnings *w, struct err *e);
/* Through the cache: the same file again gives the same texture. *out points into the
 * cache. Errors as texture_load, plus the budget: "path: 1024x1024 texture would pass the
 * 512 MiB texture budget". */
int texture_cache_load(struct texture_cache *c, const char *path, const struct texture **out,
                       struct warnings *w, struct err *e);
/* An image already in memory (an embedded glTF image), added to the cache's budget when c
 * is not NULL (then out is borrowed from it). */
int texture_cache_decode(struct texture_cache *c, const uint8_t *data, size_t len,
                         const char *name, struct texture *out, struct warnings *w,
                         struct err *e);
void texture_cache_free(struct texture_cache *c);
/* Wrap caller-made texels (copied). */
int texture_from_rgba(int w, int h, const uint8_t *rgba, struct texture *out, struct err *e);
void texture_free(struct texture *t);

/* Level 0 as a texture_level (also for textures whose chain was never built). */
static inline struct texture_level texture_base(const struct texture *t)
{
    return (struct texture_level){t->w, t->h, t->rgba};
}

/* floor(x) mod n in [0, n) for any float x; texel 0 for huge or non-finite x. Without
 * SSE4.1, floorf is a library call: the truncation below is exact for |x| < 2^31. Power-of-
 * two sizes take a mask; a coordinate already inside [0, n) needs neither. */
static inline int texture_wrap(float x, int n)
{
    if (!(x > -1e9f && x < 1e9f))
        return 0;
    int i = (int)x;
    i -= (float)i > x; /* truncation rounded up a negative x: floor */
    if ((unsigned)i < (unsigned)n)
        return i;
    if ((n & (n - 1)) == 0)
        return i & (n - 1);
    i %= n;
    return i < 0 ? i + n : i;
}

/* RASTTY_FLOOR_TEXELS is for measuring only (`make floor-build`, tests/bench_floor.sh; never
 * a build anyone runs): every texel fetch then reads one of the level's first 16 texels,
 * which stay in L1 — the frame with the texture's cache misses taken out and everything
 * else (addresses, gathers, shading) left in. Wrong pictures, honest times. */
#ifdef RASTTY_FLOOR_TEXELS
#define TEXEL_INDEX(k) ((k) & 15)
#else
#define TEXEL_INDEX(k) (k)
#endif

/* texel at column i, row j counted from the bottom */
static inline const uint8_t *texture_texel(const struct texture_level *lv, int i, int j)
{
    return lv->rgba + TEXEL_INDEX((size_t)(lv->h - 1 - j) * (size_t)lv->w + (size_t)i) * 4;
}

static inline void texture_nearest(const struct texture_level *lv, float u, float v,
                                   float rgb_out[3])
{
    const float k = 1.0f / 255.0f;
    const uint8_t *p = texture_texel(lv, texture_wrap(u * (float)lv->w, lv->w),
                                     texture_wrap(v * (float)lv->h, lv->h));
    rgb_out[0] = p[0] * k;
    rgb_out[1] = p[1] * k;
    rgb_out[2] = p[2] * k;
}

static inline void texture_bilinear(const struct texture_level *lv, float u, float v,
                                    float rgb_out[3])
{
    const float k = 1.0f / 255.0f;
    float x = u * (float)lv->w - 0.5f, y = v * (float)lv->h - 0.5f;
    if (!(x > -1e9f && x < 1e9f && y > -1e9f && y < 1e9f)) { /* as nearest does: texel 0 */
        x = 0;
        y = 0;
    }
    int xi = (int)x, yi = (int)y;
    xi -= (float)xi > x, yi -= (float)yi > y; /* floor */
    float ax = x - (float)xi, ay = y - (float)yi;
    int i0 = texture_wrap((float)xi, lv->w), j0 = texture_wrap((float)yi, lv->h);
    int i1 = i0 + 1 == lv->w ? 0 : i0 + 1, j1 = j0 + 1 == lv->h ? 0 : j0 + 1;
    const uint8_t *p00 = texture_texel(lv, i0, j0), *p10 = texture_texel(lv, i1, j0);
    const uint8_t *p01 = texture_texel(lv, i0, j1), *p11 = texture_texel(lv, i1, j1);
    for (int c = 0; c < 3; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]);
        float b = p01[c] + ax * (p11[c] - p01[c]);
        rgb_out[c] = (a + ay * (b - a)) * k;
    }
}

/* The levels a footprint of 2^lambda texels (of level 0) blends: l0 and l0 + 1 with weight
 * frac of the second (GL's rule: lambda <= 0 magnifies, level 0 alone). */
static inline int texture_levels(const struct texture *t, float lambda, float *frac_out)
{
    *frac_out = 0;
    if (!(lambda > 0) || t->n_levels < 2)
        return 0;
    if (!(lambda < (float)(t->n_levels - 1)))
        return t->n_levels - 1;
    int l0 = (int)lambda;
    *frac_out = lambda - (float)l0;
    return l0;
}

/* Sample at (u, v) with the filter; lambda = log2 of the pixel's footprint in level-0
 * texels (trilinear only). Writes rgb in [0,1]. Inline: it runs once per shaded pixel. */
static inline void texture_sample(const struct texture *t, enum tex_filter f, float u, float v,
                                  float lambda, float rgb_out[3])
{
    struct texture_level base = texture_base(t);
    if (f == TEX_NEAREST) {
        texture_nearest(&base, u, v, rgb_out);
        return;
    }
    float frac = 0;
    int l0 = f == TEX_TRILINEAR ? texture_levels(t, lambda, &frac) : 0;
    if (l0 == 0)
        texture_bilinear(&base, u, v, rgb_out);
    else
        texture_bilinear(&t->level[l0], u, v, rgb_out);
    if (f != TEX_TRILINEAR || frac == 0)
        return;
    float c1[3];
    texture_bilinear(&t->level[l0 + 1], u, v, c1);
    for (int c = 0; c < 3; c++)
        rgb_out[c] += frac * (c1[c] - rgb_out[c]);
}

/* ---- the features path (shade.h): wrap modes and alpha, scalar only ---- */

/* texture_wrap with a sampler's wrap mode (mesh.h's enum tex_wrap: 0 repeat, 1 clamp to
 * edge, 2 mirrored repeat), GL's rules: clamp takes the edge texel, mirror runs every other
 * copy backwards (period 2n) */
static inline int texture_wrap_mode(float x, int n, int mode)
{
    if (mode == 0)
        return texture_wrap(x, n);
    if (!(x > -1e9f && x < 1e9f))
        return 0;
    int i = (int)x;
    i -= (float)i > x; /* floor */
    if (mode == 1)
        return i < 0 ? 0 : i >= n ? n - 1 : i;
    int p = 2 * n, m = i % p;
    m += m < 0 ? p : 0;
    return m < n ? m : p - 1 - m;
}

/* texture_bilinear with wrap modes, four channels */
static inline void texture_bilinear_wrap(const struct texture_level *lv, int ws, int wt,
                                         float u, float v, float out[4])
{
    const float k = 1.0f / 255.0f;
    float x = u * (float)lv->w - 0.5f, y = v * (float)lv->h - 0.5f;
    if (!(x > -1e9f && x < 1e9f && y > -1e9f && y < 1e9f))
        x = y = 0;
    int xi = (int)x, yi = (int)y;
    xi -= (float)xi > x, yi -= (float)yi > y; /* floor */
    float ax = x - (float)xi, ay = y - (float)yi;
    int i0 = texture_wrap_mode((float)xi, lv->w, ws), i1 = texture_wrap_mode((float)xi + 1, lv->w, ws);
    int j0 = texture_wrap_mode((float)yi, lv->h, wt), j1 = texture_wrap_mode((float)yi + 1, lv->h, wt);
    const uint8_t *p00 = texture_texel(lv, i0, j0), *p10 = texture_texel(lv, i1, j0);
    const uint8_t *p01 = texture_texel(lv, i0, j1), *p11 = texture_texel(lv, i1, j1);
    for (int c = 0; c < 4; c++) {
        float a = p00[c] + ax * (p10[c] - p00[c]);
        float b = p01[c] + ax * (p11[c] - p01[c]);
        out[c] = (a + ay * (b - a)) * k;
    }
}

/* texture_sample with wrap modes (ws, wt), rgba in [0, 1] */
static inline void texture_sample_wrap(const struct texture *t, enum tex_filter f, int ws, int wt,
                                       float u, float v, float lambda, float out[4])
{
    struct texture_level base = texture_base(t);
    if (f == TEX_NEAREST) {
        const uint8_t *p = texture_texel(&base, texture_wrap_mode(u * (float)base.w, base.w, ws),
                                         texture_wrap_mode(v * (float)base.h, base.h, wt));
        for (int c = 0; c < 4; c++)
            out[c] = p[c] * (1.0f / 255.0f);
        return;
    }
    float frac = 0;
    int l0 = f == TEX_TRILINEAR ? texture_levels(t, lambda, &frac) : 0;
    texture_bilinear_wrap(l0 == 0 ? &base : &t->level[l0], ws, wt, u, v, out);
    if (f != TEX_TRILINEAR || frac == 0)
        return;
    float c1[4];
    texture_bilinear_wrap(&t->level[l0 + 1], ws, wt, u, v, c1);
    for (int c = 0; c < 4; c++)
        out[c] += frac * (c1[c] - out[c]);
}

/* texture_wrap for four coordinates */
SIMD_INLINE vi texture_wrap_v(vf x, int n)
{
    vi ok = (x > vf_set(-1e9f)) & (x < vf_set(1e9f));
    x = vf_select(ok, x, vf_set(0));
    vi i = vi_floor(x) & ok;
    if ((n & (n - 1)) == 0)
        return i & vi_set(n - 1);
    vi inside = (i >= vi_set(0)) & (i < vi_set(n));
    if (vi_any(~inside))
        for (int l = 0; l < SIMD_LANES; l++)
            if (!inside[l]) {
                int r = i[l] % n;
                i[l] = r < 0 ? r + n : r;
            }
    return i;
}

/* byte c (0 r, 1 g, 2 b) of the texels loaded as 32-bit words (RGBA8 in memory order) */
SIMD_INLINE vi texel_channel_v(vi words, int c)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
    return (words >> (24 - 8 * c)) & vi_set(255);
#else
    return (words >> (8 * c)) & vi_set(255);
#endif
}

/* the rgb of the texels at (i, j), j counted from the bottom, one vector per channel: one
 * 32-bit load per texel (a gather), split into channels in vector registers */
SIMD_INLINE void texture_fetch_v(const struct texture_level *lv, vi i, vi j, vi rgb_out[3])
{
    vi v = vi_gather(lv->rgba, TEXEL_INDEX((vi_set(lv->h - 1) - j) * vi_set(lv->w) + i));
    for (int c = 0; c < 3; c++)
        rgb_out[c] = texel_channel_v(v, c);
}

/* texture_bilinear, a sample per lane, all of one level */
static inline void texture_bilinear_v(const struct texture_level *lv, vf u, vf v, vf rgb_out[3])
{
    const vf k = vf_set(1.0f / 255.0f);
    vf x = u * vf_set((float)lv->w) - vf_set(0.5f), y = v * vf_set((float)lv->h) - vf_set(0.5f);
    vi ok = (x > vf_set(-1e9f)) & (x < vf_set(1e9f)) & (y > vf_set(-1e9f)) & (y < vf_set(1e9f));
    x = vf_select(ok, x, vf_set(0));
    y = vf_select(ok, y, vf_set(0));
    vi xi = vi_floor(x), yi = vi_floor(y);
    vf ax = x - vf_from_vi(xi), ay = y - vf_from_vi(yi);
    vi i0 = texture_wrap_v(vf_from_vi(xi), lv->w), j0 = texture_wrap_v(vf_from_vi(yi), lv->h);
    vi i1 = vi_select(i0 + 1 == vi_set(lv->w), vi_set(0), i0 + 1);
    vi j1 = vi_select(j0 + 1 == vi_set(lv->h), vi_set(0), j0 + 1);
    vi c00[3], c10[3], c01[3], c11[3];
    texture_fetch_v(lv, i0, j0, c00);
    texture_fetch_v(lv, i1, j0, c10);
    texture_fetch_v(lv, i0, j1, c01);
    texture_fetch_v(lv, i1, j1, c11);
    for (int ch = 0; ch < 3; ch++) {
        vf a = vf_from_vi(c00[ch]) + ax * vf_from_vi(c10[ch] - c00[ch]);
        vf b = vf_from_vi(c01[ch]) + ax * vf_from_vi(c11[ch] - c01[ch]);
        rgb_out[ch] = (a + ay * (b - a)) * k;
    }
}

/* texture_bilinear_v with a level of t per lane (lane l samples level lv[l]): the same
 * operations lane by lane, with that level's size */
static inline void texture_bilinear_v_levels(const struct texture *t, vi lv, vf u, vf v,
                                             vf rgb_out[3])
{
    const vf k = vf_set(1.0f / 255.0f);
    vi W, H;
    const uint8_t *px[SIMD_LANES];
    for (int l = 0; l < SIMD_LANES; l++) {
        struct texture_level L = lv[l] == 0 ? texture_base(t) : t->level[lv[l]];
        W[l] = L.w, H[l] = L.h, px[l] = L.rgba;
    }
    vf x = u * vf_from_vi(W) - vf_set(0.5f), y = v * vf_from_vi(H) - vf_set(0.5f);
    vi ok = (x > vf_set(-1e9f)) & (x < vf_set(1e9f)) & (y > vf_set(-1e9f)) & (y < vf_set(1e9f));
    x = vf_select(ok, x, vf_set(0));
    y = vf_select(ok, y, vf_set(0));
    vi xi = vi_floor(x), yi = vi_floor(y);
    vf ax = x - vf_from_vi(xi), ay = y - vf_from_vi(yi);
    /* texture_wrap of whole numbers: floor(x) mod n in [0, n) */
    vi i0 = xi, j0 = yi;
    vi outside = (i0 < vi_set(0)) | (i0 >= W) | (j0 < vi_set(0)) | (j0 >= H);
    if (vi_any(outside))
        for (int l = 0; l < SIMD_LANES; l++) {
            int r = i0[l] % W[l], q = j0[l] % H[l];
            i0[l] = r < 0 ? r + W[l] : r;
            j0[l] = q < 0 ? q + H[l] : q;
        }
    vi i1 = vi_select(i0 + 1 == W, vi_set(0), i0 + 1);
    vi j1 = vi_select(j0 + 1 == H, vi_set(0), j0 + 1);
    vi r0 = (H - 1 - j0) * W, r1 = (H - 1 - j1) * W; /* row starts, in texels */
    uint32_t tx[4][SIMD_LANES]; /* p00 p10 p01 p11 of each lane */
    for (int l = 0; l < SIMD_LANES; l++) {
        const uint8_t *p = px[l];
        __builtin_memcpy(&tx[0][l], p + (size_t)(r0[l] + i0[l]) * 4, 4);
        __builtin_memcpy(&tx[1][l], p + (size_t)(r0[l] + i1[l]) * 4, 4);
        __builtin_memcpy(&tx[2][l], p + (size_t)(r1[l] + i0[l]) * 4, 4);
        __builtin_memcpy(&tx[3][l], p + (size_t)(r1[l] + i1[l]) * 4, 4);
    }
    vi w[4];
    __builtin_memcpy(w, tx, sizeof w);
    for (int ch = 0; ch < 3; ch++) {
        vf c00 = vf_from_vi(texel_channel_v(w[0], ch)), c10 = vf_from_vi(texel_channel_v(w[1], ch));
        vf c01 = vf_from_vi(texel_channel_v(w[2], ch)), c11 = vf_from_vi(texel_channel_v(w[3], ch));
        vf a = c00 + ax * (c10 - c00);
        vf b = c01 + ax * (c11 - c01);
        rgb_out[ch] = (a + ay * (b - a)) * k;
    }
}

/* vf_log2 of one float: the same operations */
static inline float texture_log2(float x)
{
    int32_t b;
    __builtin_memcpy(&b, &x, sizeof b);
    float e = (float)(((b >> 23) & 255) - 127);
    int32_t m = (b & 0x7fffff) | 0x3f800000;
    float t;
    __builtin_memcpy(&t, &m, sizeof t);
    t -= 1.0f;
    return e + t * (SIMD_LOG2_C1 + t * (SIMD_LOG2_C2 + t * SIMD_LOG2_C3));
}

/* texture_lod_v of one pixel: the same operations */
static inline float texture_lod(const struct texture *t, float dudx, float dvdx, float dudy,
                                float dvdy)
{
    float w = (float)t->w, h = (float)t->h;
    float ax = dudx * w, bx = dvdx * h, ay = dudy * w, by = dvdy * h;
    float rx = ax * ax + bx * bx, ry = ay * ay + by * by;
    float r2 = rx > ry ? rx : ry;
    if (!(r2 > 1e-30f && r2 < 1e30f))
        return -1;
    return 0.5f * texture_log2(r2);
}

/* The level of detail (texture_sample's lambda) of every lane's pixel from the screen-space
 * derivatives of u and v: log2 of the longer side of the pixel's footprint in level-0
 * texels, rho = max(|(du/dx, dv/dx)|, |(du/dy, dv/dy)|) (GL's formula, without its
 * approximations). A zero or non-finite footprint gives -1: magnification. */
SIMD_INLINE vf texture_lod_v(const struct texture *t, vf dudx, vf dvdx, vf dudy, vf dvdy)
{
    vf w = vf_set((float)t->w), h = vf_set((float)t->h);
    vf ax = dudx * w, bx = dvdx * h, ay = dudy * w, by = dvdy * h;
    vf rx = ax * ax + bx * bx, ry = ay * ay + by * by;
    vf r2 = vf_select(rx > ry, rx, ry);
    vi ok = (r2 > vf_set(1e-30f)) & (r2 < vf_set(1e30f));
    vf lambda = vf_set(0.5f) * vf_log2(vf_select(ok, r2, vf_set(1)));
    return vf_select(ok, lambda, vf_set(-1));
}

/* A sample per lane: in every lane exactly what texture_sample gives (lambda per lane). */
SIMD_INLINE void
texture_sample_v(const struct texture *t, enum tex_filter f, vf u, vf v, vf lambda, vf rgb_out[3])
{
    struct texture_level base = texture_base(t);
    if (f == TEX_NEAREST) {
        const vf k = vf_set(1.0f / 255.0f);
        vi c[3];
        texture_fetch_v(&base, texture_wrap_v(u * vf_set((float)base.w), base.w),
                        texture_wrap_v(v * vf_set((float)base.h), base.h), c);
        for (int ch = 0; ch < 3; ch++)
            rgb_out[ch] = vf_from_vi(c[ch]) * k;
        return;
    }
    if (f == TEX_BILINEAR) {
        texture_bilinear_v(&base, u, v, rgb_out);
        return;
    }
    if (t->n_levels < 2) { /* no chain: level 0 alone, as texture_levels says */
        texture_bilinear_v(&base, u, v, rgb_out);
        return;
    }
    /* texture_levels in every lane */
    const int top = t->n_levels - 1;
    vi in = (lambda > vf_set(0)) & (lambda < vf_set((float)top)); /* between two levels */
    vi beyond = (lambda > vf_set(0)) & ~in;                        /* the last level */
    vi l0 = vi_trunc(vf_select(in, lambda, vf_set(0)));
    l0 = vi_select(beyond, vi_set(top), l0);
    vf fr = vf_select(in, lambda - vf_from_vi(l0), vf_set(0));
    if (vi_all(l0 == vi_set(l0[0]))) { /* one level for all four: its size is a constant */
        texture_bilinear_v(l0[0] == 0 ? &base : &t->level[l0[0]], u, v, rgb_out);
        if (!vi_any(fr != vf_set(0)))
            return;
        vf c1[3];
        texture_bilinear_v(&t->level[l0[0] + 1], u, v, c1);
        for (int ch = 0; ch < 3; ch++) /* frac 0 lanes: + 0 * (c1 - c0), exactly c0 */
            rgb_out[ch] += fr * (c1[ch] - rgb_out[ch]);
        return;
    }
    /* the footprint changes level inside these four: each lane on its own level */
    texture_bilinear_v_levels(t, l0, u, v, rgb_out);
    if (!vi_any(fr != vf_set(0)))
        return;
    vf c1[3];
    texture_bilinear_v_levels(t, vi_select(l0 < vi_set(top), l0 + 1, l0), u, v, c1);
    for (int ch = 0; ch < 3; ch++)
        rgb_out[ch] += fr * (c1[ch] - rgb_out[ch]);
}

#endif
