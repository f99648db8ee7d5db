#include "rlrun/algos/dqn/dqn.hpp"

#include "rlrun/nn/policy_graph.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "rlrun/algos/common/features_extractor_net.hpp"
#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/algos/common/training_state.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/env/image_space.hpp"

namespace rlrun {

namespace {
// Replay sampling: DQN's own stream, drawn before algos/common/rng_streams.hpp named them (it is
// kNoiseStream's word; fixed forever, as every stream is). Exploration is kActionStream.
constexpr uint64_t kReplayStream = 0x2545f4914f6cdd1dULL;

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument("DQN: " + message);
}

// Validates before the networks are built from the config: the fields' constraints (visit),
// then what DQN adds: Discrete actions, and a target network that moves (tau > 0).
const DQN::Config& checked(const DQN::Config& c, const AlgorithmSetup& setup) {
  valid_config(c, "DQN");
  require(setup.action_space.is_discrete(),
          "action space " + setup.action_space.describe() + " is not supported (Discrete only)");
  require(c.off_policy.tau > 0.0, "tau must be in (0, 1]");
  return c;
}
}  // namespace

ConfigProblems DQN::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  check_gradient_steps(out, config.off_policy.gradient_steps);
  if (config.off_policy.tau == 0.0)
    out.push_back({"tau", "must be > 0 (0 would never update the target network)"});
  check_net_arch(out, "policy.net_arch", config.policy.net_arch);
  const int actions =
      setup.action_space.is_discrete() ? static_cast<int>(setup.action_space.n()) : 1;
  const QNetworkConfig& p = config.policy;
  // q_net's CNN and q_net_target's.
  const int features =
      features_extractor_output_dim(out, "policy.features_extractor_class", p.extractor(),
                                    setup.observation_space, 2, config.off_policy.batch_size);
  // The Q-network, its target and the second core's activations of both.
  check_network_memory(out, "policy.net_arch", features, config.policy.net_arch, actions, 4,
                       config.off_policy.batch_size);
  check_replay_buffer(out, config.off_policy, setup);
  return out;
}

DQN::DQN(const Config& config, const AlgorithmSetup& setup)
    : OffPolicyAlgorithm("DQN", checked(config, setup).off_policy, setup,
                         /*buffer_action_dim=*/1, {kReplayStream, "replay_rng"},
                         encoder_normalizes_images(config.policy.features_extractor_class,
                                                   config.policy.normalize_images)),
      config_(config),
      action_start_(static_cast<float>(setup.action_space.start())),
      action_rng_(setup.seed ^ kActionStream),
      // DQNPolicy._build: q_net with torch's default Linear init, then q_net_target loaded
      // from q_net's state_dict.
      extractor_(config.policy.extractor(), setup.observation_space, features_dim(), setup.pool),
      q_net_([&] {
        Rng init_rng(setup.seed);
        return SplitMlp(
            make_q_network(extractor_.out_dim(), static_cast<int>(setup.action_space.n()),
                           config.policy, init_rng),
            setup.pool);
      }()),
      q_net_target_(q_net_),
      act_net_(q_net_.net()),
      optimizer_(q_net_.net().block(), AdamConfig{}, setup.pool),
      exploration_schedule_{config.exploration_initial_eps, config.exploration_final_eps,
                            config.exploration_fraction} {
  // Resume: counters, exploration rate, the action stream and the optimizer's two parts (the
  // networks, target included, are in the model tensors).
  checkpoint("n_calls", n_calls_);
  checkpoint("exploration_rate", exploration_rate_);
  checkpoint("action_rng", action_rng_);
  checkpoint("optimizer/adam0", optimizer_.part(0));
  checkpoint("optimizer/adam1", optimizer_.part(1));
  // SB3 QNetwork: the extractor's networks (NatureCNN, a CombinedExtractor's per image key)
  // with torch's default init (DQN never applies ortho init); their own stream, as torch's
  // draws cannot be replayed anyway.
  Rng extractor_rng(setup.seed ^ kFeaturesExtractorInitStream);
  extractor_.init_torch_default(extractor_rng);
  extractor_target_ = extractor_;  // q_net_target.load_state_dict(q_net.state_dict())
  act_extractor_ = extractor_;
  for (const ParamBlock& block : extractor_.blocks()) {
    const std::string name =
        "optimizer/cnn" +
        (extractor_optimizers_.empty() ? "" : std::to_string(extractor_optimizers_.size()));
    extractor_optimizers_.emplace_back(block, AdamConfig{}, setup.pool);
    checkpoint(name + "_adam0", extractor_optimizers_.back().part(0));
    checkpoint(name + "_adam1", extractor_optimizers_.back().part(1));
  }
}

// SB3 dqn/dqn.py DQN.train, one pass of its loop over gradient steps (CleanRL's dqn.py has the
// same steps with an MSE loss and no gradient clipping).
double DQN::train_on_batch(const ReplayBatch& b, float lr) {
  const Eigen::Index n = b.obs.cols();
  const float inv_n = 1.0f / static_cast<float>(n);
  const auto gamma = static_cast<float>(config_.off_policy.gamma);

  // with th.no_grad():
  //   next_q_values = q_net_target(next_obs).max(dim=1)
  //   target_q_values = rewards + (1 - dones) * gamma * next_q_values
  const Eigen::MatrixXf& next_q =
      q_net_target_.forward(extractor_target_.forward(batch_next_obs(b)));
  targets_.resize(n);
  for (Eigen::Index j = 0; j < n; ++j)
    targets_(j) = b.rewards(j) + (1.0f - b.dones(j)) * gamma * next_q.col(j).maxCoeff();

  // current_q_values = th.gather(q_net(obs), dim=1, index=actions)
  // loss = F.smooth_l1_loss(current_q_values, target_q_values): 0.5 d^2 where |d| < 1, else
  // |d| - 0.5, averaged; its gradient is d clamped to [-1, 1], over n, at the taken actions.
  const Eigen::MatrixXf& q = q_net_.forward(extractor_.forward(batch_obs(b)));
  grad_q_.setZero(q.rows(), n);
  double loss = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto a = static_cast<Eigen::Index>(b.actions(0, j));  // .long() truncates
    if (a < 0 || a >= q.rows())  // replay buffers come from checkpoints too
      throw std::out_of_range("DQN: action " + std::to_string(a) + " outside [0, " +
                              std::to_string(q.rows()) + ")");
    const float diff = q(a, j) - targets_(j);
    const float abs_diff = std::abs(diff);
    loss += abs_diff < 1.0f ? 0.5 * static_cast<double>(diff) * diff : abs_diff - 0.5;
    grad_q_(a, j) = std::clamp(diff, -1.0f, 1.0f) * inv_n;
  }

  // optimizer.zero_grad(); loss.backward() — through the features into the CNN, if any.
  if (extractor_.learned()) {
    q_net_.zero_grad_and_backward(grad_q_, nullptr, &grad_features_);
    extractor_.zero_grad_and_backward(grad_features_);
  } else {
    q_net_.zero_grad_and_backward(grad_q_);
  }
  // th.nn.utils.clip_grad_norm_(q_net.parameters(), max_grad_norm): the gradient times
  // max_grad_norm / (norm + 1e-6) when that is below 1 (a NaN norm propagates, as torch's
  // default does); then optimizer.step(). The norm covers the CNN's parameters too.
  double sum_sq = optimizer_.grad_sum_of_squares();
  for (const SplitAdam& adam : extractor_optimizers_) sum_sq += adam.grad_sum_of_squares();
  last_grad_norm_ = static_cast<float>(std::sqrt(sum_sq));
  const float clip = static_cast<float>(config_.max_grad_norm) / (last_grad_norm_ + 1e-6f);
  const float scale = clip < 1.0f || std::isnan(clip) ? clip : 1.0f;
  optimizer_.step(lr, scale);
  for (SplitAdam& adam : extractor_optimizers_) adam.step(lr, scale);
  return loss / static_cast<double>(n);
}

void DQN::train(int gradient_steps, Logger* logger) {
  // _update_learning_rate: the schedule at the current progress, for every step of this call.
  const double lr = config_.learning_rate(progress_remaining());
  double loss_sum = 0.0;
  for (int step = 0; step < gradient_steps; ++step)
    loss_sum += train_on_batch(sample_batch(), static_cast<float>(lr));
  n_updates_ += gradient_steps;
  act_net_stale_ = true;
  if (!logger) return;
  logger->record(key_learning_rate_, lr);
  logger->record(key_loss_, loss_sum / std::max(gradient_steps, 1));
  logger->record(key_n_updates_, static_cast<double>(n_updates_));
}

void DQN::on_step(Logger* logger) {
  // SB3 DQN._on_step. Each call is one VecEnv step = n_envs transitions, hence the division.
  ++n_calls_;
  const int64_t period = std::max<int64_t>(config_.target_update_interval / setup_.n_envs, 1);
  if (n_calls_ % period == 0) {
    const auto tau = static_cast<float>(config_.off_policy.tau);
    polyak_update(q_net_.params(), q_net_target_.params(), tau);
    polyak_update(extractor_, extractor_target_, tau);
  }
  exploration_rate_ = exploration_schedule_(progress_remaining());
  if (logger) logger->record(key_exploration_rate_, exploration_rate_);
}

void DQN::random_actions(Eigen::Index n, Eigen::MatrixXf& actions) {
  if (actions.rows() != 1 || actions.cols() != n) actions.resize(1, n);
  for (Eigen::Index e = 0; e < n; ++e)
    setup_.action_space.sample(action_rng_, std::span<float>(&actions(0, e), 1));
}

// predict(deterministic): the greedy action, start + argmax Q; the value is every Q-value.
void DQN::export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const {
  const std::string encoded = acting_encoder().export_to(graph, obs);
  const std::string q = graph.mlp(extractor_.export_to(graph, encoded), q_net_.net());
  std::string action = graph.argmax(q);
  if (action_start_ != 0.0f)
    action = graph.affine(action, Eigen::VectorXf::Zero(1), Eigen::VectorXf::Ones(1),
                          Eigen::VectorXf::Constant(1, action_start_));
  graph.set_action(action);
  if (with_value) graph.set_value(q);
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
    act_extractor_.copy_parameters_from(extractor_);
    act_net_stale_ = false;
  }
  greedy_actions(act_net_.forward(act_extractor_.forward(acting_features(obs))), action_start_,
                 actions);
}

void DQN::select_actions(const Eigen::MatrixXf& obs, bool warmup, Eigen::MatrixXf& env_actions,
                         Eigen::MatrixXf& buffer_actions) {
  // The buffer stores the Q-network index (= the env action when the Discrete space starts at
  // 0, as SB3 assumes).
  if (warmup)
    random_actions(obs.cols(), env_actions);
  else
    predict(obs, false, env_actions);
  buffer_actions = env_actions;
  if (action_start_ != 0.0f) buffer_actions.array() -= action_start_;
}

void DQN::save(TensorMap& tensors) const {
  save_q_network(q_net_.net(), "q_net", tensors);
  save_q_network(q_net_target_.net(), "q_net_target", tensors);
  extractor_.save("q_net.features_extractor", tensors);
  extractor_target_.save("q_net_target.features_extractor", tensors);
  tensors["exploration_rate"] = scalar_tensor<double>(exploration_rate_);
}

void DQN::load(const TensorMap& tensors) {
  load_q_network(q_net_.net(), "q_net", tensors);
  load_q_network(q_net_target_.net(), "q_net_target", tensors);
  extractor_.load("q_net.features_extractor", tensors);
  extractor_target_.load("q_net_target.features_extractor", tensors);
  if (tensors.count("exploration_rate"))
    exploration_rate_ = scalar_from<double>(tensors, "exploration_rate");
  act_net_stale_ = true;
}

}  // namespace rlrun
