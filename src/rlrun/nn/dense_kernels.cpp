#include "rlrun/nn/dense_kernels.hpp"

#include <algorithm>

#include "rlrun/nn/activation.hpp"

namespace rlrun::dense {

namespace {

namespace ei = Eigen::internal;
using Packet = ei::packet_traits<float>::type;
constexpr int kLanes = ei::packet_traits<float>::size;

// Epilogues: packet(acc, i, j) handles rows i..i+kLanes-1 of column j; scalar(acc, i, j) one
// element; tail(acc, i, j, skip) is the last, overlapping packet of a column whose height is
// not a multiple of kLanes: rows i..i+skip-1 were already finished by the packet before it.
// Overwriting epilogues simply write them again (every row is summed in the same order in
// whichever lane computes it, so the value is bit-for-bit the same); accumulating ones must
// not add twice, so they add only lanes skip.. . All are tiny structs so the tile loops inline
// them.
struct StoreEpi {
  float* c;
  Index ldc;
  void packet(Packet s, Index i, Index j) const { ei::pstoreu(c + i + j * ldc, s); }
  void tail(Packet s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
  void scalar(float s, Index i, Index j) const { c[i + j * ldc] = s; }
};

struct AddEpi {
  float* c;
  Index ldc;
  void packet(Packet s, Index i, Index j) const {
    float* p = c + i + j * ldc;
    ei::pstoreu(p, ei::padd(ei::ploadu<Packet>(p), s));
  }
  void tail(Packet s, Index i, Index j, int skip) const {
    alignas(64) float lanes[kLanes];
    ei::pstoreu(lanes, s);
    for (int q = skip; q < kLanes; ++q) c[i + q + j * ldc] += lanes[q];
  }
  void scalar(float s, Index i, Index j) const { c[i + j * ldc] += s; }
};

struct AddTransposedEpi {
  float* c;
  Index ldc;
  void packet(Packet s, Index i, Index j) const { tail(s, i, j, 0); }
  void tail(Packet s, Index i, Index j, int skip) const {
    alignas(64) float lanes[kLanes];
    ei::pstoreu(lanes, s);
    for (int q = skip; q < kLanes; ++q) c[j + (i + q) * ldc] += lanes[q];
  }
  void scalar(float s, Index i, Index j) const { c[j + i * ldc] += s; }
};

enum class Act { kNone, kTanh, kReLU, kELU, kLeakyReLU };

// The activations on a packet. ELU (alpha 1): exp(v) - 1 for v <= 0. Eigen's pexpm1 would keep
// the relative digits of tiny v, but it calls plog as well and made an ELU layer's forward ~6x
// slower than tanh's; exp(v) - 1 is off by at most ~1 ulp of 1.0 (6e-8 absolute), far below
// what a float32 layer resolves. LeakyReLU: max(v, slope v) is v for v > 0 and slope v below,
// since 0 < slope < 1.
template <Act kAct>
inline Packet activate(Packet v) {
  if constexpr (kAct == Act::kTanh) return ei::ptanh(v);
  if constexpr (kAct == Act::kReLU) return ei::pmax(v, ei::pzero(v));
  if constexpr (kAct == Act::kELU)
    return ei::pselect(ei::pcmp_lt(ei::pzero(v), v), v,
                       ei::psub(ei::pexp(v), ei::pset1<Packet>(1.0f)));
  if constexpr (kAct == Act::kLeakyReLU)
    return ei::pmax(v, ei::pmul(v, ei::pset1<Packet>(kLeakyReLUSlope)));
  return v;
}

template <Act kAct>
struct BiasEpi {
  float* c;
  Index ldc;
  const float* bias;
  void packet(Packet s, Index i, Index j) const {
    ei::pstoreu(c + i + j * ldc, activate<kAct>(ei::padd(s, ei::ploadu<Packet>(bias + i))));
  }
  void tail(Packet s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
  void scalar(float s, Index i, Index j) const {
    const float v = s + bias[i];
    if constexpr (kAct == Act::kTanh || kAct == Act::kELU) {
      // Through the packet routine, so every element of a layer gets the same rounding
      // whichever path (packet or scalar tail, any batch size) computed it.
      c[i + j * ldc] = ei::pfirst(activate<kAct>(ei::pset1<Packet>(v)));
    } else if constexpr (kAct == Act::kReLU) {
      c[i + j * ldc] = v > 0.0f ? v : 0.0f;
    } else if constexpr (kAct == Act::kLeakyReLU) {
      c[i + j * ldc] = std::max(v, v * kLeakyReLUSlope);
    } else {
      c[i + j * ldc] = v;
    }
  }
};

// Backward through the activation, read off the stored output a: tanh' = 1 - a^2,
// relu' = [a > 0] (torch's threshold_backward also gives 0 at exactly 0), elu' = 1 for a > 0
// and exp(v) = a + 1 below, leaky_relu' = 1 for a > 0 and the slope below (torch's
// leaky_relu_backward: self > 0 ? grad : grad * slope; a > 0 exactly when v > 0).
template <Act kAct>
struct ActGradEpi {
  float* c;
  Index ldc;
  const float* act;
  Index ld_act;
  void packet(Packet s, Index i, Index j) const {
    const Packet a = ei::ploadu<Packet>(act + i + j * ld_act);
    Packet g;
    if constexpr (kAct == Act::kTanh) {
      g = ei::pmul(s, ei::psub(ei::pset1<Packet>(1.0f), ei::pmul(a, a)));
    } else if constexpr (kAct == Act::kReLU) {
      g = ei::pand(s, ei::pcmp_lt(ei::pzero(a), a));
    } else if constexpr (kAct == Act::kELU) {
      g = ei::pselect(ei::pcmp_lt(ei::pzero(a), a), s,
                      ei::pmul(s, ei::padd(a, ei::pset1<Packet>(1.0f))));
    } else {
      g = ei::pselect(ei::pcmp_lt(ei::pzero(a), a), s,
                      ei::pmul(s, ei::pset1<Packet>(kLeakyReLUSlope)));
    }
    ei::pstoreu(c + i + j * ldc, g);
  }
  // c never aliases act (Mlp writes the deltas to their own buffer), so rewriting is exact.
  void tail(Packet s, Index i, Index j, int /*skip*/) const { packet(s, i, j); }
  void scalar(float s, Index i, Index j) const {
    const float a = act[i + j * ld_act];
    if constexpr (kAct == Act::kTanh) {
      c[i + j * ldc] = s * (1.0f - a * a);
    } else if constexpr (kAct == Act::kReLU) {
      c[i + j * ldc] = a > 0.0f ? s : 0.0f;
    } else if constexpr (kAct == Act::kELU) {
      c[i + j * ldc] = a > 0.0f ? s : s * (a + 1.0f);
    } else {
      c[i + j * ldc] = a > 0.0f ? s : s * kLeakyReLUSlope;
    }
  }
};

// ---- gemm_rows: C = A B, vectorised over rows of A and C -----------------------------------

// One register tile: kMp packets of rows (kMp * kLanes rows) by kNr columns, summed over k.
// a points at row i0 of A, b at column j0 of B.
template <int kMp, int kNr>
inline void rows_accumulate(Packet (&acc)[kMp][kNr], Index k, const float* a, Index lda,
                            const float* b, Index b_k, Index b_j) {
  for (int p = 0; p < kMp; ++p) {
    for (int r = 0; r < kNr; ++r) acc[p][r] = ei::pset1<Packet>(0.0f);
  }
  for (Index kk = 0; kk < k; ++kk) {
    Packet av[kMp];
    for (int p = 0; p < kMp; ++p) av[p] = ei::ploadu<Packet>(a + kk * lda + p * kLanes);
    const float* bk = b + kk * b_k;
    for (int r = 0; r < kNr; ++r) {
      const Packet bv = ei::pset1<Packet>(bk[r * b_j]);
      for (int p = 0; p < kMp; ++p) acc[p][r] = ei::pmadd(av[p], bv, acc[p][r]);
    }
  }
}

template <int kMp, int kNr, class Epi>
inline void rows_tile(Index k, const float* a, Index lda, const float* b, Index b_k, Index b_j,
                      Index i0, Index j0, const Epi& epi) {
  Packet acc[kMp][kNr];
  rows_accumulate(acc, k, a, lda, b, b_k, b_j);
  for (int r = 0; r < kNr; ++r) {
    for (int p = 0; p < kMp; ++p) epi.packet(acc[p][r], i0 + p * kLanes, j0 + r);
  }
}

// The overlapping last packet of a column block (see the epilogues' tail()): rows i0.. of
// which the first `skip` are done already.
template <int kNr, class Epi>
inline void rows_tail_tile(Index k, const float* a, Index lda, const float* b, Index b_k,
                           Index b_j, Index i0, Index j0, const Epi& epi, int skip) {
  Packet acc[1][kNr];
  rows_accumulate(acc, k, a, lda, b, b_k, b_j);
  for (int r = 0; r < kNr; ++r) epi.tail(acc[0][r], i0, j0 + r, skip);
}

// Rows i0.. of kNr columns starting at j0 (b already points at column j0): tiles of kMp packets
// while they fit, then halving tiles, then for the last m % kLanes rows one packet that ends at
// row m and overlaps the rows before (a scalar loop there cost TD3's 300-wide layers ~20 % of
// their time; only m < kLanes still runs scalar). Narrow column blocks use taller tiles so that
// enough independent accumulators hide the FMA latency (a 1-column product with a single
// 2-packet tile would wait on one dependency chain per k).
template <int kMp, int kNr, class Epi>
void rows_column_block(Index i0, Index m, Index k, const float* a, Index lda, const float* b,
                       Index b_k, Index b_j, Index j0, const Epi& epi) {
  Index i = i0;
  for (; i + kMp * kLanes <= m; i += kMp * kLanes) {
    rows_tile<kMp, kNr>(k, a + i, lda, b, b_k, b_j, i, j0, epi);
  }
  if constexpr (kMp > 1) {
    rows_column_block<kMp / 2, kNr>(i, m, k, a, lda, b, b_k, b_j, j0, epi);
  } else if (i < m && m >= kLanes) {
    const Index last = m - kLanes;
    rows_tail_tile<kNr>(k, a + last, lda, b, b_k, b_j, last, j0, epi, static_cast<int>(i - last));
  } else {
    for (; i < m; ++i) {
      for (int r = 0; r < kNr; ++r) {
        float s = 0.0f;
        for (Index kk = 0; kk < k; ++kk) s += a[i + kk * lda] * b[kk * b_k + r * b_j];
        epi.scalar(s, i, j0 + r);
      }
    }
  }
}

// Tile height for kNr columns: at most 12 accumulators (16 vector registers with AVX2).
template <int kNr>
constexpr int rows_tile_packets() {
  return kNr == 1 ? 8 : kNr <= 3 ? 4 : 2;
}

template <int kNr, class Epi>
void rows_columns(Index i0, Index m, Index k, const float* a, Index lda, const float* b,
                  Index b_k, Index b_j, Index j0, const Epi& epi) {
  rows_column_block<rows_tile_packets<kNr>(), kNr>(i0, m, k, a, lda, b + j0 * b_j, b_k, b_j, j0,
                                                   epi);
}

// Rows of A per block: a block's slice of A (rows x k floats) should stay in L1 (32 KiB) while
// every column block of B streams past it. Without blocking, a 300 x 400 weight (480 KiB, more
// than L2 holds beside everything else) came from L3 again for every 6 columns.
constexpr Index kBlockBytes = 192 * 1024;
inline Index rows_per_block(Index k) {
  constexpr Index kTileRows = 2 * kLanes;
  const Index rows = kBlockBytes / (static_cast<Index>(sizeof(float)) * std::max<Index>(k, 1));
  return std::max(kTileRows, rows / kTileRows * kTileRows);
}

template <class Epi>
void rows_run(Index m, Index n, Index k, const float* a, Index lda, const float* b, Index b_k,
              Index b_j, const Epi& epi) {
  constexpr int kNr = 6;
  const Index block = rows_per_block(k);
  for (Index i0 = 0; i0 < m; i0 += block) {
    // The last block may end in a packet that overlaps the block before: those rows are done
    // for every column already, so the tail rules of the epilogues hold.
    const Index i1 = std::min(m, i0 + block);
    Index j = 0;
    for (; j + kNr <= n; j += kNr) rows_columns<kNr>(i0, i1, k, a, lda, b, b_k, b_j, j, epi);
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

// ---- gemm_dot: C(i, j) = X(:, i) . Y(:, j), vectorised over the reduction -------------------

template <int kMi, int kNj, class Epi>
inline void dot_tile(Index p, const float* x, Index ldx, const float* y, Index ldy, Index i0,
                     Index j0, const Epi& epi) {
  Packet acc[kMi][kNj];
  for (int r = 0; r < kMi; ++r) {
    for (int c = 0; c < kNj; ++c) acc[r][c] = ei::pset1<Packet>(0.0f);
  }
  const float* xs = x + i0 * ldx;
  const float* ys = y + j0 * ldy;
  Index pp = 0;
  for (; pp + kLanes <= p; pp += kLanes) {
    Packet xv[kMi];
    for (int r = 0; r < kMi; ++r) xv[r] = ei::ploadu<Packet>(xs + r * ldx + pp);
    for (int c = 0; c < kNj; ++c) {
      const Packet yv = ei::ploadu<Packet>(ys + c * ldy + pp);
      for (int r = 0; r < kMi; ++r) acc[r][c] = ei::pmadd(xv[r], yv, acc[r][c]);
    }
  }
  if (pp < p && p >= kLanes) {
    // The last p % kLanes terms: the packet ending at p, with the lanes already summed above
    // zeroed in x.
    const Index last = p - kLanes;
    const Packet keep = ei::pcmp_le(ei::pset1<Packet>(static_cast<float>(pp - last)),
                                    ei::plset<Packet>(0.0f));
    Packet xv[kMi];
    for (int r = 0; r < kMi; ++r) xv[r] = ei::pand(keep, ei::ploadu<Packet>(xs + r * ldx + last));
    for (int c = 0; c < kNj; ++c) {
      const Packet yv = ei::ploadu<Packet>(ys + c * ldy + last);
      for (int r = 0; r < kMi; ++r) acc[r][c] = ei::pmadd(xv[r], yv, acc[r][c]);
    }
    pp = p;
  }
  for (int r = 0; r < kMi; ++r) {
    for (int c = 0; c < kNj; ++c) {
      float s = ei::predux(acc[r][c]);
      for (Index q = pp; q < p; ++q) s += xs[r * ldx + q] * ys[c * ldy + q];
      epi.scalar(s, i0 + r, j0 + c);
    }
  }
}

template <int kMi, int kNj, class Epi>
void dot_row_block(Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
                   Index i0, const Epi& epi) {
  Index j = 0;
  for (; j + kNj <= n; j += kNj) dot_tile<kMi, kNj>(p, x, ldx, y, ldy, i0, j, epi);
  for (; j < n; ++j) dot_tile<kMi, 1>(p, x, ldx, y, ldy, i0, j, epi);
}

template <class Epi>
void dot_run(Index m, Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
             const Epi& epi) {
  Index i = 0;
  for (; i + 4 <= m; i += 4) dot_row_block<4, 3>(n, p, x, ldx, y, ldy, i, epi);
  switch (m - i) {
    case 3: dot_row_block<3, 4>(n, p, x, ldx, y, ldy, i, epi); break;
    case 2: dot_row_block<2, 6>(n, p, x, ldx, y, ldy, i, epi); break;
    case 1: dot_row_block<1, 8>(n, p, x, ldx, y, ldy, i, epi); break;
    default: break;
  }
}

// Turns the run-time epilogue choice into a compile-time one, once per product.
template <class Run>
void dispatch(Epilogue epilogue, const EpilogueArgs& g, Run&& run) {
  switch (epilogue) {
    case Epilogue::kStore: return run(StoreEpi{g.c, g.ldc});
    case Epilogue::kAdd: return run(AddEpi{g.c, g.ldc});
    case Epilogue::kAddTransposed: return run(AddTransposedEpi{g.c, g.ldc});
    case Epilogue::kBias: return run(BiasEpi<Act::kNone>{g.c, g.ldc, g.bias});
    case Epilogue::kBiasTanh: return run(BiasEpi<Act::kTanh>{g.c, g.ldc, g.bias});
    case Epilogue::kBiasReLU: return run(BiasEpi<Act::kReLU>{g.c, g.ldc, g.bias});
    case Epilogue::kBiasELU: return run(BiasEpi<Act::kELU>{g.c, g.ldc, g.bias});
    case Epilogue::kBiasLeakyReLU: return run(BiasEpi<Act::kLeakyReLU>{g.c, g.ldc, g.bias});
    case Epilogue::kTanhGrad: return run(ActGradEpi<Act::kTanh>{g.c, g.ldc, g.act, g.ld_act});
    case Epilogue::kReLUGrad: return run(ActGradEpi<Act::kReLU>{g.c, g.ldc, g.act, g.ld_act});
    case Epilogue::kELUGrad: return run(ActGradEpi<Act::kELU>{g.c, g.ldc, g.act, g.ld_act});
    case Epilogue::kLeakyReLUGrad:
      return run(ActGradEpi<Act::kLeakyReLU>{g.c, g.ldc, g.act, g.ld_act});
  }
}

}  // namespace

void gemm_rows(Index m, Index n, Index k, const float* a, Index lda, const float* b, Index b_k,
               Index b_j, Epilogue epilogue, const EpilogueArgs& args) {
  dispatch(epilogue, args, [&](const auto& epi) { rows_run(m, n, k, a, lda, b, b_k, b_j, epi); });
}

void gemm_dot(Index m, Index n, Index p, const float* x, Index ldx, const float* y, Index ldy,
              Epilogue epilogue, const EpilogueArgs& args) {
  dispatch(epilogue, args, [&](const auto& epi) { dot_run(m, n, p, x, ldx, y, ldy, epi); });
}

void transpose(Index rows, Index cols, const float* a, Index lda, float* b, Index ldb) {
  const Index rows_full = rows / kLanes * kLanes;
  const Index cols_full = cols / kLanes * kLanes;
  for (Index j = 0; j < cols_full; j += kLanes) {
    for (Index i = 0; i < rows_full; i += kLanes) {
#pragma GCC diagnostic push
// PacketBlock<__m256, 8>: GCC notes that the vector type's alignment attribute does not carry
// into the template argument; the block is a plain local, so nothing depends on it.
#pragma GCC diagnostic ignored "-Wignored-attributes"
      ei::PacketBlock<Packet, kLanes> block;
#pragma GCC diagnostic pop
      // Block A(i.., j..): packet q holds column j + q; transposed, row i + q of the block.
      for (int q = 0; q < kLanes; ++q) block.packet[q] = ei::ploadu<Packet>(a + i + (j + q) * lda);
      ei::ptranspose(block);
      for (int q = 0; q < kLanes; ++q) ei::pstoreu(b + j + (i + q) * ldb, block.packet[q]);
    }
  }
  // The rest element by element, writing B contiguously: rows of A past the last full block
  // (all of them for a 1- or 2-unit head), then columns past it.
  for (Index i = rows_full; i < rows; ++i)
    for (Index j = 0; j < cols; ++j) b[j + i * ldb] = a[i + j * lda];
  for (Index i = 0; i < rows_full; ++i)
    for (Index j = cols_full; j < cols; ++j) b[j + i * ldb] = a[i + j * lda];
}

int packet_size() { return kLanes; }

}  // namespace rlrun::dense
