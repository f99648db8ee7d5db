// The dense kernels on AVX2 + FMA (8 lanes, 16 registers). CMakeLists.txt compiles this file
// with -mavx2 -mfma -ffp-contract=off; nothing in it runs unless dense_kernels.cpp found AVX2
// and FMA on the CPU.
#include "rlrun/nn/dense_kernels_paths.hpp"

#if defined(RLRUN_KERNELS_X86)
#include "rlrun/nn/dense_kernel_set.hpp"
#include "rlrun/nn/simd/vec_avx2.hpp"

namespace rlrun::dense {

const KernelTable& avx2_kernels() { return KernelSet<simd::VecAvx2>::table(KernelPath::kAvx2); }

}  // namespace rlrun::dense
#endif
