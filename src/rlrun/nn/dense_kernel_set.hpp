#pragma once
// The bodies of the dense kernels (dense_kernels.hpp), written once over a SIMD vector type V
// (simd/vec_*.hpp) and compiled once per instruction set by dense_kernels_{avx512,avx2,
// baseline}.cpp. Include it only from those files, after the vector type, inside an anonymous
// namespace: every function here then has internal linkage, so the AVX-512 copy can never be
// linked in place of the SSE one (the classic pitfall of compiling one header with different
// -m flags; for the same reason nothing here calls an inline function of the standard library
// or of Eigen).
//
// Same bits on every path. The AVX-512 and AVX2 paths give bit-identical results (a test checks
// it), because no value depends on the vector width:
// * gemm_rows vectorises over output rows, and every output element is the sum over k in order
//   0, 1, ..., k-1 with one fused multiply-add per term, whichever lane or scalar loop
//   computes it;
// * gemm_dot reduces along the vector, so it always uses 16 logical lanes (term p goes to lane
//   p mod 16) and adds the lanes in one fixed tree, whatever the register width (one zmm, two
//   ymm or four xmm registers hold the 16 lanes);
// * tanh, exp and GELU's normal CDF are our own rational / polynomial approximations built
//   from +, *, /, fma, min, max and exact bit operations, so every lane follows the same
//   sequence of correctly rounded operations;
// * the translation units are compiled with -ffp-contract=off, so the compiler fuses nothing
//   on its own. Only the SSE path (CPUs without FMA) rounds a * b + c twice and so differs in
//   the last bits.
// Which kernel an Mlp calls depends on shapes only (dense::kLogicalLanes), never on the width.
#include <cstddef>

#include "rlrun/nn/activation.hpp"  // kLeakyReLUSlope
#include "rlrun/nn/dense_kernels.hpp"

namespace rlrun::dense {
namespace {

inline Index min_index(Index a, Index b) { return a < b ? a : b; }
inline Index max_index(Index a, Index b) { return a < b ? b : a; }

template <class V>
struct KernelSet {
  static constexpr int kLanes = V::kLanes;

  // Scalar a * b + c rounded like the vector path's fma(): once where V has fused multiply-add
  // (every path but SSE and the generic one), twice otherwise.
  static float madd(float a, float b, float c) {
    if constexpr (V::kFusedMultiplyAdd) {
      return __builtin_fmaf(a, b, c);
    } else {
      return a * b + c;
    }
  }

  // ---- elementary functions --------------------------------------------------------------

  // e^x after Cephes' expf (S. Moshier, Cephes Math Library): x = n ln2 + r with |r| <= ln2/2,
  // ln2 split in two parts so n ln2 is exact, e^r by its degree-7 minimax polynomial, then
  // scaled by 2^n in the exponent bits. x is clamped to [-87.3, 88.3], where 2^n stays normal;
  // e^-87.3 ~ 1e-38 is 0 for its one use here, ELU's exp(v) - 1.
  static V exp(V x) {
    // (The constant first: x86's min/max return their second operand when one is NaN, so a NaN
    // input stays NaN.)
    x = min(V::set1(88.3f), max(V::set1(-87.3f), x));
    const V n = floor(fma(x, V::set1(1.44269504088896341f), V::set1(0.5f)));
    V r = fma(n, V::set1(-0.693359375f), x);
    r = fma(n, V::set1(2.12194440e-4f), r);
    V p = V::set1(1.9875691500e-4f);
    p = fma(p, r, V::set1(1.3981999507e-3f));
    p = fma(p, r, V::set1(8.3334519073e-3f));
    p = fma(p, r, V::set1(4.1665795894e-2f));
    p = fma(p, r, V::set1(1.6666665459e-1f));
    p = fma(p, r, V::set1(5.0000001201e-1f));
    p = fma(p, r * r, r + V::set1(1.0f));
    return p * exp2_integer(n);
  }

  // tanh(x) = x P(x^2) / Q(x^2) with x clamped to [-9, 9] (tanh rounds to +-1 in float beyond):
  // a (4, 4) rational approximation fitted for rlrun by scripts/data/fit_tanh.py (minimax of the
  // relative error on [0, 9], 2e-8 in exact arithmetic; at most ~5 float ulp evaluated in float
  // as here). 13 vector operations, one division; the exp-based formula it replaced took ~28 and
  // was a sixth of PPO's time on 32-wide tanh networks. Q > 0 everywhere (positive
  // coefficients). NaN stays NaN (see exp).
  static V tanh(V x) {
    x = min(V::set1(9.0f), max(V::set1(-9.0f), x));
    const V z = x * x;
    V p = V::set1(1.335871147e-08f);
    p = fma(p, z, V::set1(2.061216401e-05f));
    p = fma(p, z, V::set1(3.495782148e-03f));
    p = fma(p, z, V::set1(1.338119060e-01f));
    p = fma(p, z, V::set1(1.0f));
    V q = V::set1(7.778263011e-07f);
    q = fma(q, z, V::set1(3.285947314e-04f));
    q = fma(q, z, V::set1(2.587772720e-02f));
    q = fma(q, z, V::set1(4.671450555e-01f));
    q = fma(q, z, V::set1(1.0f));
    return x * p / q;
  }

  // a * a - u exactly, for u = a * a rounded (a >= 0, a * a far from overflow): one fused
  // multiply-add where V has it; else Dekker's product with Veltkamp's split (T. J. Dekker, "A
  // floating-point technique for extending the available precision", Numer. Math. 18, 1971),
  // every step exact, so the baseline path gets the same value.
  static V square_error(V a, V u) {
    if constexpr (V::kFusedMultiplyAdd) {
      return fma(a, a, V::zero() - u);
    } else {
      const V c = a * V::set1(4097.0f);  // 2^12 + 1: hi keeps the upper 12 of 24 bits
      const V hi = c - (c - a);
      const V lo = a - hi;
      return ((hi * hi - u) + V::set1(2.0f) * hi * lo) + lo * lo;
    }
  }

  // The standard normal distribution at x for GELU (torch.nn.GELU's default, the exact
  // x Phi(x)) and its derivative Phi(x) + x phi(x): cdf = Phi(x) and e = exp(-x^2 / 2) (phi(x)
  // = e / sqrt(2 pi)). With a = |x|, Phi(-a) = e S(a) / 2, S(a) = erfcx(a / sqrt(2)) ~= P(a) /
  // Q(a): the scaled-erfc form erfc(t) = exp(-t^2) R(t) of W. J. Cody ("Rational Chebyshev
  // approximations for the error function", Math. Comp. 23, 1969), but one (4, 5) rational on
  // [0, 13.2] fitted for rlrun by scripts/data/fit_gelu.py (relative error 5e-9 in exact
  // arithmetic, positive coefficients), so no erf / erfc split and no branch; Phi(x) = 1 -
  // Phi(-a) for x > 0. Phi(-a) keeps its relative accuracy far into the tail, where torch's
  // float 1 + erf(x / sqrt(2)) cancels; a^2 is carried as its rounded value u plus its exact
  // error du (exp(-(u + du) / 2) = exp(-u / 2) (1 - du / 2)), else e would be off by up to 4e-6
  // relative at a = 13. Evaluated so, gelu is within 9 float ulp (6e-7 relative) of x Phi(x)
  // and gelu' within 5 ulp of its larger term Phi or |x phi| (measured by the script and on
  // every kernel path, where they are >= 1e-30). Beyond |x| = 13.2, where |gelu(x)| < 6e-39 is
  // below float's normal range, Phi(-a) is taken as 0 (e too, so x phi(x) is 0 for any huge
  // x). NaN stays NaN.
  struct Normal {
    V cdf;
    V e;
  };
  static Normal normal(V x) {
    const V abs_x = max(x, V::zero() - x);
    const V a = min(V::set1(13.2f), abs_x);  // (the constant first: see exp)
    const V u = a * a;
    V e = exp(u * V::set1(-0.5f));
    e = fma(e, square_error(a, u) * V::set1(-0.5f), e);
    e = select_greater(abs_x, V::set1(13.2f), V::zero(), e);
    V p = V::set1(8.021332324e-03f);
    p = fma(p, a, V::set1(7.983950526e-02f));
    p = fma(p, a, V::set1(3.622303307e-01f));
    p = fma(p, a, V::set1(8.708534837e-01f));
    p = fma(p, a, V::set1(1.0f));
    V q = V::set1(1.005310286e-02f);
    q = fma(q, a, V::set1(1.000714600e-01f));
    q = fma(q, a, V::set1(4.638746083e-01f));
    q = fma(q, a, V::set1(1.193686843e+00f));
    q = fma(q, a, V::set1(1.668738365e+00f));
    q = fma(q, a, V::set1(1.0f));
    const V tail = e * V::set1(0.5f) * (p / q);  // Phi(-a)
    return {select_greater(x, V::zero(), V::set1(1.0f) - tail, tail), e};
  }

  static V gelu(V x) { return x * normal(x).cdf; }

  // s gelu'(z) = s (Phi(z) + z phi(z)), 1 / sqrt(2 pi) = 0.3989422804.
  static V gelu_grad(V s, V z) {
    const Normal n = normal(z);
    return s * fma(z, n.e * V::set1(0.3989422804014327f), n.cdf);
  }

  enum class Act { kNone, kTanh, kReLU, kELU, kLeakyReLU, kGELU };

  // ELU (alpha 1) is exp(v) - 1 below 0: off by at most ~1 ulp of 1.0 (6e-8 absolute) for tiny
  // v, far below what a float32 layer resolves, and much cheaper than an expm1. LeakyReLU:
  // max(v, slope v) is v above 0 and slope v below, since 0 < slope < 1.
  template <Act kAct>
  static V activate(V v) {
    if constexpr (kAct == Act::kTanh) return tanh(v);
    if constexpr (kAct == Act::kReLU) return max(V::zero(), v);  // NaN stays NaN, as in torch
    if constexpr (kAct == Act::kELU) return select_greater(v, V::zero(), v, exp(v) - V::set1(1.0f));
    if constexpr (kAct == Act::kLeakyReLU) return max(v, v * V::set1(kLeakyReLUSlope));
    if constexpr (kAct == Act::kGELU) return gelu(v);
    return v;
  }

  static float first_lane(V v) {
    float lanes[kLanes];
    v.store(lanes);
    return lanes[0];
  }

  // ---- epilogues --------------------------------------------------------------------------
  // packet(s, i, j) handles rows i..i+kLanes-1 of column j; scalar(s, i, j) one element;
  // tail(s, i, j, skip) the last, overlapping packet of a column whose height is not a multiple
  // of kLanes: rows i..i+skip-1 were finished by the packet before it. Overwriting epilogues
  // write them again (every row is summed in the same order in whichever lane computes it, so
  // the value is bit-for-bit the same); accumulating ones add only lanes skip.. .

  struct StoreEpi {
    float* c;
    Index ldc;
    void packet(V s, Index i, Index j) const { s.store(c + i + j * ldc); }
    void tail(V s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
    void scalar(float s, Index i, Index j) const { c[i + j * ldc] = s; }
  };

  struct AddEpi {
    float* c;
    Index ldc;
    void packet(V s, Index i, Index j) const {
      float* p = c + i + j * ldc;
      (V::load(p) + s).store(p);
    }
    void tail(V s, Index i, Index j, int skip) const {
      float lanes[kLanes];
      s.store(lanes);
      for (int q = skip; q < kLanes; ++q) c[i + q + j * ldc] += lanes[q];
    }
    void scalar(float s, Index i, Index j) const { c[i + j * ldc] += s; }
  };

  struct AddTransposedEpi {
    float* c;
    Index ldc;
    void packet(V s, Index i, Index j) const { tail(s, i, j, 0); }
    void tail(V s, Index i, Index j, int skip) const {
      float lanes[kLanes];
      s.store(lanes);
      for (int q = skip; q < kLanes; ++q) c[j + (i + q) * ldc] += lanes[q];
    }
    void scalar(float s, Index i, Index j) const { c[j + i * ldc] += s; }
  };

  template <Act kAct>
  struct BiasEpi {
    float* c;
    Index ldc;
    const float* bias;
    void packet(V s, Index i, Index j) const {
      activate<kAct>(s + V::load(bias + i)).store(c + i + j * ldc);
    }
    void tail(V s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
    // Through the vector routine, so every element gets the same rounding whichever path
    // (packet or scalar tail, any batch size) computed it.
    void scalar(float s, Index i, Index j) const {
      c[i + j * ldc] = first_lane(activate<kAct>(V::set1(s + bias[i])));
    }
  };

  // bias + GELU, also keeping the pre-activation v for the backward (kGELUGrad): gelu is not
  // monotonic (its minimum is at v = -0.75), so its output does not determine v.
  struct BiasGeluEpi {
    float* c;
    Index ldc;
    const float* bias;
    float* pre;
    void packet(V s, Index i, Index j) const {
      const V v = s + V::load(bias + i);
      v.store(pre + i + j * ldc);
      gelu(v).store(c + i + j * ldc);
    }
    void tail(V s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
    void scalar(float s, Index i, Index j) const {
      const float v = s + bias[i];
      pre[i + j * ldc] = v;
      c[i + j * ldc] = first_lane(gelu(V::set1(v)));
    }
  };

  // Backward through the activation, read off the stored output a: tanh' = 1 - a^2,
  // relu' = [a > 0] (torch's threshold_backward also gives 0 at exactly 0), elu' = 1 for a > 0
  // and exp(v) = a + 1 below, leaky_relu' = 1 for a > 0 and the slope below (torch's
  // leaky_relu_backward: self > 0 ? grad : grad * slope; a > 0 exactly when v > 0).
  // GELU reads the pre-activation instead (a = v, from kBiasGELU's pre): gelu_grad.
  template <Act kAct>
  static V activation_grad(V s, V a) {
    if constexpr (kAct == Act::kGELU) return gelu_grad(s, a);
    if constexpr (kAct == Act::kTanh) return s * (V::set1(1.0f) - a * a);
    if constexpr (kAct == Act::kReLU) return select_greater(a, V::zero(), s, V::zero());
    if constexpr (kAct == Act::kELU)
      return select_greater(a, V::zero(), s, s * (a + V::set1(1.0f)));
    return select_greater(a, V::zero(), s, s * V::set1(kLeakyReLUSlope));
  }

  template <Act kAct>
  struct ActGradEpi {
    float* c;
    Index ldc;
    const float* act;
    Index ld_act;
    void packet(V s, Index i, Index j) const {
      activation_grad<kAct>(s, V::load(act + i + j * ld_act)).store(c + i + j * ldc);
    }
    // c never aliases act (Mlp writes the deltas to their own buffer), so rewriting is exact.
    void tail(V s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
    void scalar(float s, Index i, Index j) const {
      c[i + j * ldc] = first_lane(activation_grad<kAct>(V::set1(s), V::set1(act[i + j * ld_act])));
    }
  };

  // ---- gemm_rows: C = A B, vectorised over rows of A and C ---------------------------------

  // One register tile: kMp packets of rows by kNr columns, summed over k in order. Packet p
  // starts at row p * kLanes of `a`, the last one at row `last` (a rest tile's last packet
  // overlaps the one before it; a full tile passes (kMp - 1) * kLanes).
  template <int kMp, int kNr>
  static void rows_accumulate(V (&acc)[kMp][kNr], Index k, const float* a, Index lda,
                              const float* b, Index b_k, Index b_j,
                              Index last = (kMp - 1) * kLanes) {
    for (int p = 0; p < kMp; ++p) {
      for (int r = 0; r < kNr; ++r) acc[p][r] = V::zero();
    }
    for (Index kk = 0; kk < k; ++kk) {
      V av[kMp];
      for (int p = 0; p + 1 < kMp; ++p) av[p] = V::load(a + kk * lda + p * kLanes);
      av[kMp - 1] = V::load(a + kk * lda + last);
      const float* bk = b + kk * b_k;
      for (int r = 0; r < kNr; ++r) {
        const V bv = V::set1(bk[r * b_j]);
        for (int p = 0; p < kMp; ++p) acc[p][r] = fma(av[p], bv, acc[p][r]);
      }
    }
  }

  template <int kMp, int kNr, class Epi>
  static void rows_tile(Index k, const float* a, Index lda, const float* b, Index b_k, Index b_j,
                        Index i0, Index j0, const Epi& epi) {
    V acc[kMp][kNr];
    rows_accumulate(acc, k, a, lda, b, b_k, b_j);
    for (int r = 0; r < kNr; ++r) {
      for (int p = 0; p < kMp; ++p) epi.packet(acc[p][r], i0 + p * kLanes, j0 + r);
    }
  }

  // The rest of a column block, rows i0..m (fewer than a full tile, m >= kLanes): kP packets,
  // the last one ending at row m and overlapping the one before (its first `skip` rows are done
  // already; the epilogues' tail rules). One pass over A and B for the whole rest: TD3's
  // 300-row products end in 44 rows, which as a 2-packet tile and then one overlapping packet
  // (a tile of 6 accumulators, bound by its loads) took 14 % of a TD3 update on AVX-512.
  template <int kP, int kNr, class Epi>
  static void rows_rest_tile(Index k, const float* a, Index lda, const float* b, Index b_k,
                             Index b_j, Index i0, Index m, Index j0, const Epi& epi) {
    const Index last = m - kLanes;  // the last packet's first row
    V acc[kP][kNr];
    rows_accumulate(acc, k, a + i0, lda, b, b_k, b_j, last - i0);
    const int skip = static_cast<int>(i0 + (kP - 1) * kLanes - last);
    for (int r = 0; r < kNr; ++r) {
      for (int p = 0; p + 1 < kP; ++p) epi.packet(acc[p][r], i0 + p * kLanes, j0 + r);
      // A rest of whole packets (e.g. a 32-row layer) overlaps nothing: the packet epilogue
      // (an accumulating tail adds lane by lane).
      if (skip == 0) {
        epi.packet(acc[kP - 1][r], last, j0 + r);
      } else {
        epi.tail(acc[kP - 1][r], last, j0 + r, skip);
      }
    }
  }

  // rows_rest_tile with kP = `packets` (at most kMaxP).
  template <int kMaxP, int kNr, class Epi>
  static void rows_rest(int packets, Index k, const float* a, Index lda, const float* b, Index b_k,
                        Index b_j, Index i0, Index m, Index j0, const Epi& epi) {
    if (packets == kMaxP) {
      rows_rest_tile<kMaxP, kNr>(k, a, lda, b, b_k, b_j, i0, m, j0, epi);
    } else if constexpr (kMaxP > 1) {
      rows_rest<kMaxP - 1, kNr>(packets, k, a, lda, b, b_k, b_j, i0, m, j0, epi);
    }
  }

  // Rows i0.. of kNr columns starting at j0 (b already points at column j0): tiles of kMp
  // packets while they fit, then one tile of as many packets as the rest needs, its last packet
  // ending at row m and overlapping the rows before (a scalar loop there cost TD3's 300-wide
  // layers ~20 % of their time; only m < kLanes still runs scalar, with the same fused
  // multiply-adds in the same order). Every element is the same chain of fused multiply-adds
  // over k in order, whichever tile computes it. Narrow column blocks use taller tiles so that
  // enough independent accumulators hide the FMA latency.
  template <int kMp, int kNr, class Epi>
  static void rows_column_block(Index i0, Index m, Index k, const float* a, Index lda,
                                const float* b, Index b_k, Index b_j, Index j0, const Epi& epi) {
    Index i = i0;
    for (; i + kMp * kLanes <= m; i += kMp * kLanes) {
      rows_tile<kMp, kNr>(k, a + i, lda, b, b_k, b_j, i, j0, epi);
    }
    if (i == m) return;
    if (m >= kLanes) {
      const int packets = static_cast<int>((m - i + kLanes - 1) / kLanes);
      rows_rest<kMp, kNr>(packets, k, a, lda, b, b_k, b_j, i, m, j0, epi);
      return;
    }
    for (; i < m; ++i) {
      for (int r = 0; r < kNr; ++r) {
        float s = 0.0f;
        for (Index kk = 0; kk < k; ++kk) s = madd(a[i + kk * lda], b[kk * b_k + r * b_j], s);
        epi.scalar(s, i, j0 + r);
      }
    }
  }

  // Tile height in packets for kNr columns: as many accumulators as the registers allow
  // (V::kAccumulators: 12 of AVX2's 16 registers, 24 of AVX-512's 32), a power of two.
  template <int kNr>
  static constexpr int rows_tile_packets() {
    constexpr int fit = V::kAccumulators / kNr;
    return fit >= 8 ? 8 : fit >= 4 ? 4 : fit >= 2 ? 2 : 1;
  }

  template <int kNr, class Epi>
  static void rows_columns(Index i0, Index m, Index k, const float* a, Index lda, const float* b,
                           Index b_k, Index b_j, Index j0, const Epi& epi) {
    rows_column_block<rows_tile_packets<kNr>(), kNr>(i0, m, k, a, lda, b + j0 * b_j, b_k, b_j, j0,
                                                     epi);
  }

  // Rows of A per block: a block's slice of A (rows x k floats) should stay in L1/L2 while
  // every column block of B streams past it. Without blocking, a 300 x 400 weight (480 KiB)
  // came from L3 again for every 6 columns.
  static constexpr int kColumns = 6;
  static Index rows_per_block(Index k) {
    constexpr Index kBlockBytes = 192 * 1024;
    constexpr Index kTileRows = rows_tile_packets<kColumns>() * kLanes;
    const Index rows = kBlockBytes / (static_cast<Index>(sizeof(float)) * max_index(k, 1));
    return max_index(kTileRows, rows / kTileRows * kTileRows);
  }

  template <class Epi>
  static void rows_run(Index m, Index n, Index k, const float* a, Index lda, const float* b,
                       Index b_k, Index b_j, const Epi& epi) {
    const Index block = rows_per_block(k);
    for (Index i0 = 0; i0 < m; i0 += block) {
      // The last block may end in a packet that overlaps the block before: those rows are done
      // for every column already, so the tail rules of the epilogues hold.
      const Index i1 = min_index(m, i0 + block);
      Index j = 0;
      for (; j + kColumns <= n; j += kColumns)
        rows_columns<kColumns>(i0, i1, k, a, lda, b, b_k, b_j, j, epi);
      switch (n - j) {
        case 5: rows_columns<5>(i0, i1, k, a, lda, b, b_k, b_j, j, epi); break;
        case 4: rows_columns<4>(i0, i1, k, a, lda, b, b_k, b_j, j, epi); break;
        case 3: rows_columns<3>(i0, i1, k, a, lda, b, b_k, b_j, j, epi); break;
        case 2: rows_columns<2>(i0, i1, k, a, lda, b, b_k, b_j, j, epi); break;
        case 1: rows_columns<1>(i0, i1, k, a, lda, b, b_k, b_j, j, epi); break;
        default: break;
      }
    }
  }

  // ---- gemm_dot: C(i, j) = X(:, i) . Y(:, j), vectorised over the reduction ------------------

  // 16 logical lanes in 16 / kLanes registers: term p of a dot product goes to lane p mod 16.
  static constexpr int kParts = kLogicalLanes / kLanes;
  struct Lanes16 {
    V part[kParts];
  };

  // Terms p..p+15 of a column (zero past `left` terms, which are not read).
  static Lanes16 load16(const float* x, Index left) {
    Lanes16 v;
    for (int q = 0; q < kParts; ++q) {
      const Index n = left - q * kLanes;
      v.part[q] = n >= kLanes ? V::load(x + q * kLanes)
                  : n > 0     ? V::load_first(x + q * kLanes, static_cast<int>(n))
                              : V::zero();
    }
    return v;
  }

  // The 16 lanes added in one fixed tree: t8[i] = l[i] + l[i+8], t4[i] = t8[i] + t8[i+4],
  // t2[i] = t4[i] + t4[i+2], t2[0] + t2[1] (each vector type does these steps in registers).
  static float reduce16(const Lanes16& v) { return V::reduce16(v.part); }

  template <int kMi, int kNj, class Epi>
  static void dot_tile(Index p, const float* x, Index ldx, const float* y, Index ldy, Index i0,
                       Index j0, const Epi& epi) {
    Lanes16 acc[kMi][kNj];
    for (int r = 0; r < kMi; ++r) {
      for (int c = 0; c < kNj; ++c) {
        for (int q = 0; q < kParts; ++q) acc[r][c].part[q] = V::zero();
      }
    }
    const float* xs = x + i0 * ldx;
    const float* ys = y + j0 * ldy;
    for (Index pp = 0; pp < p; pp += kLogicalLanes) {
      const Index left = p - pp;
      Lanes16 xv[kMi];
      for (int r = 0; r < kMi; ++r) xv[r] = load16(xs + r * ldx + pp, left);
      for (int c = 0; c < kNj; ++c) {
        const Lanes16 yv = load16(ys + c * ldy + pp, left);
        for (int r = 0; r < kMi; ++r) {
          for (int q = 0; q < kParts; ++q)
            acc[r][c].part[q] = fma(xv[r].part[q], yv.part[q], acc[r][c].part[q]);
        }
      }
    }
    for (int r = 0; r < kMi; ++r) {
      for (int c = 0; c < kNj; ++c) epi.scalar(reduce16(acc[r][c]), i0 + r, j0 + c);
    }
  }

  // Tile shapes by accumulator budget (in 16-lane accumulators): 24 on AVX-512, 6 on AVX2.
  static constexpr int kDotBudget = V::kAccumulators / kParts;
  static constexpr int kDotRows = kDotBudget >= 12 ? 4 : kDotBudget >= 6 ? 2 : 1;
  static constexpr int kDotColumns = 3;
  static constexpr int kDotColumnsOneRow = kDotBudget >= 8 ? 8 : kDotBudget;

  template <int kMi, int kNj, class Epi>
  static void dot_row_block(Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
                            Index i0, const Epi& epi) {
    Index j = 0;
    for (; j + kNj <= n; j += kNj) dot_tile<kMi, kNj>(p, x, ldx, y, ldy, i0, j, epi);
    for (; j < n; ++j) dot_tile<kMi, 1>(p, x, ldx, y, ldy, i0, j, epi);
  }

  template <class Epi>
  static void dot_run(Index m, Index n, Index p, const float* x, Index ldx, const float* y,
                      Index ldy, const Epi& epi) {
    Index i = 0;
    for (; i + kDotRows <= m; i += kDotRows)
      dot_row_block<kDotRows, kDotColumns>(n, p, x, ldx, y, ldy, i, epi);
    for (; i < m; ++i) dot_row_block<1, kDotColumnsOneRow>(n, p, x, ldx, y, ldy, i, epi);
  }

  // Turns the run-time epilogue choice into a compile-time one, once per product.
  template <class Run>
  static void with_epilogue(Epilogue epilogue, const EpilogueArgs& g, Run&& run) {
    switch (epilogue) {
      case Epilogue::kStore: return run(StoreEpi{g.c, g.ldc});
      case Epilogue::kAdd: return run(AddEpi{g.c, g.ldc});
      case Epilogue::kAddTransposed: return run(AddTransposedEpi{g.c, g.ldc});
      case Epilogue::kBias: return run(BiasEpi<Act::kNone>{g.c, g.ldc, g.bias});
      case Epilogue::kBiasTanh: return run(BiasEpi<Act::kTanh>{g.c, g.ldc, g.bias});
      case Epilogue::kBiasReLU: return run(BiasEpi<Act::kReLU>{g.c, g.ldc, g.bias});
      case Epilogue::kBiasELU: return run(BiasEpi<Act::kELU>{g.c, g.ldc, g.bias});
      case Epilogue::kBiasLeakyReLU: return run(BiasEpi<Act::kLeakyReLU>{g.c, g.ldc, g.bias});
      case Epilogue::kBiasGELU: return run(BiasGeluEpi{g.c, g.ldc, g.bias, g.pre});
      case Epilogue::kTanhGrad: return run(ActGradEpi<Act::kTanh>{g.c, g.ldc, g.act, g.ld_act});
      case Epilogue::kReLUGrad: return run(ActGradEpi<Act::kReLU>{g.c, g.ldc, g.act, g.ld_act});
      case Epilogue::kELUGrad: return run(ActGradEpi<Act::kELU>{g.c, g.ldc, g.act, g.ld_act});
      case Epilogue::kLeakyReLUGrad:
        return run(ActGradEpi<Act::kLeakyReLU>{g.c, g.ldc, g.act, g.ld_act});
      case Epilogue::kGELUGrad: return run(ActGradEpi<Act::kGELU>{g.c, g.ldc, g.act, g.ld_act});
    }
  }

  // ---- the entry points (dense_kernels.hpp documents them) ---------------------------------

  static void gemm_rows(Index m, Index n, Index k, const float* a, Index lda, const float* b,
                        Index b_k, Index b_j, Epilogue epilogue, const EpilogueArgs& args) {
    with_epilogue(epilogue, args,
                  [&](const auto& epi) { rows_run(m, n, k, a, lda, b, b_k, b_j, epi); });
  }

  static void gemm_dot(Index m, Index n, Index p, const float* x, Index ldx, const float* y,
                       Index ldy, Epilogue epilogue, const EpilogueArgs& args) {
    with_epilogue(epilogue, args, [&](const auto& epi) { dot_run(m, n, p, x, ldx, y, ldy, epi); });
  }

  static void transpose(Index rows, Index cols, const float* a, Index lda, float* b, Index ldb) {
    constexpr int kBlock = V::kTransposeBlock;
    const Index rows_full = rows / kBlock * kBlock;
    const Index cols_full = cols / kBlock * kBlock;
    for (Index j = 0; j < cols_full; j += kBlock) {
      for (Index i = 0; i < rows_full; i += kBlock)
        V::transpose_block(a + i + j * lda, lda, b + j + i * ldb, ldb);
    }
    // The rest element by element, writing B contiguously: rows of A past the last full block
    // (all of them for a 1- or 2-unit head), then columns past it.
    for (Index i = rows_full; i < rows; ++i)
      for (Index j = 0; j < cols; ++j) b[j + i * ldb] = a[i + j * lda];
    for (Index i = 0; i < rows_full; ++i)
      for (Index j = cols_full; j < cols; ++j) b[j + i * ldb] = a[i + j * lda];
  }

  // out(i) += sum over j of d(i, j), j in order, four packets of rows at a time.
  static void row_sum_add(Index m, Index n, const float* d, Index ldd, float* out) {
    constexpr int kPackets = 4;
    Index i = 0;
    for (; i + kPackets * kLanes <= m; i += kPackets * kLanes) {
      V acc[kPackets];
      for (int q = 0; q < kPackets; ++q) acc[q] = V::zero();
      for (Index j = 0; j < n; ++j) {
        for (int q = 0; q < kPackets; ++q) acc[q] = acc[q] + V::load(d + i + q * kLanes + j * ldd);
      }
      for (int q = 0; q < kPackets; ++q)
        (V::load(out + i + q * kLanes) + acc[q]).store(out + i + q * kLanes);
    }
    for (; i < m; i += kLanes) {
      const int lanes = static_cast<int>(min_index(kLanes, m - i));
      V acc = V::zero();
      for (Index j = 0; j < n; ++j) acc = acc + V::load_first(d + i + j * ldd, lanes);
      (V::load_first(out + i, lanes) + acc).store_first(out + i, lanes);
    }
  }

  // Runs step(i, lanes) over [0, n) a packet at a time: whole packets, then one packet of the
  // last n % kLanes elements (lanes < kLanes). load_n / store_n read and write such a packet.
  template <class Step>
  static void for_each_packet(Index n, Step&& step) {
    Index i = 0;
    for (; i + kLanes <= n; i += kLanes) step(i, kLanes);
    if (i < n) step(i, static_cast<int>(n - i));
  }
  static V load_n(const float* p, int lanes) {
    return lanes == kLanes ? V::load(p) : V::load_first(p, lanes);
  }
  static void store_n(V v, float* p, int lanes) {
    if (lanes == kLanes) {
      v.store(p);
    } else {
      v.store_first(p, lanes);
    }
  }

  // One Adam step over n parameters, element by element in the order of torch's
  // _single_tensor_adam (torch/optim/adam.py): m += (1 - beta1) (g - m) (its lerp_),
  // v = beta2 v + (1 - beta2) g^2, p -= step_size m / (sqrt(v) / sqrt(bias_c2) + eps). No fused
  // multiply-add, so every path (even SSE) gives the same bits.
  static void adam_update(Index n, float* value, const float* grad, float* exp_avg,
                          float* exp_avg_sq, const AdamCoefficients& c) {
    const V w1 = V::set1(c.w1), beta2 = V::set1(c.beta2), w2 = V::set1(c.w2),
            step_size = V::set1(c.step_size), inv_sqrt = V::set1(c.inv_bias_c2_sqrt),
            eps = V::set1(c.eps);
    for_each_packet(n, [&](Index i, int lanes) {
      const V g = load_n(grad + i, lanes);
      V m = load_n(exp_avg + i, lanes);
      V v = load_n(exp_avg_sq + i, lanes);
      m = m + w1 * (g - m);
      v = beta2 * v + w2 * (g * g);
      store_n(load_n(value + i, lanes) - step_size * m / (sqrt(v) * inv_sqrt + eps), value + i,
              lanes);
      store_n(m, exp_avg + i, lanes);
      store_n(v, exp_avg_sq + i, lanes);
    });
  }

  // One RMSprop step, torch's order (torch/optim/rmsprop.py, centered false, no momentum):
  // v = alpha v + (1 - alpha) g^2, p -= lr g / (sqrt(v) + eps). No fused multiply-add.
  static void rmsprop_update(Index n, float* value, const float* grad, float* square_avg,
                             float alpha, float lr, float eps) {
    const V a = V::set1(alpha), w = V::set1(1.0f - alpha), rate = V::set1(lr), e = V::set1(eps);
    for_each_packet(n, [&](Index i, int lanes) {
      const V g = load_n(grad + i, lanes);
      const V v = a * load_n(square_avg + i, lanes) + w * (g * g);
      store_n(load_n(value + i, lanes) - rate * g / (sqrt(v) + e), value + i, lanes);
      store_n(v, square_avg + i, lanes);
    });
  }

  // Sum of g^2 (a gradient norm for clip_grad_norm_): chunks of 4096 terms summed in float in
  // the 16 logical lanes (term p in lane p mod 16) and their fixed tree, the chunks added in
  // double. torch sums in float32 too.
  static double sum_of_squares(Index n, const float* g) {
    constexpr Index kChunk = 4096;
    double total = 0.0;
    for (Index begin = 0; begin < n; begin += kChunk) {
      const Index end = min_index(n, begin + kChunk);
      Lanes16 acc;
      for (int q = 0; q < kParts; ++q) acc.part[q] = V::zero();
      for (Index p = begin; p < end; p += kLogicalLanes) {
        const Lanes16 v = load16(g + p, end - p);
        for (int q = 0; q < kParts; ++q) acc.part[q] = fma(v.part[q], v.part[q], acc.part[q]);
      }
      total += static_cast<double>(reduce16(acc));
    }
    return total;
  }

  static const KernelTable& table(KernelPath path) {
    static const KernelTable kTable{path,         &gemm_rows,   &gemm_dot,       &transpose,
                                    &row_sum_add, &adam_update, &rmsprop_update, &sum_of_squares};
    return kTable;
  }
};

}  // namespace
}  // namespace rlrun::dense
