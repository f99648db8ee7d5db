// One binary, every x86-64 CPU, the same bits (nn/dense_kernels.hpp, dense_kernel_set.hpp): the
// AVX-512 and AVX2 kernels give bit-identical outputs and gradients on the same inputs, for every
// kernel, epilogue and awkward shape; the baseline (SSE) kernels agree to rounding; tanh, exp and
// GELU are accurate; and a short training run gives byte-equal models whichever path runs it.
#include <Eigen/Core>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "grad_check.hpp"  // gelu_reference, gelu_grad_reference
#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using dense::Epilogue;
using dense::KernelPath;
using dense::KernelTable;

std::vector<float> random_values(std::size_t n, Rng& rng, double scale = 1.0) {
  std::vector<float> v(n);
  for (float& x : v) x = static_cast<float>(scale * rng.normal());
  return v;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

constexpr Epilogue kEpilogues[] = {
    Epilogue::kStore,         Epilogue::kAdd,           Epilogue::kAddTransposed,
    Epilogue::kBias,          Epilogue::kBiasTanh,      Epilogue::kBiasReLU,
    Epilogue::kBiasELU,       Epilogue::kBiasLeakyReLU, Epilogue::kBiasGELU,
    Epilogue::kTanhGrad,      Epilogue::kReLUGrad,      Epilogue::kELUGrad,
    Epilogue::kLeakyReLUGrad, Epilogue::kGELUGrad};

// Everything one kernel table computes for one shape (m x n results, depth k), concatenated.
std::vector<float> run_all(const KernelTable& t, dense::Index m, dense::Index n, dense::Index k,
                           std::uint64_t seed) {
  Rng rng(seed);
  const std::vector<float> a = random_values(m * k, rng), b = random_values(k * n, rng),
                           x = random_values(k * m, rng), bias = random_values(m, rng),
                           act = random_values(m * n, rng, 0.5), c0 = random_values(m * n, rng);
  // GELU's backward reads the pre-activation: N(0, 5^2) reaches its tails and the cut at 13.
  const std::vector<float> pre_act = random_values(m * n, rng, 5.0);
  std::vector<float> out;
  for (Epilogue e : kEpilogues) {
    // A valid stored activation (or pre-activation) for each Grad epilogue.
    const std::vector<float>& stored = e == Epilogue::kGELUGrad ? pre_act : act;
    std::vector<float> c = c0, pre(m * n, 0.0f);  // pre: kBiasGELU's pre-activations
    const dense::Index ldc = e == Epilogue::kAddTransposed ? n : m;
    const dense::EpilogueArgs args{.c = c.data(),
                                   .ldc = ldc,
                                   .bias = bias.data(),
                                   .act = stored.data(),
                                   .ld_act = m,
                                   .pre = pre.data()};
    t.gemm_rows(m, n, k, a.data(), m, b.data(), 1, k, e, args);  // A (m x k) B (k x n)
    out.insert(out.end(), c.begin(), c.end());
    if (e == Epilogue::kBiasGELU) out.insert(out.end(), pre.begin(), pre.end());
    c = c0;
    t.gemm_dot(m, n, k, x.data(), k, b.data(), k, e, args);  // X^T (m x k) B
    out.insert(out.end(), c.begin(), c.end());
    if (e == Epilogue::kBiasGELU) out.insert(out.end(), pre.begin(), pre.end());
  }
  std::vector<float> at(k * m);
  t.transpose(m, k, a.data(), m, at.data(), k);
  out.insert(out.end(), at.begin(), at.end());
  std::vector<float> sums = random_values(m, rng);
  t.row_sum_add(m, n, c0.data(), m, sums.data());
  out.insert(out.end(), sums.begin(), sums.end());
  // Three Adam steps on the m x k "weights".
  std::vector<float> p = a, mom(a.size(), 0.0f), sq(a.size(), 0.0f);
  for (int step = 1; step <= 3; ++step) {
    const std::vector<float> g = random_values(a.size(), rng);
    const dense::AdamCoefficients co{
        .w1 = 0.1f,
        .beta2 = 0.999f,
        .w2 = 0.001f,
        .step_size = static_cast<float>(1e-3 / (1.0 - std::pow(0.9, step))),
        .inv_bias_c2_sqrt = static_cast<float>(1.0 / std::sqrt(1.0 - std::pow(0.999, step))),
        .eps = 1e-8f};
    t.adam_update(static_cast<dense::Index>(p.size()), p.data(), g.data(), mom.data(), sq.data(),
                  co);
  }
  out.insert(out.end(), p.begin(), p.end());
  // Three RMSprop steps, and the gradient norm's sum of squares.
  std::vector<float> r = a, square_avg(a.size(), 0.0f);
  for (int step = 0; step < 3; ++step) {
    const std::vector<float> g = random_values(a.size(), rng);
    t.rmsprop_update(static_cast<dense::Index>(r.size()), r.data(), g.data(), square_avg.data(),
                     0.99f, 7e-4f, 1e-5f);
  }
  out.insert(out.end(), r.begin(), r.end());
  out.push_back(
      static_cast<float>(t.sum_of_squares(static_cast<dense::Index>(r.size()), r.data())));
  return out;
}

// Heights, widths and depths around every vector width (4, 8, 16) and the tile sizes, and the
// shapes of real layers (64-wide at batch 100, a 1-unit head, TD3's 300).
struct Shape {
  dense::Index m, n, k;
};
constexpr Shape kShapes[] = {{1, 1, 1},    {3, 7, 5},    {8, 9, 8},     {15, 13, 17},
                             {16, 6, 16},  {17, 11, 31}, {33, 25, 3},   {64, 100, 64},
                             {1, 100, 64}, {2, 37, 300}, {300, 7, 400}, {65, 2, 129}};

}  // namespace

TEST_CASE("AVX-512 and AVX2 kernels give the same bits, the baseline agrees to rounding",
          "[nn][kernels]") {
  const bool avx2 = dense::kernel_path_available(KernelPath::kAvx2);
  const bool avx512 = dense::kernel_path_available(KernelPath::kAvx512);
  if (!avx512) WARN("this CPU has no AVX-512: the AVX-512 kernels were built but not compared");
  if (!avx2) WARN("this CPU has no AVX2 + FMA: only the baseline kernels ran");
  for (const Shape& s : kShapes) {
    INFO("m " << s.m << " n " << s.n << " k " << s.k);
    const std::vector<float> base =
        run_all(dense::kernels(KernelPath::kBaseline), s.m, s.n, s.k, 11);
    if (!avx2) continue;
    const std::vector<float> v2 = run_all(dense::kernels(KernelPath::kAvx2), s.m, s.n, s.k, 11);
    REQUIRE(v2.size() == base.size());
    for (std::size_t i = 0; i < v2.size(); ++i) {
      INFO("element " << i);
      REQUIRE(std::abs(v2[i] - base[i]) <=
              1e-4f * (1.0f + std::abs(base[i])) * std::sqrt(float(s.k)));
    }
    if (!avx512) continue;
    const std::vector<float> v4 = run_all(dense::kernels(KernelPath::kAvx512), s.m, s.n, s.k, 11);
    CHECK(same_bits(v2, v4));
  }
}

TEST_CASE("the kernels' tanh and exp are accurate and keep NaN", "[nn][kernels]") {
  // tanh through the kBiasTanh epilogue (1x1 products: s = x * 1 + 0), ELU's exp(v) - 1
  // through kBiasELU, on every available path.
  for (KernelPath path : {KernelPath::kBaseline, KernelPath::kAvx2, KernelPath::kAvx512}) {
    if (!dense::kernel_path_available(path)) continue;
    INFO(dense::kernel_path_name(path));
    const KernelTable& t = dense::kernels(path);
    const float one = 1.0f, zero = 0.0f;
    double worst_tanh = 0.0, worst_elu = 0.0;
    for (double x = -12.0; x <= 12.0; x += 0.0009765625 * 3.1) {
      const auto xf = static_cast<float>(x);
      float y = 0.0f;
      t.gemm_rows(1, 1, 1, &xf, 1, &one, 1, 1, Epilogue::kBiasTanh,
                  {.c = &y, .ldc = 1, .bias = &zero});
      const double want = std::tanh(static_cast<double>(xf));
      worst_tanh = std::max(worst_tanh, std::abs(y - want) / std::max(std::abs(want), 1e-30));
      t.gemm_rows(1, 1, 1, &xf, 1, &one, 1, 1, Epilogue::kBiasELU,
                  {.c = &y, .ldc = 1, .bias = &zero});
      const double elu = xf > 0 ? xf : std::expm1(static_cast<double>(xf));
      worst_elu = std::max(worst_elu, std::abs(y - elu));
    }
    CHECK(worst_tanh < 5e-7);  // relative, a few float ulp
    CHECK(worst_elu < 2e-7);   // absolute (exp(v) - 1 loses relative digits near 0)
    const float nan = std::nanf("");
    float y = 0.0f;
    for (Epilogue e : {Epilogue::kBiasTanh, Epilogue::kBiasELU, Epilogue::kBiasReLU}) {
      t.gemm_rows(1, 1, 1, &nan, 1, &one, 1, 1, e, {.c = &y, .ldc = 1, .bias = &zero});
      CHECK(std::isnan(y));
    }
  }
}

TEST_CASE("the kernels' GELU and its derivative are accurate and keep NaN", "[nn][kernels]") {
  // gelu(x) = x Phi(x) through kBiasGELU and s gelu'(x) = s (Phi(x) + x phi(x)) through
  // kGELUGrad (s = 1), on 1x1 products, against double precision (std::erfc, which keeps the
  // negative tail's relative accuracy), on every available path. x runs through the tiny values
  // around 0 and past the kernels' cut at |x| = 13.2 (where gelu leaves float's normal range):
  // the relative error counts down to 1e-30 (x = -11.6), the absolute one below.
  std::vector<float> xs;
  for (double x = -14.0; x <= 14.0; x += 0.0009765625 * 3.1) xs.push_back(static_cast<float>(x));
  for (double x = 1e-30; x < 1.0; x *= 1.7) {
    xs.push_back(static_cast<float>(x));
    xs.push_back(static_cast<float>(-x));
  }
  for (KernelPath path : {KernelPath::kBaseline, KernelPath::kAvx2, KernelPath::kAvx512}) {
    if (!dense::kernel_path_available(path)) continue;
    INFO(dense::kernel_path_name(path));
    const KernelTable& t = dense::kernels(path);
    const float one = 1.0f, zero = 0.0f;
    double worst_gelu = 0.0, worst_grad = 0.0;
    for (const float xf : xs) {
      float y = 0.0f, pre = 0.0f, g = 0.0f;
      t.gemm_rows(1, 1, 1, &xf, 1, &one, 1, 1, Epilogue::kBiasGELU,
                  {.c = &y, .ldc = 1, .bias = &zero, .pre = &pre});
      REQUIRE(pre == xf);
      const double x = xf;
      const double want = test::gelu_reference(x);
      worst_gelu = std::max(worst_gelu, std::abs(y - want) / std::max(std::abs(want), 1e-30));
      t.gemm_rows(1, 1, 1, &one, 1, &one, 1, 1, Epilogue::kGELUGrad,
                  {.c = &g, .ldc = 1, .act = &xf, .ld_act = 1});
      // gelu' crosses 0 at x = -0.75: relative to the larger of its terms Phi(x), |x phi(x)|.
      const double cdf = 0.5 * std::erfc(-x / std::sqrt(2.0));
      const double want_grad = test::gelu_grad_reference(x);
      worst_grad = std::max(
          worst_grad, std::abs(g - want_grad) / std::max({cdf, std::abs(want_grad - cdf), 1e-30}));
    }
    CHECK(worst_gelu < 1e-6);  // scripts/data/fit_gelu.py: at most 9 ulp (5.4e-7)
    CHECK(worst_grad < 1e-6);  // 5 ulp
    const float nan = std::nanf(""), huge = 1e30f;
    float y = 0.0f, pre = 0.0f;
    t.gemm_rows(1, 1, 1, &nan, 1, &one, 1, 1, Epilogue::kBiasGELU,
                {.c = &y, .ldc = 1, .bias = &zero, .pre = &pre});
    CHECK(std::isnan(y));
    t.gemm_rows(1, 1, 1, &one, 1, &one, 1, 1, Epilogue::kGELUGrad,
                {.c = &y, .ldc = 1, .act = &nan, .ld_act = 1});
    CHECK(std::isnan(y));
    // Far beyond the cut: gelu(x) = x and 0, gelu' = 1 and 0 (x phi(x) is exactly 0 there).
    for (const float x : {huge, -huge}) {
      t.gemm_rows(1, 1, 1, &x, 1, &one, 1, 1, Epilogue::kBiasGELU,
                  {.c = &y, .ldc = 1, .bias = &zero, .pre = &pre});
      CHECK(y == (x > 0 ? x : 0.0f));
      t.gemm_rows(1, 1, 1, &one, 1, &one, 1, 1, Epilogue::kGELUGrad,
                  {.c = &y, .ldc = 1, .act = &x, .ld_act = 1});
      CHECK(y == (x > 0 ? 1.0f : 0.0f));
    }
  }
}

}  // namespace rlrun
