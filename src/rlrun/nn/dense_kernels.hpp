#pragma once
// Register-blocked matrix-product kernels with fused epilogues for the small, fixed-shape
// products of an Mlp (e.g. 64x64 weights times 64x256 batches). Eigen's general GEMM packs both
// operands on every call and tiles 24x4; for these shapes that reached ~60% of this machine's
// single-core FMA peak, and Eigen does not vectorise tanh over a broadcast bias expression. These
// kernels skip packing (the weights fit in L1/L2), use a 2-packet x 6-column register tile (12
// accumulators, the shape that fits 16 vector registers) and apply bias + activation or the
// activation derivative while the tile is still in registers. They are written with Eigen's
// packet primitives, so the same code targets SSE, AVX2, AVX-512 or NEON.
//
// All matrices are column-major float with explicit leading dimensions. The caller (Mlp) picks
// the kernel: gemm_rows vectorises over the output rows (needs m >= packet size to pay off),
// gemm_dot over the reduction dimension (for outputs with few rows, e.g. a 1- or 2-unit head).
#include <Eigen/Core>

namespace rlrun::dense {

using Eigen::Index;

// What happens to each computed element s = C(i, j) before it is written.
enum class Epilogue {
  kStore,           // c(i, j) = s
  kAdd,             // c(i, j) += s
  kAddTransposed,   // c(j, i) += s   (ldc is the leading dimension of the transposed target)
  kBias,            // c(i, j) = s + bias(i)
  kBiasTanh,        // c(i, j) = tanh(s + bias(i))
  kBiasReLU,        // c(i, j) = max(s + bias(i), 0)
  kBiasELU,         // c(i, j) = v > 0 ? v : exp(v) - 1, v = s + bias(i)   (nn.ELU, alpha 1)
  kBiasLeakyReLU,   // c(i, j) = max(v, 0.01 v), v = s + bias(i)   (nn.LeakyReLU, slope 0.01)
  kTanhGrad,        // c(i, j) = s * (1 - act(i, j)^2)   (act = the layer's tanh output)
  kReLUGrad,        // c(i, j) = act(i, j) > 0 ? s : 0   (act = the layer's relu output)
  kELUGrad,         // c(i, j) = act(i, j) > 0 ? s : s * (act(i, j) + 1)   (elu output)
  kLeakyReLUGrad,   // c(i, j) = act(i, j) > 0 ? s : 0.01 s   (leaky_relu output)
};

struct EpilogueArgs {
  float* c = nullptr;
  Index ldc = 0;
  const float* bias = nullptr;  // kBias*
  const float* act = nullptr;   // k*Grad
  Index ld_act = 0;
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

// Number of floats in one SIMD packet (8 with AVX2).
int packet_size();

}  // namespace rlrun::dense
