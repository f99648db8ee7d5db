// gSDE's distribution (nn/state_dependent_noise) against SB3's formulas
// (common/distributions.py StateDependentNoiseDistribution), computed here independently: by
// hand on tiny matrices, and by plain double loops for the gradient checks.
#include "rlrun/nn/state_dependent_noise.hpp"

#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "grad_check.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {
namespace {

using test::flat;
using test::numeric_gradient;
using test::require_grad_close;

constexpr double kHalfLog2Pi = 0.91893853320467274;  // log(sqrt(2 pi))
constexpr double kEps = 1e-6;                        // SB3's epsilon

StateDependentNoiseOptions options(bool full_std, bool use_expln, bool squash, bool learn) {
  StateDependentNoiseOptions o;
  o.full_std = full_std;
  o.use_expln = use_expln;
  o.squash_output = squash;
  o.learn_features = learn;
  return o;
}

Eigen::MatrixXf random_matrix(Rng& rng, int rows, int cols, double scale = 1.0) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m(k) = static_cast<float>(scale * rng.normal());
  return m;
}

// ---- the reference: SB3's graph in double, written with plain loops -------------------------

double get_std(double log_std, bool use_expln) {
  if (!use_expln) return std::exp(log_std);
  return log_std <= 0 ? std::exp(log_std) : std::log1p(log_std + kEps) + 1.0;
}

// std (latent x action) from log_std (latent x cols), broadcast when cols == 1 < action.
Eigen::MatrixXd std_of(const Eigen::MatrixXd& log_std, int action_dim, bool use_expln) {
  Eigen::MatrixXd s(log_std.rows(), action_dim);
  for (int k = 0; k < log_std.rows(); ++k)
    for (int i = 0; i < action_dim; ++i)
      s(k, i) = get_std(log_std(k, log_std.cols() == 1 ? 0 : i), use_expln);
  return s;
}

// sigma(i, j) = sqrt(sum_k latent(k, j)^2 std(k, i)^2 + 1e-6).
Eigen::MatrixXd sigma_of(const Eigen::MatrixXd& std, const Eigen::MatrixXd& latent) {
  Eigen::MatrixXd sigma(std.cols(), latent.cols());
  for (int j = 0; j < latent.cols(); ++j)
    for (int i = 0; i < std.cols(); ++i) {
      double v = 0;
      for (int k = 0; k < std.rows(); ++k) v += latent(k, j) * latent(k, j) * std(k, i) * std(k, i);
      sigma(i, j) = std::sqrt(v + kEps);
    }
  return sigma;
}

double normal_log_prob(double x, double mean, double sigma) {
  return -(x - mean) * (x - mean) / (2 * sigma * sigma) - std::log(sigma) - kHalfLog2Pi;
}

// The noise of get_noise: E_j = std * eps_j for column j when batched, else E = std * eps_mat.
Eigen::MatrixXd noise_of(const Eigen::MatrixXd& std, const Eigen::MatrixXd& latent,
                         const Eigen::MatrixXd& eps_mat, const Eigen::MatrixXd& eps_matrices) {
  const int a_dim = static_cast<int>(std.cols());
  const int n_mats = static_cast<int>(eps_matrices.cols()) / a_dim;
  const bool batched = latent.cols() != 1 && latent.cols() == n_mats;
  Eigen::MatrixXd noise = Eigen::MatrixXd::Zero(a_dim, latent.cols());
  for (int j = 0; j < latent.cols(); ++j)
    for (int i = 0; i < a_dim; ++i)
      for (int k = 0; k < std.rows(); ++k) {
        const double eps = batched ? eps_matrices(k, j * a_dim + i) : eps_mat(k, i);
        noise(i, j) += latent(k, j) * std(k, i) * eps;
      }
  return noise;
}

// ---- hand-computed values ---------------------------------------------------------------

TEST_CASE("gSDE noise: th.mm with one matrix, th.bmm with one matrix per env", "[nn][gsde]") {
  // latent_dim 2, action_dim 2, log_std = 0 except log(2) at (1, 0): std = [[1, 1], [2, 1]].
  StateDependentNoise sde(2, 2, 0.0f, options(true, false, false, false));
  sde.log_std()(1, 0) = std::log(2.0f);
  Eigen::MatrixXf eps_mat(2, 2), eps_matrices(2, 6);
  eps_mat << 1, 2,  //
      3, 4;
  // Three per-env matrices: [[1, 0], [0, 1]], [[0, 1], [1, 0]], [[2, 0], [0, -1]].
  eps_matrices << 1, 0, 0, 1, 2, 0,  //
      0, 1, 1, 0, 0, -1;
  sde.set_weights(eps_mat, eps_matrices);
  REQUIRE(sde.num_exploration_matrices() == 3);
  // E = std * eps = [[1, 2], [6, 4]].
  CHECK(sde.exploration_mat()(0, 0) == 1.0f);
  CHECK(sde.exploration_mat()(0, 1) == 2.0f);
  CHECK(sde.exploration_mat()(1, 0) == Approx(6.0f));
  CHECK(sde.exploration_mat()(1, 1) == 4.0f);

  Eigen::MatrixXf mean = Eigen::MatrixXf::Zero(2, 3), latent(2, 3);
  latent << 1, 2, -1,  //
      -1, 0.5, 3;
  Eigen::MatrixXf noise(2, 3);
  // Three columns and three matrices: bmm. Column j: noise_i = sum_k s_k std_ki eps^(j)_ki.
  //   j = 0: s = (1, -1), E0 = [[1, 0], [0, 1]] (std [[1,1],[2,1]]): (1*1 + -1*0, 1*0 + -1*1)
  //   j = 1: s = (2, 0.5), E1 = [[0, 1], [2, 0]]: (2*0 + 0.5*2, 2*1 + 0.5*0) = (1, 2)
  //   j = 2: s = (-1, 3), E2 = [[2, 0], [0, -1]]: (-2 + 0, 0 + -3) = (-2, -3)
  sde.set(mean, latent);
  sde.noise(noise);
  Eigen::MatrixXf expected(2, 3);
  expected << 1, 1, -2,  //
      -1, 2, -3;
  CHECK((noise - expected).cwiseAbs().maxCoeff() < 1e-6f);

  // Two columns, three matrices: th.mm with E = [[1, 2], [6, 4]]: noise = E^T s.
  sde.set(mean.leftCols(2), latent.leftCols(2));
  Eigen::MatrixXf noise2(2, 2), expected2(2, 2);
  sde.noise(noise2);
  expected2 << 1 * 1 + -1 * 6, 2 * 1 + 0.5 * 6,  //
      1 * 2 + -1 * 4, 2 * 2 + 0.5 * 4;
  CHECK((noise2 - expected2).cwiseAbs().maxCoeff() < 1e-6f);

  // One column: th.mm even though there are per-env matrices.
  sde.set(mean.leftCols(1), latent.leftCols(1));
  Eigen::MatrixXf noise1(2, 1);
  sde.noise(noise1);
  CHECK(noise1(0, 0) == Approx(-5.0f));
  CHECK(noise1(1, 0) == Approx(-2.0f));

  // A sample is mean + noise (no squashing for PPO/A2C); the mode is the mean.
  Eigen::MatrixXf m(2, 1), a(2, 1);
  m << 0.5, -0.25;
  sde.set(m, latent.leftCols(1));
  sde.sample(a);
  CHECK(a(0, 0) == Approx(-4.5f));
  CHECK(a(1, 0) == Approx(-2.25f));
  sde.mode(a);
  CHECK(a == m);
}

TEST_CASE("gSDE log-prob and entropy by hand, full_std on and off", "[nn][gsde]") {
  // latent_dim 1, action_dim 1, std 1, latent 2: variance 4 + 1e-6, sigma ~ 2. An action two
  // above the mean has log N = -1/2 - log 2 - log sqrt(2 pi) = -2.1120857; the entropy is
  // 1/2 + log sqrt(2 pi) + log 2 = 2.1120857.
  StateDependentNoise sde(1, 1, 0.0f, options(true, false, false, false));
  Eigen::MatrixXf mean(1, 1), latent(1, 1), action(1, 1);
  mean << 0.3f;
  latent << 2.0f;
  action << 2.3f;
  sde.set(mean, latent);
  Eigen::RowVectorXf lp(1), ent(1);
  sde.log_prob(action, lp);
  sde.entropy(ent);
  const double sigma = std::sqrt(4.0 + kEps);
  CHECK(lp(0) == Approx(-4.0 / (2 * sigma * sigma) - std::log(sigma) - kHalfLog2Pi).epsilon(1e-6));
  CHECK(lp(0) == Approx(-2.1120857).epsilon(1e-5));
  CHECK(ent(0) == Approx(2.1120857).epsilon(1e-5));

  // latent_dim 2, action_dim 2, a batch of 3 against the plain-loop reference, with a full
  // log_std matrix and with one log_std per latent feature (shape latent_dim x 1).
  Rng rng(5);
  for (const bool full : {true, false}) {
    INFO("full_std " << full);
    StateDependentNoise d(2, 2, -0.5f, options(full, false, false, false));
    REQUIRE(d.log_std().cols() == (full ? 2 : 1));
    d.log_std() = random_matrix(rng, 2, full ? 2 : 1, 0.5);
    const Eigen::MatrixXf m = random_matrix(rng, 2, 3), s = random_matrix(rng, 2, 3);
    const Eigen::MatrixXf acts = random_matrix(rng, 2, 3);
    d.set(m, s);
    Eigen::RowVectorXf logp(3), entropy(3);
    d.log_prob(acts, logp);
    d.entropy(entropy);
    const Eigen::MatrixXd sig =
        sigma_of(std_of(d.log_std().cast<double>(), 2, false), s.cast<double>());
    for (int j = 0; j < 3; ++j) {
      double ref_lp = 0, ref_ent = 0;
      for (int i = 0; i < 2; ++i) {
        ref_lp += normal_log_prob(acts(i, j), m(i, j), sig(i, j));
        ref_ent += 0.5 + kHalfLog2Pi + std::log(sig(i, j));
      }
      CHECK(logp(j) == Approx(ref_lp).epsilon(1e-5));
      CHECK(entropy(j) == Approx(ref_ent).epsilon(1e-5));
    }
    // Without full_std every action's std column is the same.
    Eigen::MatrixXf std;
    d.std_matrix(std);
    if (!full) CHECK(std.col(0) == std.col(1));
  }
}

TEST_CASE("gSDE use_expln's std: exp below zero, log1p(x + eps) + 1 above", "[nn][gsde]") {
  StateDependentNoise sde(4, 1, 0.0f, options(true, true, false, false));
  sde.log_std() << -1.0f, 0.0f, 0.5f, 2.0f;
  Eigen::MatrixXf std;
  sde.std_matrix(std);
  CHECK(std(0, 0) == Approx(0.36787944));
  CHECK(std(1, 0) == Approx(1.0));
  CHECK(std(2, 0) == Approx(1.4054658));  // log(1.5) + 1
  CHECK(std(3, 0) == Approx(2.0986123));  // log(3) + 1
  CHECK(sde.mean_std() == Approx((0.36787944 + 1.0 + 1.4054658 + 2.0986123) / 4));
  StateDependentNoise plain(1, 1, 2.0f, options(true, false, false, false));
  plain.std_matrix(std);
  CHECK(std(0, 0) == Approx(std::exp(2.0)));
}

TEST_CASE("gSDE squashed sample and log-prob: tanh, atanh of the action, log-det", "[nn][gsde]") {
  // SAC's case: action = tanh(mean + noise); log_prob inverts the action (after clipping to
  // 1 - float eps), scores it under N(mean, sigma) and subtracts log(1 - tanh(g)^2 + 1e-6).
  StateDependentNoise sde(1, 1, std::log(0.5f), options(true, false, true, true));
  Eigen::MatrixXf eps(1, 1), eps_b(1, 1);
  eps << 1.5f;
  eps_b << 0.0f;
  sde.set_weights(eps, eps_b);  // E = 0.5 * 1.5 = 0.75
  Eigen::MatrixXf mean(1, 1), latent(1, 1), a(1, 1);
  mean << 0.2f;
  latent << -0.8f;
  sde.set(mean, latent);
  sde.sample(a);
  const double u = 0.2 + (-0.8) * 0.75;  // -0.4
  CHECK(a(0, 0) == Approx(std::tanh(u)).epsilon(1e-6));
  Eigen::RowVectorXf lp(1);
  sde.log_prob(a, lp);
  const double sigma = std::sqrt(0.64 * 0.25 + kEps);
  const double t = std::tanh(u);
  CHECK(lp(0) == Approx(normal_log_prob(u, 0.2, sigma) - std::log(1 - t * t + kEps)).epsilon(1e-5));
  sde.mode(a);
  CHECK(a(0, 0) == Approx(std::tanh(0.2)));
  Eigen::RowVectorXf ent(1);
  CHECK_THROWS_AS(sde.entropy(ent), std::logic_error);

  // A saturated action is clipped to 1 - eps_f32 before atanh, as TanhBijector.inverse does.
  Eigen::MatrixXf one(1, 1);
  one << 1.0f;
  sde.log_prob(one, lp);
  const double g = std::atanh(1.0 - std::numeric_limits<float>::epsilon());
  const double tg = std::tanh(g);
  CHECK(std::isfinite(lp(0)));
  CHECK(lp(0) ==
        Approx(normal_log_prob(g, 0.2, sigma) - std::log(1 - tg * tg + kEps)).epsilon(5e-3));
}

TEST_CASE("gSDE sample_weights: torch's draw order, E = std * eps", "[nn][gsde]") {
  StateDependentNoise sde(3, 2, 0.0f, options(true, false, false, false));
  sde.log_std() = Eigen::MatrixXf::Constant(3, 2, std::log(3.0f));
  Rng rng(17), copy(17);
  sde.sample_weights(rng, 4);
  REQUIRE(sde.num_exploration_matrices() == 4);
  // exploration_mat first, row-major, then the 4 per-env matrices, each row-major.
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 2; ++i) CHECK(sde.eps_mat()(k, i) == static_cast<float>(copy.normal()));
  for (int b = 0; b < 4; ++b)
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 2; ++i)
        CHECK(sde.eps_matrices()(k, 2 * b + i) == static_cast<float>(copy.normal()));
  CHECK((sde.exploration_mat() - 3.0f * sde.eps_mat()).cwiseAbs().maxCoeff() < 1e-5f);
  CHECK((sde.exploration_matrices() - 3.0f * sde.eps_matrices()).cwiseAbs().maxCoeff() < 1e-5f);
  // A later log_std change leaves the drawn matrices alone (they are resampled explicitly).
  sde.log_std().setZero();
  Eigen::MatrixXf before = sde.exploration_mat();
  sde.set(Eigen::MatrixXf::Zero(2, 1), Eigen::MatrixXf::Ones(3, 1));
  CHECK(sde.exploration_mat() == before);
}

// ---- gradients by finite differences ------------------------------------------------------

struct Case {
  bool full_std, use_expln, learn_features;
};

// log_std values kept away from expln's kink at 0.
Eigen::MatrixXf log_std_values(Rng& rng, int rows, int cols) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) {
    const double x = rng.uniform(0.2, 0.8);
    m(k) = static_cast<float>(k % 2 == 0 ? -x : x);
  }
  return m;
}

TEST_CASE("gSDE scored gradients (PPO's evaluate_actions) match finite differences",
          "[nn][gsde][gradcheck]") {
  const Case c =
      GENERATE(Case{true, false, false}, Case{false, false, false}, Case{true, true, false},
               Case{true, false, true}, Case{false, true, true});
  INFO("full_std " << c.full_std << " use_expln " << c.use_expln << " learn_features "
                   << c.learn_features);
  Rng rng(41);
  const int latent_dim = 3, a_dim = 2, n = 4, cols = c.full_std ? a_dim : 1;
  StateDependentNoise sde(latent_dim, a_dim, 0.0f,
                          options(c.full_std, c.use_expln, false, c.learn_features));
  sde.log_std() = log_std_values(rng, latent_dim, cols);
  const Eigen::MatrixXf mean = random_matrix(rng, a_dim, n),
                        latent = random_matrix(rng, latent_dim, n);
  const Eigen::MatrixXf actions = random_matrix(rng, a_dim, n);
  const Eigen::RowVectorXf w_lp = random_matrix(rng, 1, n), w_ent = random_matrix(rng, 1, n);
  sde.set(mean, latent);
  Eigen::MatrixXf grad_mean, grad_latent;
  sde.zero_grad();
  sde.backward_scored(actions, w_lp, w_ent, grad_mean, &grad_latent);

  const Eigen::Index nm = mean.size(), nl = sde.log_std().size(), ns = latent.size();
  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> m(p.data(), a_dim, n);
    const Eigen::Map<const Eigen::MatrixXd> ls(p.data() + nm, latent_dim, cols);
    const Eigen::Map<const Eigen::MatrixXd> s(p.data() + nm + nl, latent_dim, n);
    const Eigen::MatrixXd sig = sigma_of(std_of(ls, a_dim, c.use_expln), s);
    double total = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < a_dim; ++i)
        total += w_lp(j) * normal_log_prob(actions(i, j), m(i, j), sig(i, j)) +
                 w_ent(j) * (0.5 + kHalfLog2Pi + std::log(sig(i, j)));
    return total;
  };
  Eigen::VectorXd point(nm + nl + ns);
  point << flat(mean), flat(sde.log_std()), flat(latent);
  const Eigen::VectorXd numeric = numeric_gradient(loss, point);
  require_grad_close(flat(grad_mean), numeric.head(nm));
  require_grad_close(flat(sde.log_std_grad()), numeric.segment(nm, nl));
  // The latent is detached unless learn_features (PPO/A2C: false).
  if (c.learn_features) require_grad_close(flat(grad_latent), numeric.tail(ns));
}

TEST_CASE("gSDE sampled gradients (SAC's actor loss) match finite differences",
          "[nn][gsde][gradcheck]") {
  const bool squash = GENERATE(true, false);
  const bool batched = GENERATE(false, true);
  const Case c =
      GENERATE(Case{true, false, true}, Case{false, true, true}, Case{true, true, false});
  INFO("squash " << squash << " batched " << batched << " full_std " << c.full_std << " use_expln "
                 << c.use_expln << " learn_features " << c.learn_features);
  Rng rng(43);
  const int latent_dim = 3, a_dim = 2, n = 4, cols = c.full_std ? a_dim : 1;
  StateDependentNoise sde(latent_dim, a_dim, 0.0f,
                          options(c.full_std, c.use_expln, squash, c.learn_features));
  sde.log_std() = log_std_values(rng, latent_dim, cols);
  const Eigen::MatrixXf eps_mat = random_matrix(rng, latent_dim, a_dim);
  const Eigen::MatrixXf eps_matrices = random_matrix(rng, latent_dim, a_dim * (batched ? n : 1));
  sde.set_weights(eps_mat, eps_matrices);
  const Eigen::MatrixXf mean = random_matrix(rng, a_dim, n, 0.5);
  const Eigen::MatrixXf latent = random_matrix(rng, latent_dim, n, 0.7);
  const Eigen::MatrixXf w_a = random_matrix(rng, a_dim, n);
  const Eigen::RowVectorXf w_lp = random_matrix(rng, 1, n);
  sde.set(mean, latent);
  Eigen::MatrixXf actions(a_dim, n);
  sde.sample(actions);
  Eigen::RowVectorXf logp(n);
  sde.log_prob(actions, logp);
  Eigen::MatrixXf grad_mean, grad_latent;
  sde.zero_grad();
  sde.backward_sampled(w_a, w_lp, grad_mean, &grad_latent);

  // SB3's graph: E = std(log_std) * eps, u = mean + noise, a = tanh(u) (or u), g = atanh(a)
  // (= u in double: no action is near saturation here), log N(g; mean, sigma) - log-det.
  // Without learn_features the latent is a constant in both the noise and the variance.
  const Eigen::Index nm = mean.size(), nl = sde.log_std().size(), ns = latent.size();
  const auto loss = [&](const Eigen::VectorXd& p) {
    const Eigen::Map<const Eigen::MatrixXd> m(p.data(), a_dim, n);
    const Eigen::Map<const Eigen::MatrixXd> ls(p.data() + nm, latent_dim, cols);
    const Eigen::Map<const Eigen::MatrixXd> s(p.data() + nm + nl, latent_dim, n);
    const Eigen::MatrixXd std = std_of(ls, a_dim, c.use_expln);
    const Eigen::MatrixXd sig = sigma_of(std, s);
    const Eigen::MatrixXd noise =
        noise_of(std, s, eps_mat.cast<double>(), eps_matrices.cast<double>());
    double total = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < a_dim; ++i) {
        const double u = m(i, j) + noise(i, j);
        const double a = squash ? std::tanh(u) : u;
        const double g = squash ? std::atanh(a) : a;
        double lp = normal_log_prob(g, m(i, j), sig(i, j));
        if (squash) lp -= std::log(1 - std::tanh(g) * std::tanh(g) + kEps);
        total += w_a(i, j) * a + w_lp(j) * lp;
      }
    return total;
  };
  // The float forward agrees with the reference.
  {
    const Eigen::MatrixXd std = std_of(sde.log_std().cast<double>(), a_dim, c.use_expln);
    const Eigen::MatrixXd noise =
        noise_of(std, latent.cast<double>(), eps_mat.cast<double>(), eps_matrices.cast<double>());
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < a_dim; ++i) {
        const double u = mean(i, j) + noise(i, j);
        CHECK(actions(i, j) == Approx(squash ? std::tanh(u) : u).margin(1e-5));
      }
  }
  Eigen::VectorXd point(nm + nl + ns);
  point << flat(mean), flat(sde.log_std()), flat(latent);
  const Eigen::VectorXd numeric = numeric_gradient(loss, point);
  // atanh(tanh(u)) in float32 loses a few digits: 2e-3 relative.
  require_grad_close(flat(grad_mean), numeric.head(nm), 2e-3);
  require_grad_close(flat(sde.log_std_grad()), numeric.segment(nm, nl), 2e-3);
  if (c.learn_features) require_grad_close(flat(grad_latent), numeric.tail(ns), 2e-3);
}

TEST_CASE("gSDE refuses shapes that do not fit and noise before any draw", "[nn][gsde]") {
  CHECK_THROWS_AS(StateDependentNoise(0, 1, 0.0f, {}), std::invalid_argument);
  StateDependentNoise sde(2, 1, 0.0f, {});
  Eigen::MatrixXf noise(1, 1);
  sde.set(Eigen::MatrixXf::Zero(1, 1), Eigen::MatrixXf::Zero(2, 1));
  CHECK_THROWS_AS(sde.noise(noise), std::logic_error);
  CHECK_THROWS_AS(sde.set(Eigen::MatrixXf::Zero(2, 1), Eigen::MatrixXf::Zero(2, 1)),
                  std::invalid_argument);
  CHECK_THROWS_AS(sde.set_weights(Eigen::MatrixXf::Zero(2, 2), Eigen::MatrixXf::Zero(2, 1)),
                  std::invalid_argument);
}

}  // namespace
}  // namespace rlrun
