#include "rlrun/nn/categorical.hpp"

#include <cmath>
#include <stdexcept>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::log_softmax;
using test::numeric_gradient;
using test::require_grad_close;

TEST_CASE("Categorical log_prob, entropy and their gradients", "[nn]") {
  Rng rng(7);
  const int n = 5;
  const int batch = 6;
  Eigen::MatrixXf logits(n, batch);
  for (Eigen::Index k = 0; k < logits.size(); ++k)
    logits(k) = static_cast<float>(2.0 * rng.normal());
  logits.col(0).array() += 100.0f;  // shift invariance and overflow safety
  Eigen::RowVectorXf actions(batch), w_logp(batch), w_ent(batch);
  for (int j = 0; j < batch; ++j) {
    actions(j) = static_cast<float>(rng.below(n));
    w_logp(j) = static_cast<float>(rng.normal());
    w_ent(j) = static_cast<float>(rng.normal());
  }
  actions(1) = static_cast<float>(n - 1);

  Categorical dist;
  dist.set_logits(logits);
  CHECK(dist.num_actions() == n);
  CHECK(dist.batch() == batch);
  Eigen::RowVectorXf logp(batch), ent(batch);
  dist.log_prob(actions, logp);
  dist.entropy(ent);
  for (int j = 0; j < batch; ++j) {
    const Eigen::VectorXd lp = log_softmax(logits.col(j).cast<double>());
    CHECK(logp(j) == Approx(lp(static_cast<int>(actions(j)))).epsilon(1e-5).margin(1e-5));
    CHECK(ent(j) == Approx(-(lp.array().exp() * lp.array()).sum()).epsilon(1e-5).margin(1e-6));
    CHECK(dist.probs().col(j).sum() == Approx(1.0f).epsilon(1e-6));
  }

  const auto loss = [&](const Eigen::VectorXd& z) {
    const Eigen::Map<const Eigen::MatrixXd> zm(z.data(), n, batch);
    double total = 0.0;
    for (int j = 0; j < batch; ++j) {
      const Eigen::VectorXd lp = log_softmax(zm.col(j));
      total += w_logp(j) * lp(static_cast<int>(actions(j)));
      total += w_ent(j) * -(lp.array().exp() * lp.array()).sum();
    }
    return total;
  };
  Eigen::MatrixXf grad;
  dist.backward(actions, w_logp, w_ent, grad);
  REQUIRE(grad.rows() == n);
  REQUIRE(grad.cols() == batch);
  require_grad_close(flat(grad), numeric_gradient(loss, flat(logits)));

  // Each term alone (a wrong sign in either would cancel in the sum less often, but be explicit).
  const Eigen::RowVectorXf zeros = Eigen::RowVectorXf::Zero(batch);
  Eigen::MatrixXf grad_lp, grad_ent;
  dist.backward(actions, w_logp, zeros, grad_lp);
  dist.backward(actions, zeros, w_ent, grad_ent);
  CHECK((grad_lp + grad_ent).isApprox(grad, 1e-5f));
  for (int j = 0; j < batch; ++j) {
    Eigen::VectorXf expected = -w_logp(j) * dist.probs().col(j);
    expected(static_cast<int>(actions(j))) += w_logp(j);
    CHECK(grad_lp.col(j).isApprox(expected, 1e-5f));
  }

  Eigen::RowVectorXf bad = actions;
  bad(2) = static_cast<float>(n);
  CHECK_THROWS_AS(dist.log_prob(bad, logp), std::out_of_range);
  bad(2) = 0.5f;
  CHECK_THROWS_AS(dist.log_prob(bad, logp), std::out_of_range);
}

TEST_CASE("Categorical mode takes the first maximum", "[nn]") {
  Eigen::MatrixXf logits(4, 3);
  logits.col(0) << 1.0f, 3.0f, 3.0f, 0.0f;
  logits.col(1) << -5.0f, -5.0f, -5.0f, -5.0f;
  logits.col(2) << 0.0f, 0.0f, 0.0f, 9.0f;
  Categorical dist;
  dist.set_logits(logits);
  Eigen::RowVectorXf mode(3);
  dist.mode(mode);
  CHECK(mode(0) == 1.0f);
  CHECK(mode(1) == 0.0f);
  CHECK(mode(2) == 3.0f);
}

TEST_CASE("Categorical samples follow softmax(logits)", "[nn]") {
  Eigen::MatrixXf logits(4, 2);
  logits.col(0) << 0.5f, -1.0f, 2.0f, 0.0f;
  logits.col(1) << 0.0f, 0.0f, -30.0f, 1.0f;  // action 2 is (nearly) impossible
  Categorical dist;
  dist.set_logits(logits);
  Rng rng(123);
  const int draws = 40000;
  Eigen::MatrixXd counts = Eigen::MatrixXd::Zero(4, 2);
  Eigen::RowVectorXf actions(2);
  for (int t = 0; t < draws; ++t) {
    dist.sample(rng, actions);
    for (int j = 0; j < 2; ++j) counts(static_cast<int>(actions(j)), j) += 1.0;
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 4; ++i) {
      const double p = dist.probs()(i, j);
      const double sigma = std::sqrt(draws * p * (1.0 - p));
      INFO("action " << i << " column " << j << " p " << p << " count " << counts(i, j));
      CHECK(std::abs(counts(i, j) - draws * p) <= 4.0 * sigma + 1.0);
    }
  }
  // Same seed, same stream.
  Rng a(9), b(9);
  Eigen::RowVectorXf sa(2), sb(2);
  for (int t = 0; t < 10; ++t) {
    dist.sample(a, sa);
    dist.sample(b, sb);
    CHECK(sa == sb);
  }
}

}  // namespace
}  // namespace rlrun
