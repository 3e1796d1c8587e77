/* simd.h: float and int vectors of SIMD_LANES lanes for the per-pixel and per-vertex
 * kernels (render/kernel.h) and the vector twins of shade.h, light.h and texture.h.
 *
 * GCC/Clang vector extensions: plain C operators on all lanes at once. Four lanes by
 * default, compiled to SSE2 on x86-64 (NEON on ARM, scalar code elsewhere); a kernel file
 * defines SIMD_LANES 8 before including this (kernel_avx2.c) and gets eight (one AVX
 * register). A function named with the suffix _v (vf_*, vi_* here; shade_fragment_v,
 * light_terms_v, texture_sample_v, ...) is the vector twin of the scalar function without
 * it: in every lane it gives exactly what the scalar one gives (the reference kernel is
 * built from the scalar ones, and the tests hold every kernel to it). Every lane
 * computes exactly what the scalar code would, with the same IEEE operations in the same
 * order (no fused multiply-add: the build says -ffp-contract=off), so a pixel's value never
 * depends on which lane, which group or which width it fell in. Comparisons give -1 (true)
 * or 0 per lane. A struct shared between files never holds these types: their width
 * depends on the file. */
#ifndef RASTTY_SIMD_H
#define RASTTY_SIMD_H

#include <stdint.h>
#if defined(__AVX2__)
#include <immintrin.h>
#endif

#ifndef SIMD_LANES
#define SIMD_LANES 4
#endif

/* the helpers are a few instructions each: never a call (GCC outlines some once a span
 * stage copy grows large) */
#define SIMD_INLINE static inline __attribute__((always_inline))

#if SIMD_LANES == 8
#if !defined(__AVX2__)
#error "eight lanes need AVX2 (-mavx2)"
#endif
typedef float vf __attribute__((vector_size(32)));
typedef int32_t vi __attribute__((vector_size(32)));
#elif SIMD_LANES == 4
typedef float vf __attribute__((vector_size(16)));
typedef int32_t vi __attribute__((vector_size(16)));
#else
#error "SIMD_LANES is 4 or 8"
#endif

SIMD_INLINE vf vf_set(float a)
{
#if SIMD_LANES == 8
    return (vf){a, a, a, a, a, a, a, a};
#else
    return (vf){a, a, a, a};
#endif
}

SIMD_INLINE vi vi_set(int32_t a)
{
#if SIMD_LANES == 8
    return (vi){a, a, a, a, a, a, a, a};
#else
    return (vi){a, a, a, a};
#endif
}

/* 0, 1, 2, ...: each lane's index */
SIMD_INLINE vf vf_lanes(void)
{
#if SIMD_LANES == 8
    return (vf){0, 1, 2, 3, 4, 5, 6, 7};
#else
    return (vf){0, 1, 2, 3};
#endif
}

SIMD_INLINE vi vi_lanes(void)
{
    return __builtin_convertvector(vf_lanes(), vi);
}

/* m ? a : b, lane by lane (m from a comparison: every lane 0 or -1) */
SIMD_INLINE vf vf_select(vi m, vf a, vf b)
{
#if SIMD_LANES == 8
    return __builtin_ia32_blendvps256(b, a, (vf)m);
#elif defined(__SSE4_1__)
    return __builtin_ia32_blendvps(b, a, (vf)m);
#else
    return (vf)((m & (vi)a) | (~m & (vi)b));
#endif
}

SIMD_INLINE vi vi_select(vi m, vi a, vi b)
{
#if SIMD_LANES == 8
    return (vi)__builtin_ia32_blendvps256((vf)b, (vf)a, (vf)m);
#elif defined(__SSE4_1__)
    return (vi)__builtin_ia32_blendvps((vf)b, (vf)a, (vf)m);
#else
    return (m & a) | (~m & b);
#endif
}

/* a > b ? a : b and a < b ? a : b, lane by lane: exactly that expression (b when either is
 * NaN or both are zeros), which is what SSE's maxps / minps compute */
SIMD_INLINE vf vf_max(vf a, vf b)
{
#if SIMD_LANES == 8
    return __builtin_ia32_maxps256(a, b);
#elif defined(__SSE__)
    return __builtin_ia32_maxps(a, b);
#else
    return vf_select(a > b, a, b);
#endif
}

SIMD_INLINE vf vf_min(vf a, vf b)
{
#if SIMD_LANES == 8
    return __builtin_ia32_minps256(a, b);
#elif defined(__SSE__)
    return __builtin_ia32_minps(a, b);
#else
    return vf_select(a < b, a, b);
#endif
}

SIMD_INLINE vf vf_from_vi(vi a)
{
    return __builtin_convertvector(a, vf);
}

/* truncation toward zero; |a| must be below 2^31 (callers clamp first) */
SIMD_INLINE vi vi_trunc(vf a)
{
    return __builtin_convertvector(a, vi);
}

/* floor of each lane, as an integer; |a| must be below 2^31 (callers clamp first) */
SIMD_INLINE vi vi_floor(vf a)
{
#if SIMD_LANES == 8
    return vi_trunc(__builtin_ia32_roundps256(a, 0x9)); /* toward -inf, no exception */
#elif defined(__SSE4_1__)
    return vi_trunc(__builtin_ia32_roundps(a, 0x9)); /* toward -inf, no exception */
#else
    vi i = vi_trunc(a);
    return i + (vf_from_vi(i) > a); /* -1 where truncation rounded a negative a up */
#endif
}

/* square root of each lane: the same IEEE result as sqrtf */
SIMD_INLINE vf vf_sqrt(vf a)
{
#if SIMD_LANES == 8
    return __builtin_ia32_sqrtps256(a);
#elif defined(__SSE__)
    return __builtin_ia32_sqrtps(a);
#else
    return (vf){__builtin_sqrtf(a[0]), __builtin_sqrtf(a[1]), __builtin_sqrtf(a[2]),
                __builtin_sqrtf(a[3])};
#endif
}

/* log2(1 + t) on [0, 1) as t (C1 + t (C2 + t C3)): vf_log2's polynomial, and texture.h's
 * one-float copy of it (the same constants, so the two never drift apart) */
#define SIMD_LOG2_C1 1.4234853f
#define SIMD_LOG2_C2 (-0.5877338f)
#define SIMD_LOG2_C3 0.1655588f

/* log2 of positive finite lanes, to about 0.0013 (exponent bits plus a cubic on the
 * mantissa): a texture's level of detail needs no more. Zero, negative or non-finite lanes
 * give garbage, which callers select away. */
SIMD_INLINE vf vf_log2(vf x)
{
    vi b = (vi)x;
    vf e = vf_from_vi(((b >> 23) & vi_set(255)) - vi_set(127));
    vf t = (vf)((b & vi_set(0x7fffff)) | vi_set(0x3f800000)) - vf_set(1.0f); /* [0,1) */
    vf p = t * (vf_set(SIMD_LOG2_C1) + t * (vf_set(SIMD_LOG2_C2) + t * vf_set(SIMD_LOG2_C3)));
    return e + p;
}

/* the 32-bit words base[idx[l]] (idx[l] >= 0, any alignment): one gather instruction with
 * AVX2, a load per lane without */
SIMD_INLINE vi vi_gather(const void *base, vi idx)
{
#if SIMD_LANES == 8
    return (vi)_mm256_i32gather_epi32((const int *)base, (__m256i)idx, 4);
#elif defined(__AVX2__)
    return (vi)_mm_i32gather_epi32((const int *)base, (__m128i)idx, 4);
#else
    uint32_t w[SIMD_LANES];
    for (int l = 0; l < SIMD_LANES; l++)
        __builtin_memcpy(&w[l], (const uint8_t *)base + (size_t)idx[l] * 4, 4);
    vi v;
    __builtin_memcpy(&v, w, sizeof v);
    return v;
#endif
}

/* base[idx[l]] for the first n lanes (n <= SIMD_LANES), 0 in the others: a masked gather
 * with AVX2 and four lanes (the other lanes are never read), a load per lane otherwise (an
 * eight-lane masked gather measured slower than the loads: 640x480 head 1.233 -> 1.267 ms) */
SIMD_INLINE vf vf_gather_first(const float *base, vi idx, int n)
{
#if defined(__AVX2__) && SIMD_LANES == 4
    vi live = vi_lanes() < vi_set(n);
    return (vf)_mm_mask_i32gather_ps((__m128)vf_set(0), base, (__m128i)idx, (__m128)live, 4);
#else
    vf v;
    for (int l = 0; l < SIMD_LANES; l++)
        v[l] = l < n ? base[idx[l]] : 0;
    return v;
#endif
}

/* the lanes set in m (from a comparison) as bits, lane 0 lowest */
SIMD_INLINE int vi_mask(vi m)
{
#if SIMD_LANES == 8
    return __builtin_ia32_movmskps256((vf)m);
#elif defined(__SSE__)
    return __builtin_ia32_movmskps((vf)m);
#else
    return (m[0] & 1) | (m[1] & 2) | (m[2] & 4) | (m[3] & 8);
#endif
}

/* any lane set? every lane set? how many? (m from a comparison) */
SIMD_INLINE int vi_any(vi m)
{
    return vi_mask(m) != 0;
}

SIMD_INLINE int vi_all(vi m)
{
    return vi_mask(m) == (1 << SIMD_LANES) - 1;
}

SIMD_INLINE int vi_count(vi m)
{
    unsigned b = (unsigned)vi_mask(m); /* at most 8 bits: no popcount instruction needed */
    b = b - ((b >> 1) & 0x55);
    b = (b & 0x33) + ((b >> 2) & 0x33);
    return (int)((b + (b >> 4)) & 0x0f);
}

#endif
