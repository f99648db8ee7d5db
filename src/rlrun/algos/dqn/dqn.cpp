#include "rlrun/algos/dqn/dqn.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun {

namespace {
// Distinct streams from one seed: weights (init_rng_ = seed), exploration, replay sampling.
constexpr uint64_t kActionStream = 0x5851f42d4c957f2dULL;
constexpr uint64_t kReplayStream = 0x2545f4914f6cdd1dULL;

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("DQN: " + message);
}

// Validates before any member is built from the config (the replay buffer allocates).
const DQN::Config& checked(const DQN::Config& c, const AlgorithmSetup& setup) {
  require(setup.observation_space.is_box(),
          "observation space " + setup.observation_space.describe() +
              " is not supported (Box only; SB3 would one-hot Discrete observations)");
  require(setup.action_space.is_discrete(),
          "action space " + setup.action_space.describe() + " is not supported (Discrete only)");
  require(setup.n_envs >= 1, "n_envs must be >= 1");
  const OffPolicyConfig& o = c.off_policy;
  require(o.buffer_size >= 1, "buffer_size must be >= 1");
  require(o.learning_starts >= 0, "learning_starts must be >= 0");
  require(o.batch_size >= 1, "batch_size must be >= 1");
  require(o.tau > 0.0 && o.tau <= 1.0, "tau must be in (0, 1]");
  require(o.gamma >= 0.0 && o.gamma <= 1.0, "gamma must be in [0, 1]");
  require(o.gradient_steps >= -1, "gradient_steps must be >= 0, or -1 (as many as env steps)");
  require(c.learning_rate.initial() >= 0.0, "learning_rate must be >= 0");
  require(c.target_update_interval >= 1, "target_update_interval must be >= 1");
  require(c.exploration_fraction > 0.0, "exploration_fraction must be > 0");
  require(c.exploration_initial_eps >= 0.0 && c.exploration_initial_eps <= 1.0,
          "exploration_initial_eps must be in [0, 1]");
  require(c.exploration_final_eps >= 0.0 && c.exploration_final_eps <= 1.0,
          "exploration_final_eps must be in [0, 1]");
  require(c.max_grad_norm > 0.0, "max_grad_norm must be > 0");
  return c;
}
}  // namespace

ConfigProblems DQN::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  if (!setup.observation_space.is_box())
    out.push_back({"id", "observation space " + setup.observation_space.describe() +
                             " is not supported (Box only; OneHotObservation turns Discrete "
                             "observations into a Box)"});
  check_gradient_steps(out, config.off_policy.gradient_steps);
  if (config.off_policy.tau == 0.0)
    out.push_back({"tau", "must be > 0 (0 would never update the target network)"});
  check_net_arch(out, "policy.net_arch", config.policy.net_arch);
  const int actions = setup.action_space.is_discrete() ? static_cast<int>(setup.action_space.n()) : 1;
  // The Q-network, its target and the two-core replicas of both.
  check_network_memory(out, "policy.net_arch", setup.observation_space.flat_dim(),
                       config.policy.net_arch, actions, 4, config.off_policy.batch_size);
  check_replay_memory(out, config.off_policy.buffer_size, setup);
  return out;
}

DQN::DQN(const Config& config, const AlgorithmSetup& setup)
    : config_(checked(config, setup)),
      setup_(setup),
      action_start_(static_cast<float>(setup.action_space.start())),
      init_rng_(setup.seed),
      action_rng_(setup.seed ^ kActionStream),
      replay_rng_(setup.seed ^ kReplayStream),
      // DQNPolicy._build: q_net, then q_net_target loaded from q_net's state_dict.
      q_net_(make_q_network(setup.observation_space.flat_dim(),
                            static_cast<int>(setup.action_space.n()), config.policy, init_rng_)),
      q_net_target_(q_net_),
      act_net_(q_net_),
      updater_(q_net_, q_net_target_),
      exploration_schedule_{config.exploration_initial_eps, config.exploration_final_eps,
                            config.exploration_fraction},
      state_(config.off_policy, setup.n_envs, setup.observation_space.flat_dim(), /*act_dim=*/1) {
  const int obs_dim = setup.observation_space.flat_dim();
  const int batch = config_.off_policy.batch_size;
  batch_.obs.resize(obs_dim, batch);
  batch_.next_obs.resize(obs_dim, batch);
  batch_.actions.resize(1, batch);
  batch_.rewards.resize(batch);
  batch_.dones.resize(batch);
}

void DQN::random_actions(Eigen::Index n, Eigen::MatrixXf& actions) {
  if (actions.rows() != 1 || actions.cols() != n) actions.resize(1, n);
  for (Eigen::Index e = 0; e < n; ++e)
    setup_.action_space.sample(action_rng_, std::span<float>(&actions(0, e), 1));
}

void DQN::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                  Eigen::MatrixXf& actions) {
  // SB3 DQN.predict: `if not deterministic and np.random.rand() < self.exploration_rate`, one
  // draw for the batch; then action_space.sample() per observation.
  if (!deterministic && action_rng_.uniform() < exploration_rate_) {
    random_actions(obs.cols(), actions);
    return;
  }
  if (act_net_stale_) {
    act_net_.params() = q_net_.params();  // same size: a copy, no allocation
    act_net_stale_ = false;
  }
  greedy_actions(act_net_.forward(obs), action_start_, actions);
}

void DQN::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // OffPolicyAlgorithm._sample_action: uniform actions before learning_starts, else predict()
  // with deterministic=False. The buffer stores the Q-network index (= the env action when the
  // Discrete space starts at 0, as SB3 assumes).
  if (warmup)
    random_actions(obs.cols(), env_actions);
  else
    predict(obs, false, env_actions);
  buffer_actions = env_actions;
  if (action_start_ != 0.0f) buffer_actions.array() -= action_start_;
}

void DQN::on_step(Logger* logger) {
  // SB3 DQN._on_step. Each call is one VecEnv step = n_envs transitions, hence the division.
  ++n_calls_;
  const int64_t period = std::max<int64_t>(config_.target_update_interval / setup_.n_envs, 1);
  if (n_calls_ % period == 0) {
    polyak_update(q_net_.params(), q_net_target_.params(),
                  static_cast<float>(config_.off_policy.tau));
    updater_.invalidate_target();
  }
  exploration_rate_ = exploration_schedule_(state_.progress_remaining);
  if (logger) logger->record(key_exploration_rate_, exploration_rate_);
}

double DQN::loss_and_grad(const ReplayBatch& batch) {
  return updater_.loss_and_grad(batch, static_cast<float>(config_.off_policy.gamma));
}

void DQN::train(int gradient_steps, Logger* logger) {
  // _update_learning_rate: the schedule at the current progress, for every step of this call.
  const double lr = config_.learning_rate(state_.progress_remaining);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);
  const auto max_grad_norm = static_cast<float>(config_.max_grad_norm);
  double loss_sum = 0.0;
  for (int step = 0; step < gradient_steps; ++step) {
    state_.buffer.sample(config_.off_policy.batch_size, replay_rng_, batch_);
    loss_sum += updater_.step(batch_, gamma, max_grad_norm, static_cast<float>(lr));
  }
  n_updates_ += gradient_steps;
  act_net_stale_ = true;
  if (!logger) return;
  logger->record(key_learning_rate_, lr);
  logger->record(key_loss_, loss_sum / std::max(gradient_steps, 1));
  logger->record(key_n_updates_, static_cast<double>(n_updates_));
}

void DQN::learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) {
  if (env.num_envs() != setup_.n_envs)
    throw std::invalid_argument("DQN: env has " + std::to_string(env.num_envs()) +
                                " copies, the algorithm was built for " +
                                std::to_string(setup_.n_envs));
  Logger* logger = hooks.logger;
  OffPolicyCallbacks callbacks;
  callbacks.select_actions = [this](const Eigen::MatrixXf& obs, bool warmup,
                                    Eigen::MatrixXf& env_actions, Eigen::MatrixXf& buffer_actions) {
    select_actions(obs, warmup, env_actions, buffer_actions);
  };
  callbacks.on_step = [this, logger] { on_step(logger); };
  callbacks.train = [this](int gradient_steps, Logger* log) { train(gradient_steps, log); };
  off_policy_learn(env, total_timesteps, hooks, config_.off_policy, state_, callbacks,
                   num_timesteps_);
}

void DQN::save(TensorMap& tensors) const {
  save_q_network(q_net_, "q_net", tensors);
  save_q_network(q_net_target_, "q_net_target", tensors);
  tensors["exploration_rate"] = scalar_tensor<double>(exploration_rate_);
}

void DQN::load(const TensorMap& tensors) {
  load_q_network(q_net_, "q_net", tensors);
  load_q_network(q_net_target_, "q_net_target", tensors);
  if (tensors.count("exploration_rate"))
    exploration_rate_ = scalar_from<double>(tensors, "exploration_rate");
  act_net_stale_ = true;
  updater_.invalidate_q_net();
  updater_.invalidate_target();
}

void DQN::save_training_state(StateWriter& out) const {
  out.put_int("num_timesteps", num_timesteps_);
  out.put_int("n_calls", n_calls_);
  out.put_int("n_updates", n_updates_);
  out.put_double("exploration_rate", exploration_rate_);
  out.put_rng("action_rng", action_rng_);
  out.put_rng("replay_rng", replay_rng_);
  updater_.write_state(out.sub("optimizer"));
  state_.write_state(out.sub("off_policy"));
}

void DQN::load_training_state(const StateReader& in) {
  num_timesteps_ = in.get_int("num_timesteps");
  n_calls_ = in.get_int("n_calls");
  n_updates_ = in.get_int("n_updates");
  exploration_rate_ = in.get_double("exploration_rate");
  in.get_rng("action_rng", action_rng_);
  in.get_rng("replay_rng", replay_rng_);
  updater_.read_state(in.sub("optimizer"));
  state_.read_state(in.sub("off_policy"));
}

}  // namespace rlrun
