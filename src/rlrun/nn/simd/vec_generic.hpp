#pragma once
// 4-lane float vector in GCC/Clang's portable vector extension, for CPUs other than x86-64
// (the compiler maps it to NEON on AArch64). Same operations as the x86 vector types; fma()
// is a * b + c, which the kernels' translation units compile with -ffp-contract=off, so it
// rounds twice here as on the SSE path.
namespace rlrun::dense::simd {
namespace {

using GenericFloat4 = float __attribute__((vector_size(16)));
using GenericInt4 = int __attribute__((vector_size(16)));

struct VecGeneric {
  static constexpr int kLanes = 4;
  static constexpr bool kFusedMultiplyAdd = false;
  static constexpr int kAccumulators = 12;
  GenericFloat4 r;

  static VecGeneric zero() { return {GenericFloat4{0.0f, 0.0f, 0.0f, 0.0f}}; }
  static VecGeneric set1(float x) { return {GenericFloat4{x, x, x, x}}; }
  static VecGeneric load(const float* p) { return {GenericFloat4{p[0], p[1], p[2], p[3]}}; }
  static VecGeneric load_first(const float* p, int n) {
    VecGeneric v = zero();
    for (int q = 0; q < n; ++q) v.r[q] = p[q];
    return v;
  }
  void store(float* p) const {
    for (int q = 0; q < kLanes; ++q) p[q] = r[q];
  }
  void store_first(float* p, int n) const {
    for (int q = 0; q < n; ++q) p[q] = r[q];
  }
  static void transpose_block(const float* a, long lda, float* b, long ldb) {
    for (int j = 0; j < kLanes; ++j)
      for (int i = 0; i < kLanes; ++i) b[j + i * ldb] = a[i + j * lda];
  }
  static constexpr int kTransposeBlock = kLanes;
  static float reduce16(const VecGeneric (&parts)[4]) {
    float l[16];
    for (int q = 0; q < 4; ++q) parts[q].store(l + 4 * q);
    for (int w = 8; w >= 1; w /= 2)
      for (int i = 0; i < w; ++i) l[i] = l[i] + l[i + w];
    return l[0];
  }
};

inline VecGeneric operator+(VecGeneric a, VecGeneric b) { return {a.r + b.r}; }
inline VecGeneric operator-(VecGeneric a, VecGeneric b) { return {a.r - b.r}; }
inline VecGeneric operator*(VecGeneric a, VecGeneric b) { return {a.r * b.r}; }
inline VecGeneric operator/(VecGeneric a, VecGeneric b) { return {a.r / b.r}; }
inline VecGeneric fma(VecGeneric a, VecGeneric b, VecGeneric c) { return {a.r * b.r + c.r}; }
inline VecGeneric max(VecGeneric a, VecGeneric b) { return {a.r > b.r ? a.r : b.r}; }
inline VecGeneric min(VecGeneric a, VecGeneric b) { return {a.r < b.r ? a.r : b.r}; }
inline VecGeneric select_greater(VecGeneric a, VecGeneric b, VecGeneric x, VecGeneric y) {
  return {a.r > b.r ? x.r : y.r};
}
inline VecGeneric sqrt(VecGeneric a) {
  for (int q = 0; q < VecGeneric::kLanes; ++q) a.r[q] = __builtin_sqrtf(a.r[q]);
  return a;
}
inline VecGeneric floor(VecGeneric a) {
  for (int q = 0; q < VecGeneric::kLanes; ++q) a.r[q] = __builtin_floorf(a.r[q]);
  return a;
}
inline VecGeneric exp2_integer(VecGeneric n) {
  GenericInt4 bits;
  for (int q = 0; q < VecGeneric::kLanes; ++q) bits[q] = (static_cast<int>(n.r[q]) + 127) << 23;
  return {reinterpret_cast<GenericFloat4>(bits)};
}

}  // namespace
}  // namespace rlrun::dense::simd
