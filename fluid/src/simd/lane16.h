// fluid — 16 float lanes for the pair passes, on one of three instruction sets.
//
// The including file defines exactly one of FLUID_SIMD_AVX512, FLUID_SIMD_AVX2 or neither (SSE2,
// baseline x86-64; plain floats on other processors) and is compiled with the matching -m flags.
// Every operation is one IEEE-exact per-lane operation (add, subtract, multiply, divide, sqrt, max,
// select) and lanes are reduced in a fixed order, so the three builds give bit-identical results
// (with -ffp-contract=off: no fused multiply-add). Everything here has internal linkage: the three
// object files share no inline function that the linker could pick from the wrong instruction set.
#pragma once

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <cstdint>

// Every loop over a lane group's registers is unrolled: at -O2 g++ keeps a 4-register loop (SSE2)
// as a loop over an array in memory, which made the SSE2 passes 2.5x slower.
#define FLUID_UNROLL _Pragma("GCC unroll 16")

// The wrappers every x86 instruction set spells the same way, from its intrinsics' prefix
// (_mm512, _mm256, _mm): set1, unaligned load and store, + - * /, max and sqrt.
#define FLUID_REG_ARITH(P)                                                                       \
    inline Reg regSet1(float x) { return P##_set1_ps(x); }                                       \
    inline Reg regLoad(const float* p) { return P##_loadu_ps(p); }                               \
    inline void regStore(float* p, Reg a) { P##_storeu_ps(p, a); }                               \
    inline Reg regAdd(Reg a, Reg b) { return P##_add_ps(a, b); }                                 \
    inline Reg regSub(Reg a, Reg b) { return P##_sub_ps(a, b); }                                 \
    inline Reg regMul(Reg a, Reg b) { return P##_mul_ps(a, b); }                                 \
    inline Reg regDiv(Reg a, Reg b) { return P##_div_ps(a, b); }                                 \
    inline Reg regMax(Reg a, Reg b) { return P##_max_ps(a, b); }                                 \
    inline Reg regSqrt(Reg a) { return P##_sqrt_ps(a); }

namespace {

#if defined(FLUID_SIMD_AVX512)
constexpr int kParts = 1;
using Reg = __m512;
using MReg = __mmask16;
FLUID_REG_ARITH(_mm512)
inline MReg regGreater(Reg a, Reg b) {
    return _mm512_cmp_ps_mask(a, b, _CMP_GT_OQ);
}
inline MReg regGreaterEq(Reg a, Reg b) {
    return _mm512_cmp_ps_mask(a, b, _CMP_GE_OQ);
}
inline MReg regAnd(MReg a, MReg b) {
    return MReg(a & b);
}
inline Reg regSelect(MReg m, Reg a, Reg b) {
    return _mm512_mask_blend_ps(m, b, a);
}
#elif defined(FLUID_SIMD_AVX2)
constexpr int kParts = 2;
using Reg = __m256;
using MReg = __m256;
FLUID_REG_ARITH(_mm256)
inline MReg regGreater(Reg a, Reg b) {
    return _mm256_cmp_ps(a, b, _CMP_GT_OQ);
}
inline MReg regGreaterEq(Reg a, Reg b) {
    return _mm256_cmp_ps(a, b, _CMP_GE_OQ);
}
inline MReg regAnd(MReg a, MReg b) {
    return _mm256_and_ps(a, b);
}
inline Reg regSelect(MReg m, Reg a, Reg b) {
    return _mm256_blendv_ps(b, a, m);
}
#elif defined(__SSE2__)
constexpr int kParts = 4;
using Reg = __m128;
using MReg = __m128;
FLUID_REG_ARITH(_mm)
inline MReg regGreater(Reg a, Reg b) {
    return _mm_cmpgt_ps(a, b);
}
inline MReg regGreaterEq(Reg a, Reg b) {
    return _mm_cmpge_ps(a, b);
}
inline MReg regAnd(MReg a, MReg b) {
    return _mm_and_ps(a, b);
}
inline Reg regSelect(MReg m, Reg a, Reg b) {
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}
#else // portable: one float per register, the same semantics as the x86 instructions
constexpr int kParts = 16;
using Reg = float;
using MReg = bool;
inline Reg regSet1(float x) {
    return x;
}
inline Reg regLoad(const float* p) {
    return *p;
}
inline void regStore(float* p, Reg a) {
    *p = a;
}
inline Reg regAdd(Reg a, Reg b) {
    return a + b;
}
inline Reg regSub(Reg a, Reg b) {
    return a - b;
}
inline Reg regMul(Reg a, Reg b) {
    return a * b;
}
inline Reg regDiv(Reg a, Reg b) {
    return a / b;
}
inline Reg regMax(Reg a, Reg b) {
    return a > b ? a : b;
}
inline Reg regSqrt(Reg a) {
    return __builtin_sqrtf(a);
}
inline MReg regGreater(Reg a, Reg b) {
    return a > b;
}
inline MReg regGreaterEq(Reg a, Reg b) {
    return a >= b;
}
inline MReg regAnd(MReg a, MReg b) {
    return a && b;
}
inline Reg regSelect(MReg m, Reg a, Reg b) {
    return m ? a : b;
}
#endif
#undef FLUID_REG_ARITH

constexpr int kLanes16 = 16;
constexpr int kWidth = kLanes16 / kParts; // floats per register

/// 16 float lanes.
struct F {
    Reg v[kParts];
};
/// A per-lane condition.
struct M {
    MReg v[kParts];
};

inline F splat(float x) {
    F r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regSet1(x);
    }
    return r;
}
/// 16 consecutive floats from p (no alignment needed).
inline F load(const float* p) {
    F r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regLoad(p + k * kWidth);
    }
    return r;
}
inline void store(float* p, F a) {
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        regStore(p + k * kWidth, a.v[k]);
    }
}

#define FLUID_LANE_BINARY(op, fn)                                                                  \
    inline F op(F a, F b) {                                                                        \
        F r;                                                                                       \
        FLUID_UNROLL for (int k = 0; k < kParts; ++k) {                                            \
            r.v[k] = fn(a.v[k], b.v[k]);                                                           \
        }                                                                                          \
        return r;                                                                                  \
    }
FLUID_LANE_BINARY(operator+, regAdd)
FLUID_LANE_BINARY(operator-, regSub)
FLUID_LANE_BINARY(operator*, regMul)
FLUID_LANE_BINARY(operator/, regDiv)
/// Per lane, a > b ? a : b (b when either is NaN), the same on every instruction set.
FLUID_LANE_BINARY(vmax, regMax)
#undef FLUID_LANE_BINARY

inline F operator+(F a, float b) {
    return a + splat(b);
}
inline F operator-(float a, F b) {
    return splat(a) - b;
}
inline F operator*(F a, float b) {
    return a * splat(b);
}
inline F operator*(float a, F b) {
    return splat(a) * b;
}
inline F& operator+=(F& a, F b) {
    return a = a + b;
}
inline F& operator-=(F& a, F b) {
    return a = a - b;
}

inline F vsqrt(F a) {
    F r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regSqrt(a.v[k]);
    }
    return r;
}
inline M operator>(F a, F b) {
    M r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regGreater(a.v[k], b.v[k]);
    }
    return r;
}
inline M operator>=(F a, F b) {
    M r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regGreaterEq(a.v[k], b.v[k]);
    }
    return r;
}
inline M operator&(M a, M b) {
    M r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regAnd(a.v[k], b.v[k]);
    }
    return r;
}
/// Per lane, m ? a : b.
inline F select(M m, F a, F b) {
    F r;
    FLUID_UNROLL for (int k = 0; k < kParts; ++k) {
        r.v[k] = regSelect(m.v[k], a.v[k], b.v[k]);
    }
    return r;
}

alignas(64) constexpr float kIota[kLanes16] = {0, 1, 2,  3,  4,  5,  6,  7,
                                               8, 9, 10, 11, 12, 13, 14, 15};
/// Lanes lo <= l < hi.
inline M laneRange(int lo, int hi) {
    const F iota = load(kIota);
    return (iota >= splat(float(lo))) & (splat(float(hi)) > iota);
}

/// Sum of the 16 lanes as one fixed tree, the same on every instruction set: lanes l and l + 8
/// are added, then l and l + 4 of those, then l and l + 2, then the last two. (A sum in lane
/// order is a chain of 15 dependent adds: it cost as much as a range of pairs.)
inline float sum(F a) {
#if defined(FLUID_SIMD_AVX512) || defined(FLUID_SIMD_AVX2) || defined(__SSE2__)
#if defined(FLUID_SIMD_AVX512)
    const __m256 lo8 = _mm512_castps512_ps256(a.v[0]);
    const __m256 hi8 = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a.v[0]), 1));
    const __m256 s8 = _mm256_add_ps(lo8, hi8);
    const __m128 s4 = _mm_add_ps(_mm256_castps256_ps128(s8), _mm256_extractf128_ps(s8, 1));
#elif defined(FLUID_SIMD_AVX2)
    const __m256 s8 = _mm256_add_ps(a.v[0], a.v[1]);
    const __m128 s4 = _mm_add_ps(_mm256_castps256_ps128(s8), _mm256_extractf128_ps(s8, 1));
#else
    const __m128 s4 = _mm_add_ps(_mm_add_ps(a.v[0], a.v[2]), _mm_add_ps(a.v[1], a.v[3]));
#endif
    const __m128 s2 = _mm_add_ps(s4, _mm_movehl_ps(s4, s4));
    return _mm_cvtss_f32(_mm_add_ss(s2, _mm_shuffle_ps(s2, s2, 1)));
#else
    float l[kLanes16];
    store(l, a);
    for (int w = kLanes16 / 2; w > 0; w /= 2) {
        for (int k = 0; k < w; ++k) {
            l[k] += l[k + w];
        }
    }
    return l[0];
#endif
}

} // namespace
