#pragma once
// 16-lane float vector on AVX-512F (+VL/DQ/BW, i.e. x86-64-v4), for the kernels of
// dense_kernels_avx512.cpp only: include it from a translation unit compiled with those flags,
// inside an anonymous namespace's reach (see vec_ops.hpp for the operations every vector type
// provides and why they are spelled out).
#include <immintrin.h>

#include "rlrun/nn/simd/vec_avx2.hpp"  // reduce_8_lanes

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
  // B(j.., i..) = A(i.., j..)^T for one 16x16 block (column-major, leading dimensions lda,
  // ldb): unpack pairs, then quads, then gather 128-bit lanes in two shuffles. Twice the block
  // of the 8x8 AVX version, half the loop overhead: the backward pass transposes every hidden
  // weight once per gradient step (4 % of a zoo-size SAC step with 8x8 blocks).
  static constexpr int kTransposeBlock = 16;
  static void transpose_block(const float* a, long lda, float* b, long ldb) {
    __m512 r[16], t[16], u[16];
    for (int q = 0; q < 16; ++q) r[q] = _mm512_loadu_ps(a + q * lda);
    for (int q = 0; q < 16; q += 2) {
      t[q] = _mm512_unpacklo_ps(r[q], r[q + 1]);
      t[q + 1] = _mm512_unpackhi_ps(r[q], r[q + 1]);
    }
    // u[4k + j], 128-bit lane L: rows 4k..4k+3 of column 4L + j.
    for (int k = 0; k < 16; k += 4) {
      const __m512d t0 = _mm512_castps_pd(t[k]), t1 = _mm512_castps_pd(t[k + 1]),
                    t2 = _mm512_castps_pd(t[k + 2]), t3 = _mm512_castps_pd(t[k + 3]);
      u[k] = _mm512_castpd_ps(_mm512_unpacklo_pd(t0, t2));
      u[k + 1] = _mm512_castpd_ps(_mm512_unpackhi_pd(t0, t2));
      u[k + 2] = _mm512_castpd_ps(_mm512_unpacklo_pd(t1, t3));
      u[k + 3] = _mm512_castpd_ps(_mm512_unpackhi_pd(t1, t3));
    }
    for (int j = 0; j < 4; ++j) {
      const __m512 v0 = _mm512_shuffle_f32x4(u[j], u[4 + j], 0x88);
      const __m512 v1 = _mm512_shuffle_f32x4(u[j], u[4 + j], 0xDD);
      const __m512 w0 = _mm512_shuffle_f32x4(u[8 + j], u[12 + j], 0x88);
      const __m512 w1 = _mm512_shuffle_f32x4(u[8 + j], u[12 + j], 0xDD);
      _mm512_storeu_ps(b + j * ldb, _mm512_shuffle_f32x4(v0, w0, 0x88));         // column j
      _mm512_storeu_ps(b + (4 + j) * ldb, _mm512_shuffle_f32x4(v1, w1, 0x88));   // 4 + j
      _mm512_storeu_ps(b + (8 + j) * ldb, _mm512_shuffle_f32x4(v0, w0, 0xDD));   // 8 + j
      _mm512_storeu_ps(b + (12 + j) * ldb, _mm512_shuffle_f32x4(v1, w1, 0xDD));  // 12 + j
    }
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
  const __m512i bits =
      _mm512_slli_epi32(_mm512_add_epi32(_mm512_cvttps_epi32(n.r), _mm512_set1_epi32(127)), 23);
  return {_mm512_castsi512_ps(bits)};
}

}  // namespace
}  // namespace rlrun::dense::simd
