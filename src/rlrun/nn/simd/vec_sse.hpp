#pragma once
// 4-lane float vector on SSE4.1 (part of x86-64-v2), for dense_kernels_baseline.cpp: the
// kernels of CPUs without AVX2 + FMA. There is no fused multiply-add here, so fma() rounds
// twice and this path's results differ from the AVX2 / AVX-512 ones in the last bits
// (docs/portability.md).
#include <immintrin.h>

namespace rlrun::dense::simd {
namespace {

struct VecSse {
  static constexpr int kLanes = 4;
  static constexpr bool kFusedMultiplyAdd = false;
  static constexpr int kAccumulators = 12;
  __m128 r;

  static VecSse zero() { return {_mm_setzero_ps()}; }
  static VecSse set1(float x) { return {_mm_set1_ps(x)}; }
  static VecSse load(const float* p) { return {_mm_loadu_ps(p)}; }
  static VecSse load_first(const float* p, int n) {
    float lanes[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int q = 0; q < n; ++q) lanes[q] = p[q];
    return {_mm_loadu_ps(lanes)};
  }
  void store(float* p) const { _mm_storeu_ps(p, r); }
  void store_first(float* p, int n) const {
    float lanes[4];
    _mm_storeu_ps(lanes, r);
    for (int q = 0; q < n; ++q) p[q] = lanes[q];
  }
  // The fixed 16-lane tree of dense_kernel_set.hpp: lanes 0-3 of t8 are parts 0 + 2, lanes 4-7
  // parts 1 + 3, then t4 = t8[0..3] + t8[4..7], then + 2 lanes, then + 1.
  static float reduce16(const VecSse (&parts)[4]) {
    const __m128 t4 =
        _mm_add_ps(_mm_add_ps(parts[0].r, parts[2].r), _mm_add_ps(parts[1].r, parts[3].r));
    const __m128 t2 = _mm_add_ps(t4, _mm_movehl_ps(t4, t4));
    return _mm_cvtss_f32(_mm_add_ss(t2, _mm_shuffle_ps(t2, t2, 1)));
  }
  // B(j.., i..) = A(i.., j..)^T for one 4x4 block (column-major, leading dimensions lda, ldb).
  static constexpr int kTransposeBlock = 4;
  static void transpose_block(const float* a, long lda, float* b, long ldb) {
    __m128 c0 = _mm_loadu_ps(a), c1 = _mm_loadu_ps(a + lda), c2 = _mm_loadu_ps(a + 2 * lda),
           c3 = _mm_loadu_ps(a + 3 * lda);
    _MM_TRANSPOSE4_PS(c0, c1, c2, c3);
    _mm_storeu_ps(b, c0);
    _mm_storeu_ps(b + ldb, c1);
    _mm_storeu_ps(b + 2 * ldb, c2);
    _mm_storeu_ps(b + 3 * ldb, c3);
  }
};

inline VecSse operator+(VecSse a, VecSse b) { return {_mm_add_ps(a.r, b.r)}; }
inline VecSse operator-(VecSse a, VecSse b) { return {_mm_sub_ps(a.r, b.r)}; }
inline VecSse operator*(VecSse a, VecSse b) { return {_mm_mul_ps(a.r, b.r)}; }
inline VecSse operator/(VecSse a, VecSse b) { return {_mm_div_ps(a.r, b.r)}; }
inline VecSse fma(VecSse a, VecSse b, VecSse c) { return {_mm_add_ps(_mm_mul_ps(a.r, b.r), c.r)}; }
inline VecSse max(VecSse a, VecSse b) { return {_mm_max_ps(a.r, b.r)}; }
inline VecSse min(VecSse a, VecSse b) { return {_mm_min_ps(a.r, b.r)}; }
inline VecSse select_greater(VecSse a, VecSse b, VecSse x, VecSse y) {
  return {_mm_blendv_ps(y.r, x.r, _mm_cmpgt_ps(a.r, b.r))};
}
inline VecSse sqrt(VecSse a) { return {_mm_sqrt_ps(a.r)}; }
inline VecSse floor(VecSse a) { return {_mm_floor_ps(a.r)}; }
inline VecSse exp2_integer(VecSse n) {
  const __m128i bits =
      _mm_slli_epi32(_mm_add_epi32(_mm_cvttps_epi32(n.r), _mm_set1_epi32(127)), 23);
  return {_mm_castsi128_ps(bits)};
}

}  // namespace
}  // namespace rlrun::dense::simd
