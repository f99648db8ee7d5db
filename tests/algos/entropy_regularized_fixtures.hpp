#pragma once
// What the SAC and TQC tests (test_sac.cpp, test_tqc.cpp) share, as the algorithms share their
// actor (algos/common/entropy_regularized_actor_critic.hpp): the squashed Gaussian and the actor
// loss re-implemented in double (independent of the float code under test), the checks of the
// gradient step's shared part (actor, temperature, targets), random minibatches in a Box with
// uneven bounds, and short Pendulum-v1 runs through the registry and their evaluation.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "nn/grad_check.hpp"
#include "rlrun/algos/common/entropy_regularized_actor_critic.hpp"
#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"

namespace rlrun::test {

inline constexpr double kHalfLog2Pi = 0.91893853320467274;

// One sample through test::mlp_forward.
inline Eigen::VectorXd mlp_forward_one(const Mlp& net, const Eigen::VectorXd& p,
                                       const Eigen::VectorXd& x) {
  return mlp_forward(net, p, x).col(0);
}

// SB3's Actor.action_log_prob for one observation with fixed noise: (action, log_prob).
inline std::pair<Eigen::VectorXd, double> actor_sample(const Mlp& net, const Eigen::VectorXd& p,
                                                       int a_dim, const Eigen::VectorXd& obs,
                                                       const Eigen::VectorXd& noise) {
  const Eigen::VectorXd out = mlp_forward_one(net, p, obs);
  Eigen::VectorXd a(a_dim);
  double logp = 0.0;
  for (int i = 0; i < a_dim; ++i) {
    const double mu = out(i);
    const double log_std = std::clamp(out(a_dim + i), -20.0, 2.0);
    const double std = std::exp(log_std);
    const double u = mu + std * noise(i);
    a(i) = std::tanh(u);
    // Normal(mu, std).log_prob(u) - log(1 - tanh(u)^2 + 1e-6), from u as torch computes it.
    logp += -(u - mu) * (u - mu) / (2 * std * std) - log_std - kHalfLog2Pi -
            std::log(1.0 - a(i) * a(i) + 1e-6);
  }
  return {a, logp};
}

inline Eigen::VectorXd concat(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd c(a.size() + b.size());
  c << a, b;
  return c;
}

inline Eigen::MatrixXf random_matrix(Rng& rng, int rows, int cols, double scale = 1.0) {
  Eigen::MatrixXf m(rows, cols);
  for (Eigen::Index k = 0; k < m.size(); ++k) m(k) = static_cast<float>(scale * rng.normal());
  return m;
}

// Box observations and a Box of actions whose bounds differ per dimension.
inline AlgorithmSetup box_setup(int obs_dim, int act_dim, uint64_t seed = 7) {
  std::vector<float> low(act_dim), high(act_dim);
  for (int i = 0; i < act_dim; ++i) {
    low[i] = -2.0f + static_cast<float>(i);
    high[i] = 2.0f + 3.0f * static_cast<float>(i);
  }
  return AlgorithmSetup{Space::box(-10.0f, 10.0f, {obs_dim}), Space::box(low, high, {act_dim}), 1,
                        seed};
}

// Actions inside (-1, 1), rewards of `reward_scale` units, every third transition terminal.
inline ReplayBatch random_batch(Rng& rng, int obs_dim, int act_dim, int n,
                                double reward_scale = 1.0) {
  ReplayBatch b;
  b.obs = random_matrix(rng, obs_dim, n);
  b.next_obs = random_matrix(rng, obs_dim, n);
  b.actions = random_matrix(rng, act_dim, n, 0.5).cwiseMax(-0.99f).cwiseMin(0.99f);
  b.rewards = random_matrix(rng, 1, n, reward_scale);
  b.dones = Eigen::RowVectorXf::Zero(n);
  for (int j = 0; j < n; j += 3) b.dones(j) = 1.0f;
  return b;
}

// Q(s, a) as an algorithm's actor loss reads its critics (SAC: the minimum of the critics,
// TQC: the mean of every atom), in double.
using ActorQ = std::function<double(const Eigen::VectorXd& obs, const Eigen::VectorXd& action)>;

// actor_loss = mean_j(alpha log pi(a_j|s_j) - Q(s_j, a_j)), a_j the squashed sample of the actor
// with parameters `p` and the noise of the algorithm's last step; `mean_log_prob` (if given)
// gets mean_j log pi(a_j|s_j).
inline double actor_loss(const EntropyRegularizedActorCritic& algo, const Eigen::VectorXd& p,
                         const ReplayBatch& b, double alpha, const ActorQ& q,
                         double* mean_log_prob = nullptr) {
  const Eigen::Index n = b.obs.cols();
  double loss = 0.0, log_prob = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd o = b.obs.col(j).cast<double>();
    const auto [a, lp] = actor_sample(algo.actor().net(), p, algo.actor().action_dim(), o,
                                      algo.last_policy_noise().col(j).cast<double>());
    loss += alpha * lp - q(o, a);
    log_prob += lp;
  }
  if (mean_log_prob) *mean_log_prob = log_prob / static_cast<double>(n);
  return loss / static_cast<double>(n);
}

// The parameters before a gradient step.
struct StepStart {
  explicit StepStart(const EntropyRegularizedActorCritic& algo)
      : actor(params_of(algo.actor().net())),
        alpha(std::exp(static_cast<double>(algo.ent_coef().log_value()))) {
    for (int i = 0; i < algo.critic().n_critics(); ++i) {
      critics.push_back(params_of(algo.critic().q(i).net()));
      targets.push_back(params_of(algo.critic_target().q(i).net()));
    }
  }
  Eigen::VectorXd actor;
  std::vector<Eigen::VectorXd> critics, targets;
  double alpha;
};

// What SAC's and TQC's gradient steps share, after train_on_batch(b, lr, true) returned `stats`
// from `start` with a learned entropy coefficient and target_entropy auto: the actor loss with
// the stepped critics (`q`), the entropy coefficient's loss -log_alpha mean(log pi +
// target_entropy) and its first Adam step, the targets' Polyak update with `tau` (after the
// critic step), and that the critics and the actor moved.
inline void check_actor_temperature_and_targets(const EntropyRegularizedActorCritic& algo,
                                                const StepStart& start, const ReplayBatch& b,
                                                float lr, double tau,
                                                const EntropyRegularizedStepStats& stats,
                                                const ActorQ& q) {
  CHECK(stats.ent_coef == Approx(start.alpha));
  double mean_logp = 0.0;
  const double loss = actor_loss(algo, start.actor, b, start.alpha, q, &mean_logp);
  CHECK(stats.actor_loss == Approx(loss).epsilon(1e-4).margin(1e-5));
  const double target_entropy = -algo.actor().action_dim();
  CHECK(stats.ent_coef_loss ==
        Approx(-std::log(start.alpha) * (mean_logp + target_entropy)).epsilon(1e-4));
  // Adam's first step is lr * g / (|g| + eps) = lr * sign(g), g = -(mean log pi + target).
  const double g = -(mean_logp + target_entropy);
  CHECK(algo.ent_coef().log_value() ==
        Approx(std::log(start.alpha) - lr * (g > 0 ? 1 : -1)).epsilon(1e-5));
  // target <- (1 - tau) target + tau * online.
  for (int i = 0; i < algo.critic().n_critics(); ++i) {
    const Eigen::VectorXd online = params_of(algo.critic().q(i).net());
    const Eigen::VectorXd expected = (1.0 - tau) * start.targets[i] + tau * online;
    CHECK((params_of(algo.critic_target().q(i).net()) - expected).cwiseAbs().maxCoeff() < 1e-6);
    CHECK((online - start.critics[i]).cwiseAbs().maxCoeff() > 1e-4);
  }
  CHECK((params_of(algo.actor().net()) - start.actor).cwiseAbs().maxCoeff() > 1e-4);
}

// A run of `algo` ("SAC", "TQC") on Pendulum-v1 with `algo_extra` appended to its section.
// SB3's SACPolicy.state_dict() names (sb3-contrib's TQCPolicy has the same; Critic registers its
// networks as qf0, qf1 with add_module) of a model with net_arch [8] for a 3-dim observation,
// a 1-dim action, two critics and a learned entropy coefficient.
inline void check_sb3_tensor_names(const TensorMap& t) {
  for (const char* name :
       {"actor.latent_pi.0.weight", "actor.latent_pi.2.bias", "actor.mu.weight", "actor.mu.bias",
        "actor.log_std.weight", "actor.log_std.bias", "critic.qf0.0.weight", "critic.qf0.4.weight",
        "critic.qf1.2.bias", "critic_target.qf0.0.weight", "critic_target.qf1.4.bias",
        "log_ent_coef"}) {
    INFO(name);
    CHECK(t.count(name) == 1);
  }
  CHECK(t.at("critic.qf0.0.weight").shape == std::vector<int64_t>{8, 4});
  CHECK(t.size() == 8 + 2 * 2 * 6 + 1);
}

inline Experiment pendulum_experiment(const std::string& algo, const std::string& out_dir,
                                      int64_t steps, uint64_t seed, const std::string& algo_extra) {
  const std::string yaml = "run: {name: smoke, seed: " + std::to_string(seed) +
                           ", total_timesteps: " + std::to_string(steps) + ", out_dir: " + out_dir +
                           ", console_interval: 1000000}\n"
                           "env: {id: Pendulum-v1}\n"
                           "algo: {id: " +
                           algo + algo_extra + "}\n";
  return parse_experiment(ConfigNode::load_string(yaml, "smoke.yaml"), builtin_registry());
}

// The model's deterministic policy over `episodes` episodes of its own env.
inline EvalResult evaluate_model(const ModelFile& model, int episodes, uint64_t seed) {
  const Experiment stored = experiment_from_model(model, builtin_registry());
  EnvPtr env = make_env(stored.env, builtin_registry(), "", 0.0);
  auto loaded = algorithm_from_model(model, stored, builtin_registry(), env->observation_space(),
                                     env->action_space());
  return evaluate_policy(*loaded, *env, episodes, true, seed);
}

}  // namespace rlrun::test
