// TRPO (src/rlrun/algos/trpo/): the forward-mode pass Mlp::jvp against finite differences, the
// policy's Fisher-vector products against the KL divergence's second-order behaviour (for every
// action distribution, gSDE included), the mean KL against torch's formulas, the conjugate
// gradient solver, sb3-contrib's defaults, and runs through the registry: the line search keeps
// the KL under target_kl, and when it fails the actor is left as it was while the critic learns.
// The learning bars are hidden ([.slow]).
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "algos/zoo_learning_bar.hpp"
#include "rlrun/algos/common/actor_critic_policy.hpp"
#include "rlrun/algos/trpo/conjugate_gradient.hpp"
#include "rlrun/algos/trpo/trpo.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "test_threads.hpp"

using namespace rlrun;

namespace {

Eigen::VectorXf random_vector(Eigen::Index n, Rng& rng) {
  Eigen::VectorXf v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = static_cast<float>(rng.normal());
  return v;
}

// A policy, a batch of observations and actions, evaluated at its parameters theta0.
struct PolicyCase {
  ActorCriticPolicy policy;
  Eigen::MatrixXf obs, actions;
  Eigen::VectorXf theta0;
  ActionDistributionParams old;
  Eigen::RowVectorXf values, log_prob, entropy;

  PolicyCase(const Space& action_space, bool use_sde, ActorCriticPolicyConfig cfg, Rng& rng)
      : policy(Space::box(-2.0f, 2.0f, {3}), action_space, cfg, rng, use_sde) {
    const int n = 12;
    obs = Eigen::MatrixXf::Random(3, n);
    if (use_sde) policy.reset_noise(rng, 1);
    Eigen::MatrixXf acts;
    policy.act(obs, rng, false, acts, values, log_prob);
    actions = acts;
    policy.get_actor_params(theta0);
    evaluate(theta0);
    old = policy.distribution();
  }
  void evaluate(const Eigen::VectorXf& theta) {
    policy.set_actor_params(theta);
    policy.evaluate_actions(obs, actions, values, log_prob, entropy);
  }
  // KL(pi_{theta0 + eps w} || pi_theta0), the mean sb3-contrib's TRPO takes.
  double kl_along(const Eigen::VectorXf& w, double eps) {
    evaluate(theta0 + static_cast<float>(eps) * w);
    const double kl = policy.mean_kl(old);
    evaluate(theta0);
    return kl;
  }
};

ActorCriticPolicyConfig small_policy(Activation act = Activation::kTanh) {
  ActorCriticPolicyConfig cfg;
  cfg.net_arch = {{8, 6}, {8}};
  cfg.activation_fn = act;
  cfg.log_std_init = -0.3;
  return cfg;
}

// u^T F v two ways: the product, and the KL's second-order term along u + v and u - v
// (KL(theta0 + e w) = e^2 w^T F w / 2 + O(e^3), so the difference is 2 e^2 u^T F v + O(e^3)),
// with a Richardson step removing the O(e) part of the error.
//
// gSDE's latent features are detached in the variance (learn_features false, as SB3's
// ActorCriticPolicy builds it), so autograd's Hessian, and sb3-contrib's product, do not see the
// hidden layers move the standard deviations; moving only action_net and log_std (`first`
// onwards) keeps the latent fixed and the two Hessians equal. The hidden layers' part through
// the mean is the DiagGaussian case's.
void check_fisher(PolicyCase& c, Eigen::Index first = 0) {
  Rng rng(11);
  const Eigen::Index n = c.theta0.size();
  Eigen::VectorXf u = random_vector(n, rng), v = random_vector(n, rng);
  u.head(first).setZero();
  v.head(first).setZero();
  Eigen::VectorXf fv, fu;
  c.evaluate(c.theta0);
  c.policy.fisher_vector_product(v, fv);
  c.policy.fisher_vector_product(u, fu);
  const double product = u.cast<double>().dot(fv.cast<double>());
  CHECK(product == Approx(v.cast<double>().dot(fu.cast<double>())).epsilon(1e-4));  // symmetric
  auto quadratic = [&](double eps) {
    return (c.kl_along(u + v, eps) - c.kl_along(u - v, eps)) / (2 * eps * eps);
  };
  const double eps = 2e-3;
  const double estimate = 2 * quadratic(eps / 2) - quadratic(eps);
  INFO("u F v " << product << ", from the KL " << estimate);
  CHECK(product == Approx(estimate).epsilon(0.02).margin(1e-4));
  // F is positive semi-definite: v F v >= 0.
  CHECK(v.dot(fv) >= -1e-6f);
}

// Where action_net's weights start in the actor vector (after the hidden layers).
Eigen::Index action_net_offset(const ActorCriticPolicy& policy) {
  const Mlp& actor = policy.actor();
  Eigen::Index offset = 0;
  for (int l = 0; l + 1 < actor.num_layers(); ++l)
    offset += Eigen::Index{actor.layer_in(l) + 1} * actor.layer_out(l);
  return offset;
}

}  // namespace

TEST_CASE("Mlp::jvp is the derivative of the output along a parameter direction", "[nn][trpo]") {
  for (Activation act : {Activation::kTanh, Activation::kELU, Activation::kGELU}) {
    INFO("activation " << activation_name(act));
    Rng rng(5);
    Mlp mlp(3, {7, 5}, 2, act);
    mlp.init_orthogonal(rng, std::sqrt(2.0f), 1.0f);
    const Eigen::MatrixXf x = Eigen::MatrixXf::Random(3, 9);
    const Eigen::VectorXf theta = mlp.params();
    const Eigen::VectorXf dir = random_vector(theta.size(), rng);
    const double eps = 1e-3;
    mlp.params() = theta + static_cast<float>(eps) * dir;
    const Eigen::MatrixXd plus = mlp.forward(x).cast<double>();
    mlp.params() = theta - static_cast<float>(eps) * dir;
    const Eigen::MatrixXd minus = mlp.forward(x).cast<double>();
    mlp.params() = theta;
    mlp.forward(x);
    Eigen::MatrixXf tangent;
    mlp.jvp(dir, tangent);
    const Eigen::MatrixXd numeric = (plus - minus) / (2 * eps);
    REQUIRE(tangent.rows() == 2);
    REQUIRE(tangent.cols() == 9);
    CHECK((tangent.cast<double>() - numeric).cwiseAbs().maxCoeff() <
          2e-3 * std::max(1.0, numeric.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("TRPO's Fisher-vector product is the KL divergence's Hessian for every distribution",
          "[algos][trpo]") {
  Rng rng(7);
  SECTION("Categorical") {
    PolicyCase c(Space::discrete(4), false, small_policy(), rng);
    check_fisher(c);
  }
  SECTION("MultiCategorical") {
    PolicyCase c(Space::multi_discrete({3, 2}), false, small_policy(Activation::kReLU), rng);
    check_fisher(c);
  }
  SECTION("Bernoulli") {
    PolicyCase c(Space::multi_binary(3), false, small_policy(), rng);
    check_fisher(c);
  }
  SECTION("DiagGaussian") {
    PolicyCase c(Space::box(-1.0f, 1.0f, {2}), false, small_policy(), rng);
    check_fisher(c);
  }
  SECTION("gSDE, full_std") {
    PolicyCase c(Space::box(-1.0f, 1.0f, {2}), true, small_policy(), rng);
    check_fisher(c, action_net_offset(c.policy));
  }
  SECTION("gSDE, one std per feature, expln") {
    ActorCriticPolicyConfig cfg = small_policy();
    cfg.full_std = false;
    cfg.use_expln = true;
    cfg.log_std_init = 0.4;  // expln's log1p branch
    PolicyCase c(Space::box(-1.0f, 1.0f, {2}), true, cfg, rng);
    check_fisher(c, action_net_offset(c.policy));
  }
}

TEST_CASE("TRPO's mean KL follows torch's formulas, per entry for Gaussians", "[algos][trpo]") {
  Rng rng(9);
  SECTION("Gaussian: only log_std moved by d gives (e^{2d} - 1) / 2 - d per entry") {
    PolicyCase c(Space::box(-1.0f, 1.0f, {2}), false, small_policy(), rng);
    Eigen::VectorXf theta = c.theta0;
    const float d = 0.3f;
    theta.tail(2).array() += d;
    c.evaluate(theta);
    CHECK(c.policy.mean_kl(c.old) == Approx((std::exp(2.0 * d) - 1) / 2 - d).epsilon(1e-5));
  }
  SECTION("Categorical: sum p log(p / q) per sample, averaged") {
    PolicyCase c(Space::discrete(3), false, small_policy(), rng);
    Eigen::VectorXf theta = c.theta0 + 0.3f * random_vector(c.theta0.size(), rng);
    c.evaluate(theta);
    const ActionDistributionParams now = c.policy.distribution();
    double expected = 0;
    for (Eigen::Index j = 0; j < now.head.cols(); ++j) {
      const Eigen::ArrayXd p = now.head.col(j).cast<double>().array().exp() /
                               now.head.col(j).cast<double>().array().exp().sum();
      const Eigen::ArrayXd q = c.old.head.col(j).cast<double>().array().exp() /
                               c.old.head.col(j).cast<double>().array().exp().sum();
      expected += (p * (p / q).log()).sum();
    }
    expected /= static_cast<double>(now.head.cols());
    CHECK(expected > 1e-4);
    CHECK(c.policy.mean_kl(c.old) == Approx(expected).epsilon(1e-5));
  }
}

TEST_CASE("conjugate gradient solves a symmetric positive definite system", "[algos][trpo]") {
  Rng rng(1);
  Eigen::MatrixXf m = Eigen::MatrixXf::Random(6, 6);
  const Eigen::MatrixXf a = m * m.transpose() + Eigen::MatrixXf::Identity(6, 6);
  const Eigen::VectorXf b = random_vector(6, rng);
  const auto product = [&](const Eigen::VectorXf& v, Eigen::VectorXf& out) { out = a * v; };
  const Eigen::VectorXf x = conjugate_gradient(product, b, 20, rng);
  CHECK((a * x - b).norm() < 1e-3f * b.norm());
  // One iteration from a near-zero start is a step along the residual, as sb3-contrib's.
  const Eigen::VectorXf x1 = conjugate_gradient(product, b, 1, rng);
  const float alpha = b.squaredNorm() / b.dot(a * b);
  CHECK((x1 - alpha * b).norm() < 1e-3f * x1.norm());
}

TEST_CASE("TRPO's defaults are sb3-contrib 2.4's", "[algos][trpo]") {
  const TRPO::Config c;
  CHECK(c.learning_rate(1.0) == Approx(1e-3));
  CHECK(c.n_steps == 2048);
  CHECK(c.batch_size == 128);
  CHECK(c.gamma == 0.99);
  CHECK(c.cg_max_steps == 15);
  CHECK(c.cg_damping == 0.1);
  CHECK(c.line_search_shrinking_factor == 0.8);
  CHECK(c.line_search_max_iter == 10);
  CHECK(c.n_critic_updates == 10);
  CHECK(c.gae_lambda == 0.95);
  CHECK(!c.use_sde);
  CHECK(c.normalize_advantage);
  CHECK(c.target_kl == 0.01);
  CHECK(c.sub_sampling_factor == 1);
}

namespace {

struct TrpoRun {
  ModelFile model;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // progress.csv
  std::string column(const std::string& name, size_t row) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i < rows.at(row).size() ? rows[row][i] : "";
    return "(missing " + name + ")";
  }
};

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
  return out;
}

TrpoRun run_trpo(const std::string& name, const std::string& algo, const std::string& env) {
  testing::TempDir dir("trpo_" + name);
  const std::string yaml = "run: {name: " + name +
                           ", seed: 2, total_timesteps: 1024, out_dir: " + dir.str() +
                           ", console_interval: 100000}\n" + env + "algo: " + algo + "\n";
  const Experiment e =
      parse_experiment(ConfigNode::load_string(yaml, name + ".yaml"), builtin_registry());
  const TrainOutcome outcome = train_experiment(e, builtin_registry(), testing::test_execution());
  TrpoRun run{read_model(outcome.model_path), {}, {}};
  std::ifstream csv(outcome.run_dir + "/progress.csv");
  std::string line;
  std::getline(csv, line);
  run.header = split_csv(line);
  while (std::getline(csv, line)) run.rows.push_back(split_csv(line));
  return run;
}

}  // namespace

TEST_CASE("TRPO steps within target_kl, and a failed line search leaves the actor as it was",
          "[algos][trpo]") {
  const std::string cartpole = "env: {id: CartPole-v1, n_envs: 2}\n";
  const std::string base =
      "{id: TRPO, n_steps: 128, batch_size: 64, n_critic_updates: 3, "
      "policy: {net_arch: [16]}";
  const TrpoRun a = run_trpo("trpo_a", base + "}", cartpole);
  const TrpoRun b = run_trpo("trpo_b", base + "}", cartpole);
  REQUIRE(a.rows.size() >= 3);
  CHECK(a.model.meta.algorithm == "TRPO");
  CHECK(a.model.tensors.at("action_net.weight").bytes ==
        b.model.tensors.at("action_net.weight").bytes);  // deterministic
  bool some_success = false;
  for (size_t r = 0; r < a.rows.size(); ++r) {
    if (a.column("train/is_line_search_success", r) != "1") continue;
    some_success = true;
    CHECK(std::stod(a.column("train/kl_divergence_loss", r)) < 0.01);
    CHECK(std::stod(a.column("train/kl_divergence_loss", r)) > 0.0);
    // The objective starts at mean(normalised advantages) = 0 and must improve.
    CHECK(std::stod(a.column("train/policy_objective", r)) > 0.0);
  }
  CHECK(some_success);

  // target_kl below any step's KL: every line search fails; the critic still learns (the
  // learning rate matters to it only), the actor never moves.
  const std::string tight = base + ", target_kl: 1e-30";
  const TrpoRun c = run_trpo("trpo_c", tight + "}", cartpole);
  const TrpoRun d = run_trpo("trpo_d", tight + ", learning_rate: 0.01}", cartpole);
  for (size_t r = 0; r < c.rows.size(); ++r) {
    if (c.column("train/is_line_search_success", r).empty()) continue;  // before any update
    CHECK(c.column("train/is_line_search_success", r) == "0");
    CHECK(c.column("train/kl_divergence_loss", r) == "0");
  }
  for (const char* actor : {"mlp_extractor.policy_net.0.weight", "action_net.weight"})
    CHECK(c.model.tensors.at(actor).bytes == d.model.tensors.at(actor).bytes);
  CHECK(c.model.tensors.at("value_net.weight").bytes !=
        d.model.tensors.at("value_net.weight").bytes);
}

TEST_CASE("TRPO with gSDE runs through the registry and logs sb3-contrib's keys", "[algos][trpo]") {
  const TrpoRun run =
      run_trpo("trpo_sde",
               "{id: TRPO, n_steps: 256, gamma: 0.9, use_sde: true, sde_sample_freq: 4, "
               "policy: {net_arch: [16]}}",
               "env: {id: Pendulum-v1, n_envs: 2}\n");
  for (const char* key : {"train/policy_objective", "train/value_loss", "train/kl_divergence_loss",
                          "train/explained_variance", "train/is_line_search_success", "train/std",
                          "train/n_updates", "train/learning_rate"}) {
    INFO(key);
    CHECK(run.column(key, run.rows.size() - 1).rfind("(missing", 0) != 0);
    CHECK(!run.column(key, run.rows.size() - 1).empty());
  }
  CHECK(run.model.tensors.count("log_std") == 1);
}

TEST_CASE("TRPO learns the zoo's CartPole-v1 and Pendulum-v1 entries in seeds 1-3",
          "[.slow][algos][trpo_slow]") {
  testing::check_zoo_learning_bar("configs/zoo/cartpole_trpo.yaml", 475.0);
  testing::check_zoo_learning_bar("configs/zoo/pendulum_trpo.yaml", -400.0);
}
