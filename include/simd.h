/* simd.h: four-lane float and int vectors for the per-pixel code (span.c, shade.h,
 * texture.h, fb.h).
 *
 * GCC/Clang vector extensions: plain C operators on four lanes at once, compiled to SSE2 on
 * x86-64 (NEON on ARM, scalar code elsewhere). Every lane computes exactly what the scalar
 * code would, with the same IEEE operations in the same order (no fused multiply-add:
 * the build says -ffp-contract=off), so a pixel's value never depends on which lane or
 * which group of four it fell in. Comparisons give -1 (true) or 0 per lane. */
#ifndef RASTTY_SIMD_H
#define RASTTY_SIMD_H

#include <stdint.h>

typedef float vf __attribute__((vector_size(16)));
typedef int32_t vi __attribute__((vector_size(16)));

#define SIMD_LANES 4

static inline vf vf_set(float a)
{
    return (vf){a, a, a, a};
}

static inline vi vi_set(int32_t a)
{
    return (vi){a, a, a, a};
}

/* m ? a : b, lane by lane (m from a comparison: every lane 0 or -1) */
static inline vf vf_select(vi m, vf a, vf b)
{
#if defined(__SSE4_1__)
    return __builtin_ia32_blendvps(b, a, (vf)m);
#else
    return (vf)((m & (vi)a) | (~m & (vi)b));
#endif
}

static inline vi vi_select(vi m, vi a, vi b)
{
#if defined(__SSE4_1__)
    return (vi)__builtin_ia32_blendvps((vf)b, (vf)a, (vf)m);
#else
    return (m & a) | (~m & b);
#endif
}

/* a > b ? a : b and a < b ? a : b, lane by lane: exactly that expression (b when either is
 * NaN or both are zeros), which is what SSE's maxps / minps compute */
static inline vf vf_max(vf a, vf b)
{
#if defined(__SSE__)
    return __builtin_ia32_maxps(a, b);
#else
    return vf_select(a > b, a, b);
#endif
}

static inline vf vf_min(vf a, vf b)
{
#if defined(__SSE__)
    return __builtin_ia32_minps(a, b);
#else
    return vf_select(a < b, a, b);
#endif
}

static inline vf vf_from_vi(vi a)
{
    return __builtin_convertvector(a, vf);
}

/* truncation toward zero; |a| must be below 2^31 (callers clamp first) */
static inline vi vi_trunc(vf a)
{
    return __builtin_convertvector(a, vi);
}

/* floor of each lane, as an integer; |a| must be below 2^31 (callers clamp first) */
static inline vi vi_floor(vf a)
{
#if defined(__SSE4_1__)
    return vi_trunc(__builtin_ia32_roundps(a, 0x9)); /* toward -inf, no exception */
#else
    vi i = vi_trunc(a);
    return i + (vf_from_vi(i) > a); /* -1 where truncation rounded a negative a up */
#endif
}

/* square root of each lane: the same IEEE result as sqrtf */
static inline vf vf_sqrt(vf a)
{
#if defined(__SSE__)
    return __builtin_ia32_sqrtps(a);
#else
    return (vf){__builtin_sqrtf(a[0]), __builtin_sqrtf(a[1]), __builtin_sqrtf(a[2]),
                __builtin_sqrtf(a[3])};
#endif
}

/* log2 of positive finite lanes, to about 0.0013 (exponent bits plus a cubic on the
 * mantissa): a texture's level of detail needs no more. Zero, negative or non-finite lanes
 * give garbage, which callers select away. */
static inline vf vf_log2(vf x)
{
    vi b = (vi)x;
    vf e = vf_from_vi(((b >> 23) & vi_set(255)) - vi_set(127));
    vf t = (vf)((b & vi_set(0x7fffff)) | vi_set(0x3f800000)) - vf_set(1.0f); /* [0,1) */
    vf p = t * (vf_set(1.4234853f) + t * (vf_set(-0.5877338f) + t * vf_set(0.1655588f)));
    return e + p;
}

/* any lane set? (m from a comparison) */
static inline int vi_any(vi m)
{
#if defined(__SSE__)
    return __builtin_ia32_movmskps((vf)m) != 0;
#else
    return (m[0] | m[1] | m[2] | m[3]) != 0;
#endif
}

/* every lane set? (m from a comparison) */
static inline int vi_all(vi m)
{
#if defined(__SSE__)
    return __builtin_ia32_movmskps((vf)m) == 15;
#else
    return (m[0] & m[1] & m[2] & m[3]) != 0;
#endif
}

#endif
