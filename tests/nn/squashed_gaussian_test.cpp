#include "rlrun/nn/squashed_gaussian.hpp"

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

TEST_CASE("SquashedGaussian pathwise gradients through tanh and its log-det", "[nn]") {
  Rng rng(23);
  const int d = 2;
  const int batch = 7;
  Eigen::MatrixXf mean(d, batch), log_std(d, batch), noise(d, batch), w_a(d, batch);
  Eigen::RowVectorXf w_logp(batch);
  for (Eigen::Index k = 0; k < mean.size(); ++k) {
    mean(k) = static_cast<float>(rng.normal());
    log_std(k) = static_cast<float>(rng.uniform(-1.5, 0.5));
    noise(k) = static_cast<float>(rng.normal());
    w_a(k) = static_cast<float>(rng.normal());
  }
  for (int j = 0; j < batch; ++j) w_logp(j) = static_cast<float>(rng.normal());

  SquashedGaussian dist;
  dist.set(mean, log_std);
  Eigen::MatrixXf actions(d, batch);
  dist.sample_from_noise(noise, actions);
  Eigen::RowVectorXf logp(batch);
  dist.log_prob(logp);

  // Reference, written the way SB3's graph computes it: u = mean + std * eps, a = tanh(u),
  // log N(u; mean, std) from u (not from eps), minus log(1 - a^2 + 1e-6). The finite difference
  // therefore differentiates through every path autograd would.
  struct Out {
    Eigen::MatrixXd a;
    Eigen::VectorXd logp;
  };
  const auto reference = [&](const Eigen::MatrixXd& m, const Eigen::MatrixXd& ls) {
    Out out{Eigen::MatrixXd(d, batch), Eigen::VectorXd::Zero(batch)};
    for (int j = 0; j < batch; ++j) {
      for (int i = 0; i < d; ++i) {
        const double s = std::exp(ls(i, j));
        const double u = m(i, j) + s * noise(i, j);
        const double a = std::tanh(u);
        out.a(i, j) = a;
        out.logp(j) += -(u - m(i, j)) * (u - m(i, j)) / (2 * s * s) - std::log(s) - 0.5 * kLog2Pi -
                       std::log(1.0 - a * a + 1e-6);
      }
    }
    return out;
  };
  const Out ref = reference(mean.cast<double>(), log_std.cast<double>());
  CHECK((actions.cast<double>() - ref.a).cwiseAbs().maxCoeff() < 1e-6);
  // log(1 - a^2 + 1e-6) loses digits in float when |a| is near 1 (as in SB3): 1e-4 relative.
  for (int j = 0; j < batch; ++j) CHECK(logp(j) == Approx(ref.logp(j)).epsilon(1e-4).margin(1e-4));

  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> m(p.data(), d, batch);
    const Eigen::Map<const Eigen::MatrixXd> ls(p.data() + d * batch, d, batch);
    const Out o = reference(m, ls);
    return (o.a.array() * w_a.cast<double>().array()).sum() + o.logp.dot(flat(w_logp));
  };
  Eigen::VectorXd point(2 * d * batch);
  point << flat(mean), flat(log_std);

  Eigen::MatrixXf grad_mean, grad_log_std;
  dist.backward(w_a, w_logp, grad_mean, grad_log_std);
  Eigen::VectorXd analytic(2 * d * batch);
  analytic << flat(grad_mean), flat(grad_log_std);
  require_grad_close(analytic, numeric_gradient(loss, point));

  // The log-prob path alone (SAC's actor loss is alpha * logp - Q(a)).
  const Eigen::MatrixXf zero_a = Eigen::MatrixXf::Zero(d, batch);
  dist.backward(zero_a, w_logp, grad_mean, grad_log_std);
  const auto loss_logp = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> m(p.data(), d, batch);
    const Eigen::Map<const Eigen::MatrixXd> ls(p.data() + d * batch, d, batch);
    return reference(m, ls).logp.dot(flat(w_logp));
  };
  analytic << flat(grad_mean), flat(grad_log_std);
  require_grad_close(analytic, numeric_gradient(loss_logp, point));
}

TEST_CASE("SquashedGaussian sampling, mode, log_prob of given actions, clamp", "[nn]") {
  Eigen::MatrixXf mean(2, 3), log_std(2, 3);
  mean << 0.3f, -0.2f, 1.0f, 0.0f, -1.2f, 0.5f;
  log_std << -1.0f, -0.5f, 0.0f, -2.0f, -0.3f, -1.2f;
  SquashedGaussian dist;
  dist.set(mean, log_std);
  Eigen::MatrixXf mode(2, 3);
  dist.mode(mode);
  CHECK(mode.isApprox(mean.array().tanh().matrix()));

  Rng rng(5);
  Eigen::MatrixXf a(2, 3);
  dist.sample(rng, a);
  CHECK(a == dist.actions());
  CHECK(a.cwiseAbs().maxCoeff() < 1.0f);
  Rng replay(5);
  Eigen::MatrixXf noise(2, 3);
  for (Eigen::Index j = 0; j < 3; ++j) {
    for (Eigen::Index i = 0; i < 2; ++i) noise(i, j) = static_cast<float>(replay.normal());
  }
  CHECK(dist.noise() == noise);
  // log_prob of the sample vs of the same actions inverted through atanh.
  Eigen::RowVectorXf from_sample(3), from_actions(3);
  dist.log_prob(from_sample);
  dist.log_prob(a, from_actions);
  for (int j = 0; j < 3; ++j)
    CHECK(from_actions(j) == Approx(from_sample(j)).epsilon(1e-3).margin(1e-3));

  Eigen::MatrixXf raw(1, 4), clamped(1, 4), grad(1, 4);
  raw << -25.0f, -20.0f, 1.0f, 3.0f;
  SquashedGaussian::clamp_log_std(raw, clamped);
  CHECK(clamped(0) == -20.0f);
  CHECK(clamped(1) == -20.0f);
  CHECK(clamped(2) == 1.0f);
  CHECK(clamped(3) == 2.0f);
  grad.setOnes();
  SquashedGaussian::clamp_log_std_backward(raw, grad);
  CHECK(grad(0) == 0.0f);
  CHECK(grad(1) == 1.0f);
  CHECK(grad(2) == 1.0f);
  CHECK(grad(3) == 0.0f);
}

}  // namespace
}  // namespace rlrun
