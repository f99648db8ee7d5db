#pragma once
// PPO's minibatch loss (stable_baselines3/ppo/ppo.py, train()) and its derivatives with respect
// to the policy outputs, so that the policy can backpropagate them:
//   loss = -mean(min(A r, A clip(r, 1-eps, 1+eps)))             (clipped surrogate)
//        + vf_coef * mean((R - V_pred)^2)                         (V_pred optionally clipped)
//        + ent_coef * (-mean(H))
// with r = exp(log_prob - old_log_prob). Advantages are normalised before (SB3 does it per
// minibatch, with torch's unbiased std).
#include <Eigen/Core>
#include <cstdint>
#include <optional>

namespace rlrun {

struct PpoLossInputs {
  const Eigen::RowVectorXf& values;        // V(s) of the current policy
  const Eigen::RowVectorXf& log_prob;      // log pi(a|s) of the current policy
  const Eigen::RowVectorXf& entropy;       // H(pi(.|s))
  const Eigen::RowVectorXf& old_log_prob;  // from the rollout
  const Eigen::RowVectorXf& old_values;    // from the rollout (for value clipping)
  const Eigen::RowVectorXf& advantages;    // already normalised if requested
  const Eigen::RowVectorXf& returns;
};

struct PpoLossTerms {
  double policy_loss = 0, value_loss = 0, entropy_loss = 0, loss = 0;
  double clip_fraction = 0, approx_kl = 0;  // approx_kl: mean((r - 1) - log r), Schulman's k3
};

// Writes dloss/dvalues, dloss/dlog_prob, dloss/dentropy (each 1 x batch, pre-sized).
PpoLossTerms ppo_loss(const PpoLossInputs& in, float clip_range, std::optional<float> clip_range_vf,
                      float ent_coef, float vf_coef, Eigen::RowVectorXf& grad_values,
                      Eigen::RowVectorXf& grad_log_prob, Eigen::RowVectorXf& grad_entropy);

// In place: (a - mean) / (std + 1e-8) with the unbiased std, as torch's .std() in SB3.
void normalize_advantages(Eigen::RowVectorXf& advantages);

// What SB3's PPO.train (and sb3-contrib's MaskablePPO.train) logs: the minibatches' mean
// losses and clip fraction, the mean approx_kl of the last epoch run, the last minibatch's loss.
struct PpoTrainStatistics {
  double entropy_loss_sum = 0, pg_loss_sum = 0, value_loss_sum = 0, clip_fraction_sum = 0;
  int n_minibatches = 0;
  double last_loss = 0, approx_kl_sum = 0;
  int approx_kl_count = 0;

  void start_epoch() {
    approx_kl_sum = 0;
    approx_kl_count = 0;
  }
  void add(const PpoLossTerms& t) {
    pg_loss_sum += t.policy_loss;
    value_loss_sum += t.value_loss;
    entropy_loss_sum += t.entropy_loss;
    clip_fraction_sum += t.clip_fraction;
    approx_kl_sum += t.approx_kl;
    ++approx_kl_count;
    ++n_minibatches;
    last_loss = t.loss;
  }
};

// SB3's PPO.train logs (and sb3-contrib's MaskablePPO and RecurrentPPO, the same keys): the
// statistics' means, train/explained_variance of the rollout, train/std of a Gaussian policy,
// n_updates, the clip ranges and the learning rate.
struct RolloutBuffer;
class ActorCriticPolicy;
class Logger;
void record_ppo_statistics(Logger& logger, const PpoTrainStatistics& statistics,
                           const RolloutBuffer& rollout, const ActorCriticPolicy& policy,
                           int64_t n_updates, float lr, float clip_range,
                           std::optional<float> clip_range_vf);

}  // namespace rlrun
