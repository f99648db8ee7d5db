#include "rlrun/nn/diag_gaussian.hpp"

#include <cmath>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::numeric_gradient;
using test::require_grad_close;

constexpr double kLog2Pi = 1.8378770664093453;

double normal_log_prob(double a, double m, double log_std) {
  const double s = std::exp(log_std);
  return -(a - m) * (a - m) / (2.0 * s * s) - log_std - 0.5 * kLog2Pi;
}

TEST_CASE("DiagGaussian log_prob, entropy and their gradients", "[nn]") {
  Rng rng(17);
  const int d = 3;
  const int batch = 5;
  Eigen::MatrixXf mean(d, batch), actions(d, batch);
  Eigen::VectorXf log_std(d);
  log_std << -0.5f, 0.0f, 0.7f;
  for (Eigen::Index k = 0; k < mean.size(); ++k) {
    mean(k) = static_cast<float>(rng.normal());
    actions(k) = mean(k) + static_cast<float>(1.5 * rng.normal());
  }
  Eigen::RowVectorXf w_logp(batch), w_ent(batch);
  for (int j = 0; j < batch; ++j) {
    w_logp(j) = static_cast<float>(rng.normal());
    w_ent(j) = static_cast<float>(rng.normal());
  }

  DiagGaussian dist;
  dist.set(mean, log_std);
  Eigen::RowVectorXf logp(batch), ent(batch);
  dist.log_prob(actions, logp);
  dist.entropy(ent);
  const double expected_entropy = d * 0.5 * (1.0 + kLog2Pi) + log_std.cast<double>().sum();
  for (int j = 0; j < batch; ++j) {
    double expected = 0.0;
    for (int i = 0; i < d; ++i) expected += normal_log_prob(actions(i, j), mean(i, j), log_std(i));
    CHECK(logp(j) == Approx(expected).epsilon(1e-5).margin(1e-5));
    CHECK(ent(j) == Approx(expected_entropy).epsilon(1e-6));
  }

  // Loss over the concatenation [mean (col-major), log_std].
  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> m(p.data(), d, batch);
    const Eigen::Map<const Eigen::VectorXd> ls(p.data() + d * batch, d);
    double total = 0.0;
    for (int j = 0; j < batch; ++j) {
      double lp = 0.0;
      for (int i = 0; i < d; ++i) lp += normal_log_prob(actions(i, j), m(i, j), ls(i));
      total += w_logp(j) * lp + w_ent(j) * (d * 0.5 * (1.0 + kLog2Pi) + ls.sum());
    }
    return total;
  };
  Eigen::VectorXd point(d * batch + d);
  point << flat(mean), log_std.cast<double>();
  Eigen::MatrixXf grad_mean;
  Eigen::VectorXf grad_log_std;
  dist.backward(actions, w_logp, w_ent, grad_mean, grad_log_std);
  REQUIRE(grad_mean.rows() == d);
  REQUIRE(grad_mean.cols() == batch);
  REQUIRE(grad_log_std.size() == d);
  Eigen::VectorXd analytic(d * batch + d);
  analytic << flat(grad_mean), grad_log_std.cast<double>();
  require_grad_close(analytic, numeric_gradient(loss, point));
}

TEST_CASE("DiagGaussian sample and mode", "[nn]") {
  Eigen::MatrixXf mean(2, 1);
  mean << 1.5f, -3.0f;
  Eigen::VectorXf log_std(2);
  log_std << std::log(0.5f), std::log(2.0f);
  DiagGaussian dist;
  dist.set(mean, log_std);
  Eigen::MatrixXf mode(2, 1);
  dist.mode(mode);
  CHECK(mode == mean);

  Rng rng(99);
  const int draws = 20000;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero(), sum_sq = Eigen::Vector2d::Zero();
  Eigen::MatrixXf a(2, 1);
  for (int t = 0; t < draws; ++t) {
    dist.sample(rng, a);
    sum += a.col(0).cast<double>();
    sum_sq += a.col(0).cast<double>().array().square().matrix();
  }
  const Eigen::Vector2d m = sum / draws;
  const Eigen::Vector2d sd = (sum_sq / draws - m.array().square().matrix()).cwiseSqrt();
  CHECK(m(0) == Approx(1.5).margin(4 * 0.5 / std::sqrt(draws)));
  CHECK(m(1) == Approx(-3.0).margin(4 * 2.0 / std::sqrt(draws)));
  CHECK(sd(0) == Approx(0.5).epsilon(0.03));
  CHECK(sd(1) == Approx(2.0).epsilon(0.03));
}

}  // namespace
}  // namespace rlrun
