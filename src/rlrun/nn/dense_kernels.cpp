// Holds the dense kernels chosen for this CPU (select_kernels) and forwards every call to them
// (dense_kernels.hpp). The kernels themselves live in dense_kernel_set.hpp, compiled per
// instruction set by dense_kernels_{avx512,avx2,baseline}.cpp.
#include "rlrun/nn/dense_kernels.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

#include "rlrun/nn/dense_kernels_paths.hpp"

namespace rlrun::dense {

const char* kernel_path_name(KernelPath path) {
  switch (path) {
    case KernelPath::kAvx512: return "avx512";
    case KernelPath::kAvx2: return "avx2";
    case KernelPath::kBaseline: return "baseline";
  }
  return "?";
}

bool kernel_path_available(KernelPath path) {
  switch (path) {
    case KernelPath::kBaseline: return true;
#if defined(RLRUN_KERNELS_X86)
    // __builtin_cpu_supports reads CPUID and, for AVX and AVX-512, whether the OS saves the
    // wider registers (XGETBV); x86-64-v4's subset (F, VL, DQ, BW) is what the AVX-512 file is
    // compiled for.
    case KernelPath::kAvx2: return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case KernelPath::kAvx512:
      return kernel_path_available(KernelPath::kAvx2) && __builtin_cpu_supports("avx512f") &&
             __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512bw");
#else
    default: return false;
#endif
  }
  return false;
}

const KernelTable& kernels(KernelPath path) {
  if (!kernel_path_available(path)) {
    throw std::runtime_error(std::string("the ") + kernel_path_name(path) +
                             " kernels do not run on this CPU (or were not built for it)");
  }
  switch (path) {
#if defined(RLRUN_KERNELS_X86)
    case KernelPath::kAvx512: return avx512_kernels();
    case KernelPath::kAvx2: return avx2_kernels();
#endif
    default: return baseline_kernels();
  }
}

KernelPath best_kernel_path() {
  for (KernelPath path : {KernelPath::kAvx512, KernelPath::kAvx2}) {
    if (kernel_path_available(path)) return path;
  }
  return KernelPath::kBaseline;
}

namespace {

// The table select_kernels() chose; null: the best available.
std::atomic<const KernelTable*> selected_table{nullptr};

}  // namespace

void select_kernels(const std::string& name) {
  if (name.empty() || name == "auto") {
    selected_table.store(&kernels(best_kernel_path()));
    return;
  }
  for (KernelPath path : {KernelPath::kAvx512, KernelPath::kAvx2, KernelPath::kBaseline}) {
    if (name == kernel_path_name(path)) {
      if (!kernel_path_available(path))
        throw std::runtime_error(name + ": the " + name + " kernels do not run on this CPU");
      selected_table.store(&kernels(path));
      return;
    }
  }
  throw std::runtime_error(name + ": expected auto, avx512, avx2 or baseline");
}

const KernelTable& active_kernels() {
  if (const KernelTable* table = selected_table.load(std::memory_order_relaxed)) return *table;
  static const KernelTable& best = kernels(best_kernel_path());
  return best;
}

void gemm_rows(Index m, Index n, Index k, const float* a, Index lda, const float* b, Index b_k,
               Index b_j, Epilogue epilogue, const EpilogueArgs& args) {
  active_kernels().gemm_rows(m, n, k, a, lda, b, b_k, b_j, epilogue, args);
}

void gemm_dot(Index m, Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
              Epilogue epilogue, const EpilogueArgs& args) {
  active_kernels().gemm_dot(m, n, p, x, ldx, y, ldy, epilogue, args);
}

void transpose(Index rows, Index cols, const float* a, Index lda, float* b, Index ldb) {
  active_kernels().transpose(rows, cols, a, lda, b, ldb);
}

void row_sum_add(Index m, Index n, const float* d, Index ldd, float* out) {
  active_kernels().row_sum_add(m, n, d, ldd, out);
}

}  // namespace rlrun::dense

namespace rlrun::dense {

void adam_update(Index n, float* value, const float* grad, float* exp_avg, float* exp_avg_sq,
                 const AdamCoefficients& coefficients) {
  active_kernels().adam_update(n, value, grad, exp_avg, exp_avg_sq, coefficients);
}

void rmsprop_update(Index n, float* value, const float* grad, float* square_avg, float alpha,
                    float lr, float eps) {
  active_kernels().rmsprop_update(n, value, grad, square_avg, alpha, lr, eps);
}

double sum_of_squares(Index n, const float* g) { return active_kernels().sum_of_squares(n, g); }

}  // namespace rlrun::dense
