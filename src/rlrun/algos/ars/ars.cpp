#include "rlrun/algos/ars/ars.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/session_time.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {

bool bounded_box(const Space& space) {
  if (!space.is_box()) return false;
  for (size_t i = 0; i < space.low().size(); ++i)
    if (!std::isfinite(space.low()[i]) || !std::isfinite(space.high()[i]) ||
        !(space.low()[i] < space.high()[i]))
      return false;
  return true;
}

int output_size(const Space& action_space) {
  return action_space.is_discrete() ? static_cast<int>(action_space.n()) : action_space.flat_dim();
}

}  // namespace

ConfigProblems ARS::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  if (setup.observation_space.is_uint8_box() && setup.observation_space.shape().size() == 3)
    out.push_back({"policy",
                   "ARS's policy reads flat observations (sb3-contrib has no CnnPolicy "
                   "for ARS); images are not supported"});
  if (setup.action_space.is_box() && config.policy.squash_output &&
      !bounded_box(setup.action_space))
    out.push_back({"policy.squash_output",
                   "squashed actions are scaled to the Box's bounds, which must be finite"});
  return out;
}

ARS::ARS(const Config& config, const AlgorithmSetup& setup)
    : config_(valid_config(config, "ARS")),
      // sb3-contrib: n_top = n_delta when None, and clipped to n_delta with a warning.
      n_top_(std::min(config.n_top.value_or(config.n_delta), config.n_delta)),
      action_space_(setup.action_space),
      encoder_(setup.observation_space),
      net_(encoder_.features_dim(), config.policy.net_arch, output_size(setup.action_space),
           config.policy.activation_fn),
      rng_(setup.seed ^ kSampleStream) {
  // ARSPolicy is built from create_mlp: torch's Linear init, then zeros with zero_policy.
  Rng init(setup.seed);
  net_.init_torch_default(init);
  for (int l = 0; l < net_.num_layers(); ++l) {
    const Eigen::Index w = net_.weight(l).data() - net_.params().data();
    for (Eigen::Index i = 0; i < net_.weight(l).size(); ++i) learned_.push_back(w + i);
    if (!config_.policy.with_bias) {
      net_.bias(l).setZero();
      continue;
    }
    const Eigen::Index b = net_.bias(l).data() - net_.params().data();
    for (Eigen::Index i = 0; i < net_.bias(l).size(); ++i) learned_.push_back(b + i);
  }
  std::sort(learned_.begin(), learned_.end());
  if (config_.zero_policy) net_.params().setZero();
  checkpoint("num_timesteps", num_timesteps_);
  checkpoint("n_updates", n_updates_);
  checkpoint("rng", rng_);
}

Eigen::VectorXf ARS::weights() const {
  Eigen::VectorXf w(static_cast<Eigen::Index>(learned_.size()));
  for (size_t i = 0; i < learned_.size(); ++i) w(i) = net_.params()(learned_[i]);
  return w;
}

void ARS::set_weights(const Eigen::VectorXf& weights) {
  if (weights.size() != static_cast<Eigen::Index>(learned_.size()))
    throw std::invalid_argument("ARS::set_weights: wrong size");
  for (size_t i = 0; i < learned_.size(); ++i) net_.params()(learned_[i]) = weights(i);
}

void ARS::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  const auto start = std::chrono::steady_clock::now();
  const int64_t start_timesteps = num_timesteps_;
  const int log_interval = hooks.log_interval > 0 ? hooks.log_interval : 1;
  const Eigen::Index n_params = static_cast<Eigen::Index>(learned_.size());
  bool keep_going = true;
  while (num_timesteps_ < total_timesteps && keep_going) {
    const double progress_remaining =
        1.0 - static_cast<double>(num_timesteps_) / static_cast<double>(total_timesteps);
    const double delta_std = config_.delta_std(progress_remaining);
    const double learning_rate = config_.learning_rate(progress_remaining);
    // th.normal(0, 1, (n_delta, n_params)), row by row.
    Eigen::MatrixXf deltas(config_.n_delta, n_params);
    for (int k = 0; k < config_.n_delta; ++k)
      for (Eigen::Index p = 0; p < n_params; ++p) deltas(k, p) = static_cast<float>(rng_.normal());
    const Eigen::VectorXf w = weights();
    Eigen::VectorXd candidate_returns(2 * config_.n_delta);
    episode_returns_.clear();
    episode_lengths_.clear();
    candidate_net_ = net_;
    for (int c = 0; c < 2 * config_.n_delta; ++c) {
      const float sign = c < config_.n_delta ? 1.0f : -1.0f;
      const Eigen::VectorXf candidate =
          w + (sign * static_cast<float>(delta_std)) * deltas.row(c % config_.n_delta).transpose();
      for (size_t i = 0; i < learned_.size(); ++i)
        candidate_net_.params()(learned_[i]) = candidate(static_cast<Eigen::Index>(i));
      candidate_returns(c) = evaluate_candidate(env, hooks, keep_going);
    }
    if (hooks.on_rollout_end) hooks.on_rollout_end(num_timesteps_);
    double return_std = 0;
    const double step_size = apply_update(candidate_returns, deltas, learning_rate, return_std);
    if (hooks.logger) record_update(*hooks.logger, delta_std, learning_rate, step_size, return_std);
    ++n_updates_;
    if (hooks.logger && n_updates_ % log_interval == 0) {
      // sb3-contrib ARS._log_and_dump: this update's episodes only.
      Logger& log = *hooks.logger;
      if (!episode_returns_.empty()) {
        const double n = static_cast<double>(episode_returns_.size());
        log.record("rollout/ep_rew_mean",
                   std::accumulate(episode_returns_.begin(), episode_returns_.end(), 0.0) / n);
        log.record("rollout/ep_len_mean",
                   std::accumulate(episode_lengths_.begin(), episode_lengths_.end(), 0.0) / n);
      }
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      record_session_time(log, elapsed, num_timesteps_ - start_timesteps);
      log.record("time/total_timesteps", static_cast<double>(num_timesteps_));
      log.dump(num_timesteps_);
      if (hooks.on_log) hooks.on_log(num_timesteps_);
    }
    if (hooks.at_safe_point && !hooks.at_safe_point(num_timesteps_)) break;
  }
}

double ARS::evaluate_candidate(VecEnv& env, TrainingHooks& hooks, bool& keep_going) {
  // SB3 evaluate_policy: episode_count_targets[i] = (n_eval_episodes + i) // n_envs.
  const int n_envs = env.num_envs();
  std::vector<int> counts(n_envs, 0), targets(n_envs);
  for (int i = 0; i < n_envs; ++i) targets[i] = (config_.n_eval_episodes + i) / n_envs;
  Eigen::VectorXd current_rewards = Eigen::VectorXd::Zero(n_envs);
  Eigen::VectorXd current_lengths = Eigen::VectorXd::Zero(n_envs);
  double total_reward = 0, total_length = 0;
  env.reset();
  auto collecting = [&] {
    for (int i = 0; i < n_envs; ++i)
      if (counts[i] < targets[i]) return true;
    return false;
  };
  while (collecting()) {
    act(candidate_net_, env.obs(), actions_);
    env.step(actions_);
    current_rewards += env.original_rewards();
    current_lengths.array() += 1.0;
    for (int i = 0; i < n_envs; ++i) {
      if (counts[i] >= targets[i]) continue;
      // The callback of ARS._trigger_callback: num_timesteps += n_envs, per env still counting.
      num_timesteps_ += n_envs;
      if (hooks.on_step && !hooks.on_step(num_timesteps_)) keep_going = false;
      if (!env.done(i)) continue;
      // The Monitor's episode return when the env reports one (rlrun's episode.r), as
      // evaluate_policy reads it from a Monitor-wrapped env.
      const Info& info = env.info(i);
      const int r = info.find("episode.r"), l = info.find("episode.l");
      const bool monitored = info.has(r) && info.has(l);
      const double episode_return = monitored ? info.get(r) : current_rewards(i);
      const double episode_length = monitored ? info.get(l) : current_lengths(i);
      episode_returns_.push_back(episode_return);
      episode_lengths_.push_back(episode_length);
      total_reward += episode_return;
      total_length += episode_length;
      ++counts[i];
      current_rewards(i) = 0;
      current_lengths(i) = 0;
    }
  }
  return total_reward + config_.alive_bonus_offset * total_length;
}

double ARS::apply_update(const Eigen::VectorXd& candidate_returns, const Eigen::MatrixXf& deltas,
                         double learning_rate, double& return_std) {
  const int n = config_.n_delta;
  const Eigen::VectorXd plus = candidate_returns.head(n), minus = candidate_returns.tail(n);
  // top_idx = argsort(max(plus, minus), descending)[:n_top]; torch's sort is not stable, ties
  // are ordered by index here.
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return std::max(plus(a), minus(a)) > std::max(plus(b), minus(b));
  });
  order.resize(n_top_);
  Eigen::VectorXd top(2 * n_top_);
  for (int k = 0; k < n_top_; ++k) {
    top(k) = plus(order[k]);
    top(n_top_ + k) = minus(order[k]);
  }
  // torch's std(): unbiased, over the 2 n_top returns.
  const double mean = top.mean();
  return_std = std::sqrt((top.array() - mean).square().sum() / static_cast<double>(top.size() - 1));
  const double step_size = learning_rate / (n_top_ * return_std + 1e-6);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(deltas.cols());
  for (int k = 0; k < n_top_; ++k)
    step += (plus(order[k]) - minus(order[k])) * deltas.row(order[k]).transpose().cast<double>();
  set_weights((weights().cast<double>() + step_size * step).cast<float>());
  return step_size;
}

void ARS::record_update(Logger& log, double delta_std, double learning_rate, double step_size,
                        double return_std) const {
  log.record("train/iterations", static_cast<double>(n_updates_));
  log.record("train/delta_std", delta_std);
  log.record("train/learning_rate", learning_rate);
  log.record("train/step_size", step_size);
  log.record("rollout/return_std", return_std);
}

void ARS::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool /*deterministic*/,
                  Eigen::MatrixXf& actions) {
  // "Non deterministic action does not really make sense for ARS": always the network's.
  act(net_, obs, actions);
}

void ARS::act(Mlp& net, const Eigen::Ref<const Eigen::MatrixXf>& obs, Eigen::MatrixXf& actions) {
  const Eigen::MatrixXf& out = net.forward(encoder_(obs));
  if (action_space_.is_discrete()) {
    actions.resize(1, out.cols());
    for (Eigen::Index j = 0; j < out.cols(); ++j) {
      Eigen::Index best = 0;
      out.col(j).maxCoeff(&best);
      actions(0, j) = static_cast<float>(best + action_space_.start());
    }
    return;
  }
  actions = out;
  for (Eigen::Index i = 0; i < actions.rows(); ++i) {
    const float low = action_space_.low()[i], high = action_space_.high()[i];
    for (Eigen::Index j = 0; j < actions.cols(); ++j) {
      float a = actions(i, j);
      // squash_output: tanh, then BasePolicy.unscale_action; else np.clip to the bounds.
      if (config_.policy.squash_output) a = low + 0.5f * (std::tanh(a) + 1.0f) * (high - low);
      actions(i, j) = std::clamp(a, low, high);
    }
  }
}

void ARS::save(TensorMap& tensors) const {
  for (int l = 0; l < net_.num_layers(); ++l) {
    const std::string name = "action_net." + std::to_string(2 * l);
    tensors[name + ".weight"] = to_tensor(Eigen::MatrixXf(net_.weight(l)));
    if (config_.policy.with_bias)
      tensors[name + ".bias"] = to_tensor(Eigen::VectorXf(net_.bias(l)));
  }
}

void ARS::load(const TensorMap& tensors) {
  for (int l = 0; l < net_.num_layers(); ++l) {
    const std::string name = "action_net." + std::to_string(2 * l);
    Eigen::MatrixXf w(net_.weight(l).rows(), net_.weight(l).cols());
    from_tensor(tensors, name + ".weight", w);
    net_.weight(l) = w;
    if (config_.policy.with_bias) {
      Eigen::VectorXf b(net_.bias(l).size());
      from_tensor(tensors, name + ".bias", b);
      net_.bias(l) = b;
    }
  }
}

void ARS::export_policy(PolicyGraph& graph, const std::string& obs, bool /*with_value*/) const {
  std::string out = graph.mlp(encoder_.export_to(graph, obs), net_);
  if (action_space_.is_discrete()) {
    std::string action = graph.argmax(out);
    if (action_space_.start() != 0) {
      const Eigen::VectorXf zero = Eigen::VectorXf::Zero(1), one = Eigen::VectorXf::Ones(1);
      action =
          graph.affine(action, zero, one,
                       Eigen::VectorXf::Constant(1, static_cast<float>(action_space_.start())));
    }
    graph.set_action(action);
    return;
  }
  const Eigen::Index dim = action_space_.flat_dim();
  const Eigen::VectorXf low = Eigen::Map<const Eigen::VectorXf>(action_space_.low().data(), dim);
  const Eigen::VectorXf high = Eigen::Map<const Eigen::VectorXf>(action_space_.high().data(), dim);
  if (config_.policy.squash_output) {
    // low + (tanh(x) + 1) (high - low) / 2
    out = graph.affine(graph.activation(out, Activation::kTanh), Eigen::VectorXf::Ones(dim),
                       0.5f * (high - low), low);
  }
  graph.set_action(graph.clamp(out, low, high));
}

}  // namespace rlrun
