#pragma once
// The per-instruction-set kernel tables, for dense_kernels.cpp's dispatch only. Each is defined
// in its own translation unit, compiled with that instruction set (CMakeLists.txt).
#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun::dense {

const KernelTable& baseline_kernels();  // dense_kernels_baseline.cpp
#if defined(RLRUN_KERNELS_X86)
const KernelTable& avx2_kernels();    // dense_kernels_avx2.cpp: -mavx2 -mfma
const KernelTable& avx512_kernels();  // dense_kernels_avx512.cpp: x86-64-v4's AVX-512 subset
#endif

}  // namespace rlrun::dense
