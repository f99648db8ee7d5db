#pragma once
// 16-lane float vector on AVX-512F (+VL/DQ/BW, i.e. x86-64-v4), for the kernels of
// dense_kernels_avx512.cpp only: include it from a translation unit compiled with those flags,
// inside an anonymous namespace's reach (see vec_ops.hpp for the operations every vector type
// provides and why they are spelled out).
#include <immintrin.h>

#include "rlrun/nn/simd/vec_avx2.hpp"  // transpose_8x8

namespace rlrun::dense::simd {
namespace {

struct VecAvx512 {
  static constexpr int kLanes = 16;
  static constexpr bool kFusedMultiplyAdd = true;
  // Accumulators a tile may hold: 32 registers, a few kept for operands.
  static constexpr int kAccumulators = 24;
  __m512 r;

  static VecAvx512 zero() { return {_mm512_setzero_ps()}; }
  static VecAvx512 set1(float x) { return {_mm512_set1_ps(x)}; }
  static VecAvx512 load(const float* p) { return {_mm512_loadu_ps(p)}; }
  // Lanes n.. read as 0 and are not touched in memory (n < kLanes).
  static VecAvx512 load_first(const float* p, int n) {
    return {_mm512_maskz_loadu_ps(static_cast<__mmask16>((1u << n) - 1u), p)};
  }
  void store(float* p) const { _mm512_storeu_ps(p, r); }
  void store_first(float* p, int n) const {
    _mm512_mask_storeu_ps(p, static_cast<__mmask16>((1u << n) - 1u), r);
  }
  // The 16 lanes added in dense_kernel_set.hpp's fixed tree (l[i] + l[i + 8], then + 4, + 2,
  // + 1), as reduce_8_lanes() does it after the first step.
  static float reduce16(const VecAvx512 (&parts)[1]) {
    const __m512 v = parts[0].r;
    return reduce_8_lanes(_mm256_add_ps(_mm512_castps512_ps256(v), _mm512_extractf32x8_ps(v, 1)));
  }
  // 8x8 blocks on 256-bit halves: a transpose moves data, it does no arithmetic, and 16x16
  // blocks were not faster for the 64-wide weights it serves.
  static constexpr int kTransposeBlock = 8;
  static void transpose_block(const float* a, long lda, float* b, long ldb) {
    transpose_8x8(a, lda, b, ldb);
  }
};

inline VecAvx512 operator+(VecAvx512 a, VecAvx512 b) { return {_mm512_add_ps(a.r, b.r)}; }
inline VecAvx512 operator-(VecAvx512 a, VecAvx512 b) { return {_mm512_sub_ps(a.r, b.r)}; }
inline VecAvx512 operator*(VecAvx512 a, VecAvx512 b) { return {_mm512_mul_ps(a.r, b.r)}; }
inline VecAvx512 operator/(VecAvx512 a, VecAvx512 b) { return {_mm512_div_ps(a.r, b.r)}; }
// a * b + c with one rounding.
inline VecAvx512 fma(VecAvx512 a, VecAvx512 b, VecAvx512 c) {
  return {_mm512_fmadd_ps(a.r, b.r, c.r)};
}
inline VecAvx512 max(VecAvx512 a, VecAvx512 b) { return {_mm512_max_ps(a.r, b.r)}; }
inline VecAvx512 min(VecAvx512 a, VecAvx512 b) { return {_mm512_min_ps(a.r, b.r)}; }
// a > b ? x : y, lane by lane (false for NaN, like the scalar comparison).
inline VecAvx512 select_greater(VecAvx512 a, VecAvx512 b, VecAvx512 x, VecAvx512 y) {
  return {_mm512_mask_blend_ps(_mm512_cmp_ps_mask(a.r, b.r, _CMP_GT_OQ), y.r, x.r)};
}
inline VecAvx512 sqrt(VecAvx512 a) { return {_mm512_sqrt_ps(a.r)}; }
inline VecAvx512 floor(VecAvx512 a) {
  return {_mm512_roundscale_ps(a.r, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC)};
}
// 2^n for integral n in [-126, 127], built in the exponent bits.
inline VecAvx512 exp2_integer(VecAvx512 n) {
  const __m512i bits = _mm512_slli_epi32(
      _mm512_add_epi32(_mm512_cvttps_epi32(n.r), _mm512_set1_epi32(127)), 23);
  return {_mm512_castsi512_ps(bits)};
}

}  // namespace
}  // namespace rlrun::dense::simd
