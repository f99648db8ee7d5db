#include "rlrun/algos/qrdqn/qrdqn.hpp"

#include "rlrun/algos/common/quantile_huber_loss.hpp"
#include "rlrun/algos/common/rng_streams.hpp"
#include "rlrun/core/config_validation.hpp"
#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

namespace {
// Validates before the networks are built from the config: the fields' constraints (visit),
// then what the Q-network family adds (Discrete actions, tau > 0).
const QRDQN::Config& checked(const QRDQN::Config& c, const AlgorithmSetup& setup) {
  valid_config(c, "QRDQN");
  require_q_learning_setup("QRDQN", c.off_policy, setup);
  return c;
}

// QRDQN.__init__: without an optimizer_class in policy_kwargs, Adam with
// eps = 0.01 / batch_size, "proposed in the QR-DQN paper where batch_size = 32".
QLearningSettings settings_of(const QRDQN::Config& c) {
  AdamConfig adam;
  adam.eps = 0.01 / c.off_policy.batch_size;
  // QRDQNPolicy.quantile_net / quantile_net_target.
  return q_learning_settings(c, c.policy, c.policy.n_quantiles, adam, "quantile_net");
}
}  // namespace

ConfigProblems QRDQN::check(const Config& config, const AlgorithmSetup& setup) {
  ConfigProblems out;
  check_q_learning(out, config.off_policy, config.policy, config.policy.n_quantiles, setup);
  return out;
}

QRDQN::QRDQN(const Config& config, const AlgorithmSetup& setup)
    : QLearningAlgorithm("QRDQN", checked(config, setup).off_policy, setup, settings_of(config),
                         {kSampleStream, "replay_rng"}),
      config_(config) {}

const Eigen::MatrixXf& QRDQN::q_values(const Eigen::MatrixXf& outputs) {
  // self(obs).mean(dim=1) over (batch, n_quantiles, n_actions): each action's quantiles are
  // the rows a, a + n_actions, ... of the output column.
  const int actions = n_actions(), quantiles = n_quantiles();
  q_mean_.setZero(actions, outputs.cols());
  for (Eigen::Index j = 0; j < outputs.cols(); ++j)
    for (int k = 0; k < quantiles; ++k)
      q_mean_.col(j) += outputs.col(j).segment(static_cast<Eigen::Index>(k) * actions, actions);
  q_mean_ /= static_cast<float>(quantiles);
  return q_mean_;
}

std::string QRDQN::export_q_values(PolicyGraph& graph, const std::string& outputs) const {
  // The mean over quantiles as one dense layer: weight 1 / n_quantiles from each action's rows.
  const int actions = n_actions(), quantiles = n_quantiles();
  Eigen::MatrixXf mean =
      Eigen::MatrixXf::Zero(actions, static_cast<Eigen::Index>(actions) * quantiles);
  for (int k = 0; k < quantiles; ++k)
    mean.middleCols(static_cast<Eigen::Index>(k) * actions, actions)
        .diagonal()
        .setConstant(1.0f / static_cast<float>(quantiles));
  return graph.dense(outputs, mean, Eigen::VectorXf::Zero(actions));
}

// sb3-contrib qrdqn/qrdqn.py QRDQN.train, one pass of its loop over gradient steps.
double QRDQN::train_on_batch(const ReplayBatch& b, float lr) {
  const Eigen::Index n = b.obs.cols();
  const int actions = n_actions(), quantiles = n_quantiles();
  const auto gamma = static_cast<float>(config_.off_policy.gamma);

  // with th.no_grad():
  //   next_quantiles = quantile_net_target(next_obs)                  (batch, K, n_actions)
  //   next_greedy_actions = next_quantiles.mean(dim=1).argmax(dim=2)  (first of ties)
  //   next_quantiles = next_quantiles.gather(dim=2, index=next_greedy_actions)
  //   target_quantiles = rewards + (1 - dones) * gamma * next_quantiles
  const Eigen::MatrixXf& next = target_outputs(b);
  const Eigen::MatrixXf& next_q = q_values(next);
  target_quantiles_.resize(quantiles, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::Index greedy = 0;
    for (Eigen::Index a = 1; a < actions; ++a)
      if (next_q(a, j) > next_q(greedy, j)) greedy = a;
    const float discount = (1.0f - b.dones(j)) * gamma;
    for (int k = 0; k < quantiles; ++k)
      target_quantiles_(k, j) =
          b.rewards(j) + discount * next(static_cast<Eigen::Index>(k) * actions + greedy, j);
  }

  // current_quantiles = th.gather(quantile_net(obs), dim=2, index=actions)   (batch, K)
  const Eigen::MatrixXf& out = online_outputs(b);
  current_quantiles_.resize(quantiles, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index a = buffer_action(b, j);
    for (int k = 0; k < quantiles; ++k)
      current_quantiles_(k, j) = out(static_cast<Eigen::Index>(k) * actions + a, j);
  }

  // loss = quantile_huber_loss(current, target, sum_over_quantiles=True): summed over the
  // current quantiles, averaged over the batch and the target quantiles.
  const float scale = 1.0f / (static_cast<float>(n) * static_cast<float>(quantiles));
  const double loss =
      quantile_huber_loss(current_quantiles_, target_quantiles_, scale, grad_current_, rho_);

  // loss.backward() through the gather: the gradient lands on the taken action's rows.
  grad_outputs_.setZero(out.rows(), n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Index a = buffer_action(b, j);
    for (int k = 0; k < quantiles; ++k)
      grad_outputs_(static_cast<Eigen::Index>(k) * actions + a, j) = grad_current_(k, j);
  }
  // optimizer.zero_grad(); loss.backward();
  // if max_grad_norm is not None: clip_grad_norm_(policy.parameters(), max_grad_norm)
  // optimizer.step()
  backward_and_step(grad_outputs_, lr, config_.max_grad_norm);
  return loss;
}

}  // namespace rlrun
