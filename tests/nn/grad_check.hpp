#pragma once
// Helpers for finite-difference gradient checks. The reference loss is evaluated in double
// (the tests re-implement each forward pass in double), so a central difference with h = 1e-6
// is accurate to ~1e-9 and the comparison with the float analytic gradient can be tight.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>

#include <catch2/catch.hpp>

#include "rlrun/nn/mlp.hpp"

namespace rlrun::test {

// torch.nn.GELU (approximate='none') in double: x (1 + erf(x / sqrt(2))) / 2, written as
// x erfc(-x / sqrt(2)) / 2, which keeps its relative accuracy for negative x.
inline double gelu_reference(double x) { return 0.5 * x * std::erfc(-x / std::sqrt(2.0)); }
// Its derivative Phi(x) + x phi(x), phi(x) = exp(-x^2 / 2) / sqrt(2 pi).
inline double gelu_grad_reference(double x) {
  return 0.5 * std::erfc(-x / std::sqrt(2.0)) + x * std::exp(-0.5 * x * x) * 0.3989422804014327;
}

// An Mlp's forward pass in double from a parameter vector in Mlp::params()'s layout (per layer
// the out x in weight column-major, then the bias), x in_dim x batch: the independent
// re-implementation that the gradient checks differentiate. last_hidden (optional) receives
// the input of the output layer (Mlp::last_hidden()).
inline Eigen::MatrixXd mlp_forward(const Mlp& net, const Eigen::VectorXd& params,
                                   const Eigen::MatrixXd& x,
                                   Eigen::MatrixXd* last_hidden = nullptr) {
  Eigen::MatrixXd a = x;
  Eigen::Index offset = 0;
  for (int l = 0; l < net.num_layers(); ++l) {
    if (last_hidden != nullptr && l + 1 == net.num_layers()) *last_hidden = a;
    const int in = net.layer_in(l), out = net.layer_out(l);
    const Eigen::Map<const Eigen::MatrixXd> w(params.data() + offset, out, in);
    offset += static_cast<Eigen::Index>(in) * out;
    const Eigen::Map<const Eigen::VectorXd> b(params.data() + offset, out);
    offset += out;
    a = (w * a).colwise() + b;
    if (l + 1 < net.num_layers()) {
      switch (net.activation()) {
        case Activation::kTanh: a = a.array().tanh().matrix(); break;
        case Activation::kReLU: a = a.cwiseMax(0.0); break;
        case Activation::kELU:  // torch.nn.ELU(alpha=1)
          a = a.unaryExpr([](double v) { return v > 0.0 ? v : std::expm1(v); });
          break;
        case Activation::kLeakyReLU:  // torch.nn.LeakyReLU(negative_slope=0.01)
          a = a.unaryExpr([](double v) { return v > 0.0 ? v : 0.01 * v; });
          break;
        case Activation::kGELU: a = a.unaryExpr(&gelu_reference); break;
      }
    }
  }
  return a;
}

inline Eigen::VectorXd params_of(const Mlp& net) { return net.params().cast<double>(); }

// Central differences of f at x (double), one coordinate at a time.
inline Eigen::VectorXd numeric_gradient(const std::function<double(const Eigen::VectorXd&)>& f,
                                        Eigen::VectorXd x, double h = 1e-6) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double saved = x(i);
    x(i) = saved + h;
    const double up = f(x);
    x(i) = saved - h;
    const double down = f(x);
    x(i) = saved;
    g(i) = (up - down) / (2.0 * h);
  }
  return g;
}

// Every element: |analytic - numeric| <= rtol * max(|numeric|, scale) where scale is
// atol_frac * max|numeric| (so near-zero entries are judged against the gradient's size).
// rtol = 1e-3 catches any wrong sign or factor while tolerating float32 rounding.
inline void require_grad_close(const Eigen::VectorXd& analytic, const Eigen::VectorXd& numeric,
                               double rtol = 1e-3, double atol_frac = 5e-2) {
  REQUIRE(analytic.size() == numeric.size());
  const double scale = std::max(numeric.cwiseAbs().maxCoeff(), 1e-12) * atol_frac;
  for (Eigen::Index i = 0; i < numeric.size(); ++i) {
    const double tol = rtol * std::max(std::abs(numeric(i)), scale);
    INFO("index " << i << ": analytic " << analytic(i) << " numeric " << numeric(i));
    CHECK(std::abs(analytic(i) - numeric(i)) <= tol);
  }
}

// Reference log-softmax of one column in double (torch's Categorical normalisation).
inline Eigen::VectorXd log_softmax(const Eigen::VectorXd& z) {
  const double max = z.maxCoeff();
  return z.array() - max - std::log((z.array() - max).exp().sum());
}

template <typename Derived>
Eigen::VectorXd flat(const Eigen::DenseBase<Derived>& m) {
  Eigen::MatrixXd d = m.derived().template cast<double>();
  return Eigen::Map<const Eigen::VectorXd>(d.data(), d.size());
}

}  // namespace rlrun::test
