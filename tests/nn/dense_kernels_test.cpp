// The register-tiled kernels (src/rlrun/nn/dense_kernels.cpp) against plain Eigen products for
// every epilogue, at heights and depths that are not multiples of the SIMD packet (TD3's 300,
// 13, ...): those take the overlapping last packet, which must neither miss rows nor add rows
// twice, and must give each row the value the full packets give.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <utility>
#include <vector>

#include "grad_check.hpp"  // gelu_reference, gelu_grad_reference
#include "rlrun/nn/dense_kernels.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using dense::Epilogue;

Eigen::MatrixXf random_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = static_cast<float>(rng.normal());
  return m;
}

// What epilogue e makes of the product s (m x n), given the previous content c0 of the target,
// the bias and the stored activation (kGELUGrad: the stored pre-activation); in double.
Eigen::MatrixXd apply(Epilogue e, const Eigen::MatrixXd& s, const Eigen::MatrixXd& c0,
                      const Eigen::VectorXd& bias, const Eigen::MatrixXd& act) {
  switch (e) {
    case Epilogue::kStore: return s;
    case Epilogue::kAdd: return c0 + s;
    case Epilogue::kAddTransposed: return c0 + s.transpose();
    case Epilogue::kBias: return s.colwise() + bias;
    case Epilogue::kBiasTanh: return (s.colwise() + bias).array().tanh().matrix();
    case Epilogue::kBiasReLU: return (s.colwise() + bias).cwiseMax(0.0);
    case Epilogue::kBiasELU: {  // torch.nn.ELU(alpha=1)
      const Eigen::MatrixXd v = s.colwise() + bias;
      return v.unaryExpr([](double x) { return x > 0.0 ? x : std::expm1(x); });
    }
    case Epilogue::kBiasLeakyReLU: {  // torch.nn.LeakyReLU(negative_slope=0.01)
      const Eigen::MatrixXd v = s.colwise() + bias;
      return v.unaryExpr([](double x) { return x > 0.0 ? x : 0.01 * x; });
    }
    case Epilogue::kBiasGELU:  // torch.nn.GELU(approximate='none')
      return (s.colwise() + bias).unaryExpr(&test::gelu_reference);
    case Epilogue::kTanhGrad: return s.cwiseProduct((1.0 - act.array().square()).matrix());
    case Epilogue::kReLUGrad:
      return (act.array() > 0.0).select(s, Eigen::MatrixXd::Zero(s.rows(), s.cols()));
    case Epilogue::kELUGrad:  // d/dv expm1(v) = exp(v) = a + 1 below 0
      return (act.array() > 0.0).select(s, s.cwiseProduct((act.array() + 1.0).matrix()));
    case Epilogue::kLeakyReLUGrad: return (act.array() > 0.0).select(s, 0.01 * s);
    case Epilogue::kGELUGrad: return s.cwiseProduct(act.unaryExpr(&test::gelu_grad_reference));
  }
  return s;
}

const Epilogue kAll[] = {
    Epilogue::kStore,         Epilogue::kAdd,           Epilogue::kAddTransposed,
    Epilogue::kBias,          Epilogue::kBiasTanh,      Epilogue::kBiasReLU,
    Epilogue::kBiasELU,       Epilogue::kBiasLeakyReLU, Epilogue::kBiasGELU,
    Epilogue::kTanhGrad,      Epilogue::kReLUGrad,      Epilogue::kELUGrad,
    Epilogue::kLeakyReLUGrad, Epilogue::kGELUGrad};

// Runs one kernel product through every epilogue and compares with apply(). product(args, e)
// must compute the m x n product s_ref into args.c.
template <class Product>
void check_epilogues(Eigen::Index m, Eigen::Index n, const Eigen::MatrixXd& s_ref, Rng& rng,
                     Product&& product) {
  const Eigen::VectorXf bias = random_matrix(m, 1, rng);
  Eigen::MatrixXf act = random_matrix(m, n, rng).array().tanh().matrix();
  // Stored outputs in (-1, 1): valid for tanh, elu (> -1) and either relu. At exactly 0 the
  // derivative is the one of the negative side (torch: relu' 0, leaky_relu' 0.01, elu' 1).
  act(0, 0) = 0.0f;
  // GELU's backward reads a pre-activation: any value (here N(0, 2^2)).
  const Eigen::MatrixXf pre_act = 2.0f * random_matrix(m, n, rng);
  for (Epilogue e : kAll) {
    const bool transposed = e == Epilogue::kAddTransposed;
    Eigen::MatrixXf c = random_matrix(transposed ? n : m, transposed ? m : n, rng);
    Eigen::MatrixXf pre = Eigen::MatrixXf::Constant(m, n, -7.0f);
    const Eigen::MatrixXd c0 = c.cast<double>();
    const Eigen::MatrixXf& stored = e == Epilogue::kGELUGrad ? pre_act : act;
    dense::EpilogueArgs args{.c = c.data(),
                             .ldc = c.rows(),
                             .bias = bias.data(),
                             .act = stored.data(),
                             .ld_act = m,
                             .pre = pre.data()};
    product(e, args);
    const Eigen::MatrixXd expected =
        apply(e, s_ref, c0, bias.cast<double>(), stored.cast<double>());
    INFO("epilogue " << static_cast<int>(e));
    REQUIRE(c.rows() == expected.rows());
    const double err = (c.cast<double>() - expected).cwiseAbs().maxCoeff();
    CHECK(err < 1e-4 * (1.0 + expected.cwiseAbs().maxCoeff()));
    // kBiasGELU keeps the pre-activation s + bias for the backward; the others leave pre alone.
    const Eigen::MatrixXd expected_pre =
        e == Epilogue::kBiasGELU ? Eigen::MatrixXd(s_ref.colwise() + bias.cast<double>())
                                 : Eigen::MatrixXd::Constant(m, n, -7.0);
    CHECK((pre.cast<double>() - expected_pre).cwiseAbs().maxCoeff() <
          1e-4 * (1.0 + expected_pre.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("gemm_rows matches Eigen for heights that are not a multiple of the packet", "[nn]") {
  Rng rng(17);
  struct Shape {
    Eigen::Index m, n, k;
  };
  const std::vector<Shape> shapes = {{300, 13, 40}, {13, 7, 9}, {300, 6, 400}, {9, 1, 5},
                                     {17, 11, 3},   {8, 5, 4},  {5, 3, 6},     {31, 12, 2}};
  for (const Shape& sh : shapes) {
    INFO("m " << sh.m << " n " << sh.n << " k " << sh.k);
    const Eigen::MatrixXf a = random_matrix(sh.m, sh.k, rng);
    // B stored transposed (n x k) to exercise the strides: B(k, j) = bt(j, k).
    const Eigen::MatrixXf bt = random_matrix(sh.n, sh.k, rng);
    const Eigen::MatrixXd s = a.cast<double>() * bt.cast<double>().transpose();
    check_epilogues(sh.m, sh.n, s, rng, [&](Epilogue e, const dense::EpilogueArgs& args) {
      dense::gemm_rows(sh.m, sh.n, sh.k, a.data(), sh.m, bt.data(), sh.n, 1, e, args);
    });
  }
}

TEST_CASE("gemm_dot matches Eigen for depths that are not a multiple of the packet", "[nn]") {
  Rng rng(23);
  struct Shape {
    Eigen::Index m, n, p;
  };
  const std::vector<Shape> shapes = {{1, 13, 300}, {3, 7, 13}, {2, 9, 8}, {5, 4, 5}, {4, 6, 17}};
  for (const Shape& sh : shapes) {
    INFO("m " << sh.m << " n " << sh.n << " p " << sh.p);
    const Eigen::MatrixXf x = random_matrix(sh.p, sh.m, rng);
    const Eigen::MatrixXf y = random_matrix(sh.p, sh.n, rng);
    const Eigen::MatrixXd s = x.cast<double>().transpose() * y.cast<double>();
    check_epilogues(sh.m, sh.n, s, rng, [&](Epilogue e, const dense::EpilogueArgs& args) {
      dense::gemm_dot(sh.m, sh.n, sh.p, x.data(), sh.p, y.data(), sh.p, e, args);
    });
  }
}

TEST_CASE("gemm_rows gives a row the same bits in the overlapping last packet", "[nn]") {
  // Rows 296..299 of a 300-row product come from the overlapping packet at 292; the same rows
  // computed as part of a 304-row product (full packets only) must be bit-for-bit equal.
  Rng rng(5);
  const Eigen::Index k = 37, n = 7;
  const Eigen::MatrixXf a = random_matrix(304, k, rng);
  const Eigen::MatrixXf b = random_matrix(k, n, rng);
  Eigen::MatrixXf c300(300, n), c304(304, n);
  const Eigen::MatrixXf a300 = a.topRows(300);
  dense::gemm_rows(300, n, k, a300.data(), 300, b.data(), 1, k, Epilogue::kStore,
                   {.c = c300.data(), .ldc = 300});
  dense::gemm_rows(304, n, k, a.data(), 304, b.data(), 1, k, Epilogue::kStore,
                   {.c = c304.data(), .ldc = 304});
  CHECK(c300 == c304.topRows(300));
}

TEST_CASE("transpose matches Eigen for any shape and leading dimension", "[nn]") {
  Rng rng(3);
  for (const auto& [rows, cols] : std::vector<std::pair<Eigen::Index, Eigen::Index>>{
           {300, 400}, {13, 7}, {1, 256}, {256, 1}, {16, 24}, {9, 17}}) {
    INFO(rows << " x " << cols);
    const Eigen::MatrixXf big = random_matrix(rows + 3, cols, rng);        // lda = rows + 3
    Eigen::MatrixXf t = Eigen::MatrixXf::Constant(cols + 2, rows, -7.0f);  // ldb = cols + 2
    dense::transpose(rows, cols, big.data(), big.rows(), t.data(), t.rows());
    CHECK(t.topRows(cols) == big.topRows(rows).transpose());
    CHECK((t.bottomRows(2).array() == -7.0f).all());
  }
}

}  // namespace
}  // namespace rlrun
