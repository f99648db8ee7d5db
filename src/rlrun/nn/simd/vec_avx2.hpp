#pragma once
// 8-lane float vector on AVX2 + FMA (x86-64-v3), for dense_kernels_avx2.cpp only (see
// vec_ops.hpp for the operations every vector type provides).
#include <immintrin.h>

namespace rlrun::dense::simd {
namespace {

// B(j.., i..) = A(i.., j..)^T for one 8x8 block (column-major, leading dimensions lda, ldb):
// unpack pairs, then quads, then swap 128-bit halves.
inline void transpose_8x8(const float* a, long lda, float* b, long ldb) {
  __m256 c[8], t[8];
  for (int q = 0; q < 8; ++q) c[q] = _mm256_loadu_ps(a + q * lda);
  for (int q = 0; q < 8; q += 2) {
    t[q] = _mm256_unpacklo_ps(c[q], c[q + 1]);
    t[q + 1] = _mm256_unpackhi_ps(c[q], c[q + 1]);
  }
  for (int q = 0; q < 8; q += 4) {
    c[q] = _mm256_shuffle_ps(t[q], t[q + 2], _MM_SHUFFLE(1, 0, 1, 0));
    c[q + 1] = _mm256_shuffle_ps(t[q], t[q + 2], _MM_SHUFFLE(3, 2, 3, 2));
    c[q + 2] = _mm256_shuffle_ps(t[q + 1], t[q + 3], _MM_SHUFFLE(1, 0, 1, 0));
    c[q + 3] = _mm256_shuffle_ps(t[q + 1], t[q + 3], _MM_SHUFFLE(3, 2, 3, 2));
  }
  for (int q = 0; q < 4; ++q) {
    _mm256_storeu_ps(b + q * ldb, _mm256_permute2f128_ps(c[q], c[q + 4], 0x20));
    _mm256_storeu_ps(b + (q + 4) * ldb, _mm256_permute2f128_ps(c[q], c[q + 4], 0x31));
  }
}

// t[0] + ... + t[7] as t4[i] = t[i] + t[i + 4], t2[i] = t4[i] + t4[i + 2], t2[0] + t2[1]: the
// last three steps of dense_kernel_set.hpp's 16-lane tree.
inline float reduce_8_lanes(__m256 t) {
  const __m128 t4 = _mm_add_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps(t, 1));
  const __m128 t2 = _mm_add_ps(t4, _mm_movehl_ps(t4, t4));
  return _mm_cvtss_f32(_mm_add_ss(t2, _mm_shuffle_ps(t2, t2, 1)));
}

struct VecAvx2 {
  static constexpr int kLanes = 8;
  static constexpr bool kFusedMultiplyAdd = true;
  static constexpr int kAccumulators = 12;  // of 16 registers
  __m256 r;

  static VecAvx2 zero() { return {_mm256_setzero_ps()}; }
  static VecAvx2 set1(float x) { return {_mm256_set1_ps(x)}; }
  static VecAvx2 load(const float* p) { return {_mm256_loadu_ps(p)}; }
  static __m256i first_lanes(int n) {
    return _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  }
  // Lanes n.. read as 0 and are not touched in memory (n < kLanes).
  static VecAvx2 load_first(const float* p, int n) {
    return {_mm256_maskload_ps(p, first_lanes(n))};
  }
  void store(float* p) const { _mm256_storeu_ps(p, r); }
  void store_first(float* p, int n) const { _mm256_maskstore_ps(p, first_lanes(n), r); }
  static float reduce16(const VecAvx2 (&parts)[2]) {
    return reduce_8_lanes(_mm256_add_ps(parts[0].r, parts[1].r));
  }
  static constexpr int kTransposeBlock = 8;
  static void transpose_block(const float* a, long lda, float* b, long ldb) {
    transpose_8x8(a, lda, b, ldb);
  }
};

inline VecAvx2 operator+(VecAvx2 a, VecAvx2 b) { return {_mm256_add_ps(a.r, b.r)}; }
inline VecAvx2 operator-(VecAvx2 a, VecAvx2 b) { return {_mm256_sub_ps(a.r, b.r)}; }
inline VecAvx2 operator*(VecAvx2 a, VecAvx2 b) { return {_mm256_mul_ps(a.r, b.r)}; }
inline VecAvx2 operator/(VecAvx2 a, VecAvx2 b) { return {_mm256_div_ps(a.r, b.r)}; }
inline VecAvx2 fma(VecAvx2 a, VecAvx2 b, VecAvx2 c) { return {_mm256_fmadd_ps(a.r, b.r, c.r)}; }
inline VecAvx2 max(VecAvx2 a, VecAvx2 b) { return {_mm256_max_ps(a.r, b.r)}; }
inline VecAvx2 min(VecAvx2 a, VecAvx2 b) { return {_mm256_min_ps(a.r, b.r)}; }
inline VecAvx2 select_greater(VecAvx2 a, VecAvx2 b, VecAvx2 x, VecAvx2 y) {
  return {_mm256_blendv_ps(y.r, x.r, _mm256_cmp_ps(a.r, b.r, _CMP_GT_OQ))};
}
inline VecAvx2 sqrt(VecAvx2 a) { return {_mm256_sqrt_ps(a.r)}; }
inline VecAvx2 floor(VecAvx2 a) { return {_mm256_floor_ps(a.r)}; }
inline VecAvx2 exp2_integer(VecAvx2 n) {
  const __m256i bits =
      _mm256_slli_epi32(_mm256_add_epi32(_mm256_cvttps_epi32(n.r), _mm256_set1_epi32(127)), 23);
  return {_mm256_castsi256_ps(bits)};
}

}  // namespace
}  // namespace rlrun::dense::simd
