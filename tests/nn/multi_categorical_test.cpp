#include "rlrun/nn/multi_categorical.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::log_softmax;
using test::numeric_gradient;
using test::require_grad_close;

// Reference: each entry's log-softmax over its split of the logits, in double.
struct Reference {
  std::vector<int64_t> nvec;
  double log_prob(const Eigen::VectorXd& z, const Eigen::VectorXf& a) const {
    double total = 0.0;
    Eigen::Index at = 0;
    for (size_t i = 0; i < nvec.size(); ++i) {
      const Eigen::VectorXd lp = log_softmax(z.segment(at, nvec[i]));
      total += lp(static_cast<Eigen::Index>(a(static_cast<Eigen::Index>(i))));
      at += nvec[i];
    }
    return total;
  }
  double entropy(const Eigen::VectorXd& z) const {
    double total = 0.0;
    Eigen::Index at = 0;
    for (int64_t n : nvec) {
      const Eigen::VectorXd lp = log_softmax(z.segment(at, n));
      total -= (lp.array().exp() * lp.array()).sum();
      at += n;
    }
    return total;
  }
};

TEST_CASE("MultiCategorical log_prob, entropy and their gradients", "[nn]") {
  const Reference ref{{3, 1, 4, 2}};
  const int rows = 10, entries = 4, batch = 5;
  Rng rng(11);
  Eigen::MatrixXf logits(rows, batch);
  for (Eigen::Index k = 0; k < logits.size(); ++k)
    logits(k) = static_cast<float>(2.0 * rng.normal());
  logits.col(3).array() += 50.0f;  // shift invariance
  Eigen::MatrixXf actions(entries, batch);
  Eigen::RowVectorXf w_logp(batch), w_ent(batch);
  for (int j = 0; j < batch; ++j) {
    for (int i = 0; i < entries; ++i) actions(i, j) = static_cast<float>(rng.below(ref.nvec[i]));
    w_logp(j) = static_cast<float>(rng.normal());
    w_ent(j) = static_cast<float>(rng.normal());
  }

  MultiCategorical dist(ref.nvec);
  CHECK(dist.num_logits() == rows);
  CHECK(dist.num_entries() == entries);
  dist.set_logits(logits);
  Eigen::RowVectorXf logp(batch), ent(batch);
  dist.log_prob(actions, logp);
  dist.entropy(ent);
  for (int j = 0; j < batch; ++j) {
    const Eigen::VectorXd z = logits.col(j).cast<double>();
    CHECK(logp(j) == Approx(ref.log_prob(z, actions.col(j))).epsilon(1e-5).margin(1e-5));
    CHECK(ent(j) == Approx(ref.entropy(z)).epsilon(1e-5).margin(1e-5));
  }

  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> z(p.data(), rows, batch);
    double total = 0.0;
    for (int j = 0; j < batch; ++j)
      total +=
          w_logp(j) * ref.log_prob(z.col(j), actions.col(j)) + w_ent(j) * ref.entropy(z.col(j));
    return total;
  };
  Eigen::MatrixXf grad;
  dist.backward(actions, w_logp, w_ent, grad);
  REQUIRE(grad.rows() == rows);
  REQUIRE(grad.cols() == batch);
  require_grad_close(flat(grad), numeric_gradient(loss, flat(logits)));

  Eigen::MatrixXf bad = actions;
  bad(2, 1) = 4.0f;  // entry 2 has 4 values
  CHECK_THROWS_AS(dist.log_prob(bad, logp), std::out_of_range);
  CHECK_THROWS_AS(MultiCategorical({2, 0}), std::invalid_argument);
  CHECK_THROWS_AS(dist.set_logits(Eigen::MatrixXf::Zero(rows - 1, batch)), std::invalid_argument);
}

TEST_CASE("MultiCategorical of one entry is that Categorical, mode is the argmax per entry",
          "[nn]") {
  Eigen::MatrixXf logits(5, 3);
  logits << 0.3f, -1.0f, 2.0f,  //
      1.5f, 0.0f, -2.0f,        //
      -0.5f, 4.0f, 0.0f,        //
      0.0f, 1.0f, 1.0f,         //
      2.0f, 1.0f, -3.0f;
  MultiCategorical one({5});
  Categorical cat;
  one.set_logits(logits);
  cat.set_logits(logits);
  Eigen::MatrixXf a(1, 3);
  a << 4.0f, 2.0f, 0.0f;
  Eigen::RowVectorXf lp_multi(3), lp_cat(3), h_multi(3), h_cat(3);
  one.log_prob(a, lp_multi);
  cat.log_prob(a.row(0), lp_cat);
  one.entropy(h_multi);
  cat.entropy(h_cat);
  CHECK(lp_multi == lp_cat);
  CHECK(h_multi == h_cat);

  // Two entries, [2, 3]: rows 0-1 and rows 2-4; ties take the first index.
  MultiCategorical two({2, 3});
  two.set_logits(logits);
  Eigen::MatrixXf mode(2, 3);
  two.mode(mode);
  Eigen::MatrixXf expected(2, 3);
  expected << 1.0f, 1.0f, 0.0f,  //
      2.0f, 0.0f, 1.0f;
  CHECK(mode == expected);
}

TEST_CASE("MultiCategorical samples follow each entry's softmax", "[nn]") {
  Eigen::MatrixXf logits(5, 1);
  logits << 0.0f, 1.0f, -1.0f, 0.5f, 2.0f;
  MultiCategorical dist({2, 3});
  dist.set_logits(logits);
  Rng rng(5);
  const int draws = 30000;
  Eigen::MatrixXd counts = Eigen::MatrixXd::Zero(5, 1);
  Eigen::MatrixXf a(2, 1);
  for (int t = 0; t < draws; ++t) {
    dist.sample(rng, a);
    counts(static_cast<int>(a(0, 0)), 0) += 1;
    counts(2 + static_cast<int>(a(1, 0)), 0) += 1;
  }
  for (int entry = 0, row = 0; entry < 2; ++entry) {
    const Eigen::VectorXf& p = dist.part(entry).probs().col(0);
    for (Eigen::Index i = 0; i < p.size(); ++i, ++row) {
      const double sigma = std::sqrt(draws * p(i) * (1.0 - p(i)));
      INFO("entry " << entry << " value " << i << " p " << p(i) << " count " << counts(row, 0));
      CHECK(std::abs(counts(row, 0) - draws * p(i)) <= 4.0 * sigma + 1.0);
    }
  }
}

}  // namespace
}  // namespace rlrun
