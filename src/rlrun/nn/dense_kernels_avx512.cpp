// The dense kernels on AVX-512 (16 lanes, 32 registers). CMakeLists.txt compiles this file
// with -mavx512f -mavx512vl -mavx512dq -mavx512bw -mavx2 -mfma -ffp-contract=off; nothing in
// it runs unless dense_kernels.cpp found AVX-512 on the CPU.
#include "rlrun/nn/dense_kernels_paths.hpp"

#if defined(RLRUN_KERNELS_X86)
#include "rlrun/nn/simd/vec_avx512.hpp"
// dense_kernel_set.hpp after the vector type: its templates find the operations by lookup.
#include "rlrun/nn/dense_kernel_set.hpp"

namespace rlrun::dense {

const KernelTable& avx512_kernels() {
  return KernelSet<simd::VecAvx512>::table(KernelPath::kAvx512);
}

}  // namespace rlrun::dense
#endif
