/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* Vectors of four doubles for the solvers' per-face and per-vertex kernels
 * (GCC/Clang vector extensions). Code written on them does, in every lane,
 * the scalar code's operations in the scalar code's order (the library is
 * built with -ffp-contract=off), so a lane gets the scalar code's bits. A
 * kernel is written once as an always-inline function and compiled twice:
 * for the baseline (SSE2 on x86-64: two lanes per instruction) and, on
 * x86-64, with AVX2 (four lanes) and with AVX-512 (four lanes, 32
 * registers), chosen at run time. */
#ifndef FACET_SIMD_H
#define FACET_SIMD_H

#include <math.h>
#include <stdint.h>

typedef double v4d __attribute__((vector_size(32)));
typedef int64_t v4i __attribute__((vector_size(32)));

/* the helpers are always inlined: no vector crosses a call */
#if defined(__clang__)
#pragma clang diagnostic ignored "-Wpsabi"
#elif defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define FACET_HAVE_AVX2_CLONE 1
#define FACET_TARGET_AVX2 __attribute__((target("avx2")))
/* The same four-lane code with AVX-512's 32 vector registers and mask
 * registers (fewer spills of the kernels' many live vectors: about 5%
 * faster on Zen 4); the vectors stay four doubles wide. */
#define FACET_TARGET_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq")))
/* The copy a kernel runs: 0 baseline, 1 AVX2, 2 AVX-512. Tests lower
 * facet_simd_max_level to run the other copies on a processor that has
 * AVX-512. */
extern int facet_simd_max_level;
static inline int facet_simd_level(void)
{
    int level = 0;
    if (__builtin_cpu_supports("avx2"))
        level = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                        __builtin_cpu_supports("avx512dq")
                    ? 2
                    : 1;
    return level < facet_simd_max_level ? level : facet_simd_max_level;
}
#else
#define FACET_HAVE_AVX2_CLONE 0
#endif

static inline __attribute__((always_inline)) v4d v4_select(v4i mask, v4d yes, v4d no)
{
    return (v4d)((mask & (v4i)yes) | (~mask & (v4i)no));
}

static inline __attribute__((always_inline)) v4d v4_abs(v4d x)
{
    const v4i magnitude = {INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX};
    return (v4d)((v4i)x & magnitude);
}

static inline __attribute__((always_inline)) int v4_any(v4i mask)
{
    return (mask[0] | mask[1] | mask[2] | mask[3]) != 0;
}

static inline __attribute__((always_inline)) v4d v4_sqrt(v4d x)
{
    v4d r;
    for (int l = 0; l < 4; ++l)
        r[l] = sqrt(x[l]);
    return r;
}

#if FACET_HAVE_AVX2_CLONE
/* Vectors of eight doubles, for the AVX-512 copy only: every helper carries
 * its target (Clang refuses a 64-byte vector argument of a function without
 * AVX-512, even one always inlined: make fuzz-build failed). */
#include <immintrin.h>
typedef double v8d __attribute__((vector_size(64)));
typedef int64_t v8i __attribute__((vector_size(64)));

static inline __attribute__((always_inline)) FACET_TARGET_AVX512 v8d v8_select(v8i mask, v8d yes, v8d no)
{
    return (v8d)((mask & (v8i)yes) | (~mask & (v8i)no));
}

static inline __attribute__((always_inline)) FACET_TARGET_AVX512 v8d v8_abs(v8d x)
{
    const v8i magnitude = {INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX,
                           INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX};
    return (v8d)((v8i)x & magnitude);
}

/* a test into a mask register, instead of moving the eight lanes to
 * general registers one by one (about 1% of an L/L iteration) */
static inline __attribute__((always_inline)) FACET_TARGET_AVX512 int v8_any(v8i mask)
{
    return _mm512_test_epi64_mask((__m512i)mask, (__m512i)mask) != 0;
}

static inline __attribute__((always_inline)) FACET_TARGET_AVX512 v8d v8_sqrt(v8d x)
{
    v8d r;
    for (int l = 0; l < 8; ++l)
        r[l] = sqrt(x[l]);
    return r;
}
#endif

#endif
