#pragma once
// Independent Bernoulli bits for a MultiBinary(n) action: SB3 BernoulliDistribution
// (stable_baselines3/common/distributions.py), i.e. torch.distributions.Bernoulli(logits=z)
// with log_prob and entropy summed over the n bits. The network outputs n logits per column;
// actions are (n x batch) floats 0 or 1.
//   log p(a | z) = a z - softplus(z)            (torch: -binary_cross_entropy_with_logits)
//   H(z)         = softplus(z) - z sigmoid(z)   (torch: binary_cross_entropy_with_logits(z, p))
// with softplus(z) = max(z, 0) + log1p(exp(-|z|)), stable for any z.
#include <Eigen/Core>

#include "rlrun/rng.hpp"

namespace rlrun {

class Bernoulli {
 public:
  // Caches the probabilities sigmoid(z) and softplus(z) (n x batch; buffers reused).
  void set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits);

  Eigen::Index num_bits() const { return logits_.rows(); }
  Eigen::Index batch() const { return logits_.cols(); }
  const Eigen::MatrixXf& probs() const { return probs_; }

  // out(j) = sum_i log p(actions(i, j)). Throws std::out_of_range for a value other than 0 or 1.
  void log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out) const;
  // out(j) = sum_i H(z_ij).
  void entropy(Eigen::Ref<Eigen::RowVectorXf> out) const;
  // a = 1 when rng.uniform() < p (torch.bernoulli's law; the stream is ours), bit by bit,
  // column by column.
  void sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions) const;
  // round(p): 1 when p > 0.5 (torch.round rounds 0.5 to the even 0), i.e. when z > 0 up to the
  // rounding of sigmoid near 0.5 (SB3 mode()).
  void mode(Eigen::Ref<Eigen::MatrixXf> actions) const;

  // grad_logits = d/dz sum_j (grad_log_prob(j) log p(a_j) + grad_entropy(j) H_j):
  //   d log p(a)/dz = a - p,   dH/dz = -z p (1 - p).
  // grad_logits is resized to n x batch if needed and overwritten.
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                Eigen::MatrixXf& grad_logits) const;

 private:
  float bit(float action) const;

  Eigen::MatrixXf logits_, probs_, softplus_;
};

}  // namespace rlrun
