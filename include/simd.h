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

typedef float f4 __attribute__((vector_size(16)));
typedef int32_t i4 __attribute__((vector_size(16)));

#define SIMD_LANES 4

static inline f4 f4_set(float a)
{
    return (f4){a, a, a, a};
}

static inline i4 i4_set(int32_t a)
{
    return (i4){a, a, a, a};
}

/* m ? a : b, lane by lane (m from a comparison: every lane 0 or -1) */
static inline f4 f4_select(i4 m, f4 a, f4 b)
{
#if defined(__SSE4_1__)
    return __builtin_ia32_blendvps(b, a, (f4)m);
#else
    return (f4)((m & (i4)a) | (~m & (i4)b));
#endif
}

static inline i4 i4_select(i4 m, i4 a, i4 b)
{
#if defined(__SSE4_1__)
    return (i4)__builtin_ia32_blendvps((f4)b, (f4)a, (f4)m);
#else
    return (m & a) | (~m & b);
#endif
}

/* a > b ? a : b and a < b ? a : b, lane by lane: exactly that expression (b when either is
 * NaN or both are zeros), which is what SSE's maxps / minps compute */
static inline f4 f4_max(f4 a, f4 b)
{
#if defined(__SSE__)
    return __builtin_ia32_maxps(a, b);
#else
    return f4_select(a > b, a, b);
#endif
}

static inline f4 f4_min(f4 a, f4 b)
{
#if defined(__SSE__)
    return __builtin_ia32_minps(a, b);
#else
    return f4_select(a < b, a, b);
#endif
}

static inline f4 f4_from_i4(i4 a)
{
    return __builtin_convertvector(a, f4);
}

/* truncation toward zero; |a| must be below 2^31 (callers clamp first) */
static inline i4 i4_trunc(f4 a)
{
    return __builtin_convertvector(a, i4);
}

/* floor of each lane, as an integer; |a| must be below 2^31 (callers clamp first) */
static inline i4 i4_floor(f4 a)
{
#if defined(__SSE4_1__)
    return i4_trunc(__builtin_ia32_roundps(a, 0x9)); /* toward -inf, no exception */
#else
    i4 i = i4_trunc(a);
    return i + (f4_from_i4(i) > a); /* -1 where truncation rounded a negative a up */
#endif
}

/* square root of each lane: the same IEEE result as sqrtf */
static inline f4 f4_sqrt(f4 a)
{
#if defined(__SSE__)
    return __builtin_ia32_sqrtps(a);
#else
    return (f4){__builtin_sqrtf(a[0]), __builtin_sqrtf(a[1]), __builtin_sqrtf(a[2]),
                __builtin_sqrtf(a[3])};
#endif
}

/* log2 of positive finite lanes, to about 0.0013 (exponent bits plus a cubic on the
 * mantissa): a texture's level of detail needs no more. Zero, negative or non-finite lanes
 * give garbage, which callers select away. */
static inline f4 f4_log2(f4 x)
{
    i4 b = (i4)x;
    f4 e = f4_from_i4(((b >> 23) & i4_set(255)) - i4_set(127));
    f4 t = (f4)((b & i4_set(0x7fffff)) | i4_set(0x3f800000)) - f4_set(1.0f); /* [0,1) */
    f4 p = t * (f4_set(1.4234853f) + t * (f4_set(-0.5877338f) + t * f4_set(0.1655588f)));
    return e + p;
}

/* any lane set? (m from a comparison) */
static inline int i4_any(i4 m)
{
#if defined(__SSE__)
    return __builtin_ia32_movmskps((f4)m) != 0;
#else
    return (m[0] | m[1] | m[2] | m[3]) != 0;
#endif
}

/* every lane set? (m from a comparison) */
static inline int i4_all(i4 m)
{
#if defined(__SSE__)
    return __builtin_ia32_movmskps((f4)m) == 15;
#else
    return (m[0] & m[1] & m[2] & m[3]) != 0;
#endif
}

#endif
