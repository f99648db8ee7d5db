#include "rlrun/nn/bernoulli.hpp"

#include <cmath>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::numeric_gradient;
using test::require_grad_close;

// torch's formulas in double: log p(a) = a z - softplus(z), H = softplus(z) - z sigmoid(z).
double softplus(double z) { return std::max(z, 0.0) + std::log1p(std::exp(-std::abs(z))); }
double sigmoid(double z) { return 1.0 / (1.0 + std::exp(-z)); }

TEST_CASE("Bernoulli log_prob, entropy and their gradients", "[nn]") {
  const int n = 4, batch = 6;
  Rng rng(21);
  Eigen::MatrixXf logits(n, batch), actions(n, batch);
  for (Eigen::Index k = 0; k < logits.size(); ++k) {
    logits(k) = static_cast<float>(2.5 * rng.normal());
    actions(k) = static_cast<float>(rng.below(2));
  }
  logits(0, 0) = 40.0f;  // saturated bits stay finite
  logits(1, 0) = -40.0f;
  Eigen::RowVectorXf w_logp(batch), w_ent(batch);
  for (int j = 0; j < batch; ++j) {
    w_logp(j) = static_cast<float>(rng.normal());
    w_ent(j) = static_cast<float>(rng.normal());
  }

  Bernoulli dist;
  dist.set_logits(logits);
  CHECK(dist.num_bits() == n);
  Eigen::RowVectorXf logp(batch), ent(batch);
  dist.log_prob(actions, logp);
  dist.entropy(ent);
  for (int j = 0; j < batch; ++j) {
    double lp = 0, h = 0;
    for (int i = 0; i < n; ++i) {
      const double z = logits(i, j);
      lp += actions(i, j) * z - softplus(z);
      h += softplus(z) - z * sigmoid(z);
      CHECK(dist.probs()(i, j) == Approx(sigmoid(z)).epsilon(1e-6).margin(1e-12));
    }
    CHECK(std::isfinite(logp(j)));
    CHECK(logp(j) == Approx(lp).epsilon(1e-5).margin(1e-5));
    CHECK(ent(j) == Approx(h).epsilon(1e-5).margin(1e-5));
  }

  // The gradient check uses moderate logits (finite differences of a saturated sigmoid are 0).
  logits(0, 0) = 1.2f;
  logits(1, 0) = -0.7f;
  dist.set_logits(logits);
  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> z(p.data(), n, batch);
    double total = 0.0;
    for (int j = 0; j < batch; ++j)
      for (int i = 0; i < n; ++i)
        total += w_logp(j) * (actions(i, j) * z(i, j) - softplus(z(i, j))) +
                 w_ent(j) * (softplus(z(i, j)) - z(i, j) * sigmoid(z(i, j)));
    return total;
  };
  Eigen::MatrixXf grad;
  dist.backward(actions, w_logp, w_ent, grad);
  REQUIRE(grad.rows() == n);
  REQUIRE(grad.cols() == batch);
  require_grad_close(flat(grad), numeric_gradient(loss, flat(logits)));

  Eigen::MatrixXf bad = actions;
  bad(3, 2) = 2.0f;
  CHECK_THROWS_AS(dist.log_prob(bad, logp), std::out_of_range);
  bad(3, 2) = 0.5f;
  CHECK_THROWS_AS(dist.backward(bad, w_logp, w_ent, grad), std::out_of_range);
}

TEST_CASE("Bernoulli mode is round(p), samples follow p", "[nn]") {
  Eigen::MatrixXf logits(4, 1);
  logits << 0.8f, -0.3f, 0.0f, 3.0f;  // p = 0.5 rounds to 0, as torch.round
  Bernoulli dist;
  dist.set_logits(logits);
  Eigen::MatrixXf mode(4, 1);
  dist.mode(mode);
  CHECK(mode(0, 0) == 1.0f);
  CHECK(mode(1, 0) == 0.0f);
  CHECK(mode(2, 0) == 0.0f);
  CHECK(mode(3, 0) == 1.0f);

  Rng rng(3);
  const int draws = 30000;
  Eigen::VectorXd ones = Eigen::VectorXd::Zero(4);
  Eigen::MatrixXf a(4, 1);
  for (int t = 0; t < draws; ++t) {
    dist.sample(rng, a);
    ones += a.col(0).cast<double>();
  }
  for (int i = 0; i < 4; ++i) {
    const double p = dist.probs()(i, 0);
    const double sigma = std::sqrt(draws * p * (1.0 - p));
    INFO("bit " << i << " p " << p << " ones " << ones(i));
    CHECK(std::abs(ones(i) - draws * p) <= 4.0 * sigma + 1.0);
  }
}

}  // namespace
}  // namespace rlrun
