#pragma once
// Register-blocked matrix-product kernels with fused epilogues for the small, fixed-shape
// products of an Mlp (e.g. 64x64 weights times 64x256 batches). Eigen's general GEMM packs both
// operands on every call and tiles 24x4; for these shapes that reached ~60% of this machine's
// single-core FMA peak, and Eigen does not vectorise tanh over a broadcast bias expression. These
// kernels skip packing (the weights fit in L1/L2), use a 2-packet x 6-column register tile (12
// accumulators, the shape that fits 16 vector registers) and apply bias + activation or the
// activation derivative while the tile is still in registers.
//
// One binary, every x86-64 CPU, the same bits (docs/portability.md). The kernels are compiled
// once per instruction set (dense_kernels_avx512.cpp, _avx2.cpp, _baseline.cpp, all from
// dense_kernel_set.hpp) and the best one the CPU has is picked at run time; select_kernels()
// (RLRUN_KERNELS=avx512|avx2|baseline for the programs) forces one. The AVX-512 and AVX2 kernels give bit-identical results
// (dense_kernel_set.hpp says how), so a seed trains the same model on every node of a cluster;
// only the baseline path (CPUs without AVX2 + FMA) rounds a * b + c twice.
//
// All matrices are column-major float with explicit leading dimensions. The caller (Mlp) picks
// the kernel from the shapes alone: gemm_rows vectorises over the output rows (for m >=
// kLogicalLanes), gemm_dot over the reduction dimension (outputs with few rows, e.g. a 1- or
// 2-unit head).
#include <cstddef>
#include <string>

namespace rlrun::dense {

using Index = std::ptrdiff_t;

// The width the kernels' results are defined by, whatever the registers hold: gemm_dot adds
// its terms in 16 lanes, and callers choose between kernels by comparing shapes with it.
inline constexpr int kLogicalLanes = 16;

// What happens to each computed element s = C(i, j) before it is written.
enum class Epilogue {
  kStore,          // c(i, j) = s
  kAdd,            // c(i, j) += s
  kAddTransposed,  // c(j, i) += s   (ldc is the leading dimension of the transposed target)
  kBias,           // c(i, j) = s + bias(i)
  kBiasTanh,       // c(i, j) = tanh(s + bias(i))
  kBiasReLU,       // c(i, j) = max(s + bias(i), 0)
  kBiasELU,        // c(i, j) = v > 0 ? v : exp(v) - 1, v = s + bias(i)   (nn.ELU, alpha 1)
  kBiasLeakyReLU,  // c(i, j) = max(v, 0.01 v), v = s + bias(i)   (nn.LeakyReLU, slope 0.01)
  kBiasGELU,       // c(i, j) = v Phi(v), pre(i, j) = v = s + bias(i)   (nn.GELU, exact erf form)
  kTanhGrad,       // c(i, j) = s * (1 - act(i, j)^2)   (act = the layer's tanh output)
  kReLUGrad,       // c(i, j) = act(i, j) > 0 ? s : 0   (act = the layer's relu output)
  kELUGrad,        // c(i, j) = act(i, j) > 0 ? s : s * (act(i, j) + 1)   (elu output)
  kLeakyReLUGrad,  // c(i, j) = act(i, j) > 0 ? s : 0.01 s   (leaky_relu output)
  kGELUGrad,       // c(i, j) = s * gelu'(act(i, j))   (act = the pre-activation, kBiasGELU's pre)
};

struct EpilogueArgs {
  float* c = nullptr;
  Index ldc = 0;
  const float* bias = nullptr;  // kBias*
  const float* act = nullptr;   // k*Grad
  Index ld_act = 0;
  // kBiasGELU also writes the pre-activation v here (same shape and ldc as c): GELU's
  // derivative cannot be read off its output (gelu is not monotonic), so kGELUGrad reads v.
  float* pre = nullptr;
};

// C(i, j) <- epilogue(sum_k A(i, k) B(k, j)) for i < m, j < n, with A column-major (lda) and
// B(k, j) = b[k * b_k + j * b_j] (any strides: B is only read one scalar at a time).
void gemm_rows(Index m, Index n, Index k, const float* a, Index lda, const float* b, Index b_k,
               Index b_j, Epilogue epilogue, const EpilogueArgs& args);

// C(i, j) <- epilogue(sum_p X(p, i) Y(p, j)) for i < m, j < n: dot products of columns of X
// (p x m, ldx) and Y (p x n, ldy).
void gemm_dot(Index m, Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
              Epilogue epilogue, const EpilogueArgs& args);

// B = A^T for A rows x cols (column-major, lda) into B cols x rows (ldb), in packet-sized
// square blocks (a plain element loop writes with a stride and ran ~10x slower; Mlp transposes
// a weight for every backward pass).
void transpose(Index rows, Index cols, const float* a, Index lda, float* b, Index ldb);

// out(i) += sum_j D(i, j) for i < m, j < n (D column-major, ldd), j in order: a bias gradient.
void row_sum_add(Index m, Index n, const float* d, Index ldd, float* out);

// One Adam step over n parameters (nn/adam.cpp computes the coefficients once per step).
struct AdamCoefficients {
  float w1;  // 1 - beta1
  float beta2;
  float w2;                // 1 - beta2
  float step_size;         // lr / (1 - beta1^t)
  float inv_bias_c2_sqrt;  // 1 / sqrt(1 - beta2^t)
  float eps;
};
void adam_update(Index n, float* value, const float* grad, float* exp_avg, float* exp_avg_sq,
                 const AdamCoefficients& coefficients);

// One RMSprop step over n parameters (nn/rmsprop.cpp).
void rmsprop_update(Index n, float* value, const float* grad, float* square_avg, float alpha,
                    float lr, float eps);
// sum_i g_i^2, the same bits on the AVX2 and AVX-512 paths (clip_grad.cpp, split_adam.cpp).
double sum_of_squares(Index n, const float* g);

// ---- which kernels run ----------------------------------------------------------------------

enum class KernelPath { kBaseline, kAvx2, kAvx512 };

// The functions above for one instruction set.
struct KernelTable {
  KernelPath path;
  void (*gemm_rows)(Index, Index, Index, const float*, Index, const float*, Index, Index, Epilogue,
                    const EpilogueArgs&);
  void (*gemm_dot)(Index, Index, Index, const float*, Index, const float*, Index, Epilogue,
                   const EpilogueArgs&);
  void (*transpose)(Index, Index, const float*, Index, float*, Index);
  void (*row_sum_add)(Index, Index, const float*, Index, float*);
  void (*adam_update)(Index, float*, const float*, float*, float*, const AdamCoefficients&);
  void (*rmsprop_update)(Index, float*, const float*, float*, float, float, float);
  double (*sum_of_squares)(Index, const float*);
};

// "avx512", "avx2" or "baseline" ("baseline" is SSE4.2 on x86-64, the portable vector
// extension elsewhere).
const char* kernel_path_name(KernelPath path);
// Whether this binary has the path and this CPU (and OS) can run it.
bool kernel_path_available(KernelPath path);
// The fastest path available here (what active_kernels() uses unless told otherwise).
KernelPath best_kernel_path();
// The kernels of a path; throws std::runtime_error when it is not available.
const KernelTable& kernels(KernelPath path);
// Chooses the path the functions above use: "avx512", "avx2", "baseline", or "auto"/"" for
// the best available. Called once by the programs' entry points before any work (the user's
// RLRUN_KERNELS, apps/common/process_environment.cpp). Throws std::runtime_error for a name
// that is no path or a path this CPU cannot run.
void select_kernels(const std::string& name);
// The chosen kernels; the best available when select_kernels was not called.
const KernelTable& active_kernels();

}  // namespace rlrun::dense
