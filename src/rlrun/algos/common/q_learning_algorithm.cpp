#include "rlrun/algos/common/q_learning_algorithm.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <utility>

#include "rlrun/algos/common/polyak.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/env/image_space.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

QLearningSettings q_learning_settings(const QLearningConfig& config, const QNetworkConfig& policy,
                                      int outputs_per_action, const AdamConfig& adam,
                                      std::string network_name) {
  return QLearningSettings{
      config.learning_rate,
      config.target_update_interval,
      {config.exploration_initial_eps, config.exploration_final_eps, config.exploration_fraction},
      policy,
      outputs_per_action,
      adam,
      std::move(network_name)};
}

void require_q_learning_setup(const std::string& algo, const OffPolicyConfig& off_policy,
                              const AlgorithmSetup& setup) {
  if (!setup.action_space.is_discrete())
    throw std::invalid_argument(algo + ": action space " + setup.action_space.describe() +
                                " is not supported (Discrete only)");
  if (!(off_policy.tau > 0.0)) throw std::invalid_argument(algo + ": tau must be in (0, 1]");
}

void check_q_learning(ConfigProblems& out, const OffPolicyConfig& off_policy,
                      const QNetworkConfig& policy, int outputs_per_action,
                      const AlgorithmSetup& setup) {
  check_gradient_steps(out, off_policy.gradient_steps);
  if (off_policy.tau == 0.0)
    out.push_back({"tau", "must be > 0 (0 would never update the target network)"});
  check_net_arch(out, "policy.net_arch", policy.net_arch);
  const int actions =
      setup.action_space.is_discrete() ? static_cast<int>(setup.action_space.n()) : 1;
  // The online network's CNN and the target's.
  const int features =
      features_extractor_output_dim(out, "policy.features_extractor_class", policy.extractor(),
                                    setup.observation_space, 2, off_policy.batch_size);
  // The network, its target and the second core's activations of both.
  check_network_memory(out, "policy.net_arch", features, policy.net_arch,
                       actions * std::max(outputs_per_action, 1), 4, off_policy.batch_size);
  check_replay_buffer(out, off_policy, setup);
}

QLearningAlgorithm::QLearningAlgorithm(std::string id, const OffPolicyConfig& off_policy,
                                       const AlgorithmSetup& setup, QLearningSettings settings,
                                       const ReplayStream& replay)
    : OffPolicyAlgorithm(std::move(id), off_policy, setup, /*buffer_action_dim=*/1, replay,
                         encoder_normalizes_images(settings.policy.features_extractor_class,
                                                   settings.policy.normalize_images)),
      settings_(std::move(settings)),
      tau_(off_policy.tau),
      n_actions_(static_cast<int>(setup.action_space.n())),
      action_start_(static_cast<float>(setup.action_space.start())),
      action_rng_(setup.seed ^ kActionStream),
      extractor_(settings_.policy.extractor(), setup.observation_space, features_dim(), setup.pool),
      // DQNPolicy._build / QRDQNPolicy._build: the online network with torch's default Linear
      // init, then the target loaded from its state_dict.
      q_net_([&] {
        Rng init_rng(setup.seed);
        return SplitMlp(
            make_q_network(extractor_.out_dim(), n_actions_ * settings_.outputs_per_action,
                           settings_.policy, init_rng),
            setup.pool);
      }()),
      q_net_target_(q_net_),
      act_net_(q_net_.net()),
      optimizer_(q_net_.net().block(), settings_.adam, setup.pool) {
  // Resume: counters, exploration rate, the action stream and the optimizer's two parts (the
  // networks, target included, are in the model tensors).
  checkpoint("n_calls", n_calls_);
  checkpoint("exploration_rate", exploration_rate_);
  checkpoint("action_rng", action_rng_);
  checkpoint("optimizer/adam0", optimizer_.part(0));
  checkpoint("optimizer/adam1", optimizer_.part(1));
  // SB3 QNetwork: the extractor's networks (NatureCNN, a CombinedExtractor's per image key)
  // with torch's default init (neither algorithm applies ortho init); their own stream, as
  // torch's draws cannot be replayed anyway.
  Rng extractor_rng(setup.seed ^ kFeaturesExtractorInitStream);
  extractor_.init_torch_default(extractor_rng);
  extractor_target_ = extractor_;  // target.load_state_dict(online.state_dict())
  act_extractor_ = extractor_;
  for (const ParamBlock& block : extractor_.blocks()) {
    const std::string name =
        "optimizer/cnn" +
        (extractor_optimizers_.empty() ? "" : std::to_string(extractor_optimizers_.size()));
    extractor_optimizers_.emplace_back(block, settings_.adam, setup.pool);
    checkpoint(name + "_adam0", extractor_optimizers_.back().part(0));
    checkpoint(name + "_adam1", extractor_optimizers_.back().part(1));
  }
}

const Eigen::MatrixXf& QLearningAlgorithm::target_outputs(const ReplayBatch& b) {
  return q_net_target_.forward(extractor_target_.forward(batch_next_obs(b)));
}

const Eigen::MatrixXf& QLearningAlgorithm::online_outputs(const ReplayBatch& b) {
  return q_net_.forward(extractor_.forward(batch_obs(b)));
}

Eigen::Index QLearningAlgorithm::buffer_action(const ReplayBatch& b, Eigen::Index j) const {
  const auto a = static_cast<Eigen::Index>(b.actions(0, j));  // .long() truncates
  if (a < 0 || a >= n_actions_)
    throw std::out_of_range(id() + ": action " + std::to_string(a) + " outside [0, " +
                            std::to_string(n_actions_) + ")");
  return a;
}

void QLearningAlgorithm::backward_and_step(const Eigen::MatrixXf& grad_outputs, float lr,
                                           std::optional<double> max_grad_norm) {
  if (extractor_.learned()) {
    q_net_.zero_grad_and_backward(grad_outputs, nullptr, &grad_features_);
    extractor_.zero_grad_and_backward(grad_features_);
  } else {
    q_net_.zero_grad_and_backward(grad_outputs);
  }
  float scale = 1.0f;
  last_grad_norm_ = 0.0f;
  if (max_grad_norm) {
    // th.nn.utils.clip_grad_norm_(parameters, max_grad_norm): the gradient times
    // max_grad_norm / (norm + 1e-6) when that is below 1 (a NaN norm propagates, as torch's
    // default does). The norm covers the CNN's parameters too.
    double sum_sq = optimizer_.grad_sum_of_squares();
    for (const SplitAdam& adam : extractor_optimizers_) sum_sq += adam.grad_sum_of_squares();
    last_grad_norm_ = static_cast<float>(std::sqrt(sum_sq));
    const float clip = static_cast<float>(*max_grad_norm) / (last_grad_norm_ + 1e-6f);
    scale = clip < 1.0f || std::isnan(clip) ? clip : 1.0f;
  }
  optimizer_.step(lr, scale);
  for (SplitAdam& adam : extractor_optimizers_) adam.step(lr, scale);
}

void QLearningAlgorithm::train(int gradient_steps, Logger* logger) {
  // _update_learning_rate: the schedule at the current progress, for every step of this call.
  const double lr = settings_.learning_rate(progress_remaining());
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

void QLearningAlgorithm::on_step(Logger* logger) {
  // SB3 DQN._on_step. Each call is one VecEnv step = n_envs transitions, hence the division.
  ++n_calls_;
  const int64_t period = std::max<int64_t>(settings_.target_update_interval / setup_.n_envs, 1);
  if (n_calls_ % period == 0) {
    const auto tau = static_cast<float>(tau_);
    polyak_update(q_net_.params(), q_net_target_.params(), tau);
    polyak_update(extractor_, extractor_target_, tau);
  }
  exploration_rate_ = settings_.exploration(progress_remaining());
  if (logger) logger->record(key_exploration_rate_, exploration_rate_);
}

void QLearningAlgorithm::random_actions(Eigen::Index n, Eigen::MatrixXf& actions) {
  if (actions.rows() != 1 || actions.cols() != n) actions.resize(1, n);
  for (Eigen::Index e = 0; e < n; ++e)
    setup_.action_space.sample(action_rng_, std::span<float>(&actions(0, e), 1));
}

void QLearningAlgorithm::export_policy(PolicyGraph& graph, const std::string& obs,
                                       bool with_value) const {
  const std::string encoded = acting_encoder().export_to(graph, obs);
  const std::string q =
      export_q_values(graph, graph.mlp(extractor_.export_to(graph, encoded), q_net_.net()));
  std::string action = graph.argmax(q);
  if (action_start_ != 0.0f)
    action = graph.affine(action, Eigen::VectorXf::Zero(1), Eigen::VectorXf::Ones(1),
                          Eigen::VectorXf::Constant(1, action_start_));
  graph.set_action(action);
  if (with_value) graph.set_value(q);
}

void QLearningAlgorithm::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                                 Eigen::MatrixXf& actions) {
  // `if not deterministic and np.random.rand() < self.exploration_rate`, one draw for the
  // batch; then action_space.sample() per observation.
  if (!deterministic && action_rng_.uniform() < exploration_rate_) {
    random_actions(obs.cols(), actions);
    return;
  }
  if (act_net_stale_) {
    act_net_.params() = q_net_.params();  // same size: a copy, no allocation
    act_extractor_.copy_parameters_from(extractor_);
    act_net_stale_ = false;
  }
  greedy_actions(q_values(act_net_.forward(act_extractor_.forward(acting_features(obs)))),
                 action_start_, actions);
}

void QLearningAlgorithm::select_actions(const Eigen::MatrixXf& obs, bool warmup,
                                        Eigen::MatrixXf& env_actions,
                                        Eigen::MatrixXf& buffer_actions) {
  if (warmup)
    random_actions(obs.cols(), env_actions);
  else
    predict(obs, false, env_actions);
  buffer_actions = env_actions;
  if (action_start_ != 0.0f) buffer_actions.array() -= action_start_;
}

void QLearningAlgorithm::save(TensorMap& tensors) const {
  const std::string& name = settings_.network_name;
  save_q_network(q_net_.net(), name, tensors);
  save_q_network(q_net_target_.net(), name + "_target", tensors);
  extractor_.save(name + ".features_extractor", tensors);
  extractor_target_.save(name + "_target.features_extractor", tensors);
  tensors["exploration_rate"] = scalar_tensor<double>(exploration_rate_);
}

void QLearningAlgorithm::load(const TensorMap& tensors) {
  const std::string& name = settings_.network_name;
  load_q_network(q_net_.net(), name, tensors);
  load_q_network(q_net_target_.net(), name + "_target", tensors);
  extractor_.load(name + ".features_extractor", tensors);
  extractor_target_.load(name + "_target.features_extractor", tensors);
  if (tensors.count("exploration_rate"))
    exploration_rate_ = scalar_from<double>(tensors, "exploration_rate");
  act_net_stale_ = true;
}

}  // namespace rlrun
