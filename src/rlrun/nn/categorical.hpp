#pragma once
// Categorical distribution over n actions per column, parameterised by unnormalised logits
// (n x batch): SB3 CategoricalDistribution, i.e. torch.distributions.Categorical(logits=...).
// Actions are stored as integer-valued floats in a row vector (one per column), the way the
// rollout buffer keeps them.
#include <Eigen/Core>

#include "rlrun/rng.hpp"

namespace rlrun {

class Categorical {
 public:
  // Normalises with a max-shifted log-sum-exp per column (torch: logits - logits.logsumexp()) and
  // caches log-probabilities and probabilities. Buffers are reused for a repeated shape.
  void set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits);
  // With invalid-action masks (0/1, the logits' shape): sb3-contrib's MaskableCategorical
  // (nn/action_masking.hpp), the logits of masked actions -1e8 before normalising. Their
  // probability is set to exactly 0, as torch's exp(-1e8) is (Eigen's vectorised exp stops at
  // about -88, giving 1e-38), so they are never sampled and add nothing to the entropy.
  void set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                  const Eigen::Ref<const Eigen::MatrixXf>& masks);

  int num_actions() const { return static_cast<int>(log_probs_.rows()); }
  Eigen::Index batch() const { return log_probs_.cols(); }
  const Eigen::MatrixXf& log_probs() const { return log_probs_; }  // n x batch
  const Eigen::MatrixXf& probs() const { return probs_; }          // n x batch

  // out(j) = log p(actions(j) | column j). Throws std::out_of_range for an action outside [0, n).
  void log_prob(const Eigen::Ref<const Eigen::RowVectorXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out) const;
  // out(j) = -sum_i p_ij log p_ij (torch clamps log p to the lowest finite float so that
  // p = 0 entries contribute 0; we do the same).
  void entropy(Eigen::Ref<Eigen::RowVectorXf> out) const;
  // One draw per column by inverting the CDF with rng.uniform() (torch uses multinomial; the
  // law is the same, the stream is ours).
  void sample(Rng& rng, Eigen::Ref<Eigen::RowVectorXf> actions) const;
  // argmax per column, the first index on ties (torch.argmax on probs, SB3's mode()).
  void mode(Eigen::Ref<Eigen::RowVectorXf> actions) const;

  // grad_logits = d/dlogits sum_j (grad_log_prob(j) log p(a_j) + grad_entropy(j) H_j):
  //   d log p(a)/dz = onehot(a) - p,   dH/dz = -p (log p + H).
  // grad_logits is resized to n x batch if needed and overwritten.
  void backward(const Eigen::Ref<const Eigen::RowVectorXf>& actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                Eigen::MatrixXf& grad_logits) const;

 private:
  Eigen::Index action_index(float action) const;

  Eigen::MatrixXf log_probs_;
  Eigen::MatrixXf probs_;
  Eigen::MatrixXf masked_;  // the masked logits (set_logits with masks)
};

}  // namespace rlrun
