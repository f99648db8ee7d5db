// The dense kernels every CPU runs: SSE4.2 on x86-64 (the portable build's x86-64-v2 floor),
// the compiler's portable vector extension elsewhere. Compiled with -ffp-contract=off like the
// other paths (CMakeLists.txt).
#include "rlrun/nn/dense_kernels_paths.hpp"

#if defined(__x86_64__)
#include "rlrun/nn/simd/vec_sse.hpp"
#else
#include "rlrun/nn/simd/vec_generic.hpp"
#endif
#include "rlrun/nn/dense_kernel_set.hpp"

namespace rlrun::dense {

const KernelTable& baseline_kernels() {
#if defined(__x86_64__)
  return KernelSet<simd::VecSse>::table(KernelPath::kBaseline);
#else
  return KernelSet<simd::VecGeneric>::table(KernelPath::kBaseline);
#endif
}

}  // namespace rlrun::dense
