#pragma once
// Diagonal Gaussian with a state-independent log standard deviation: SB3
// DiagGaussianDistribution (common/distributions.py), used by PPO/A2C for Box actions. The mean
// comes from the network (d x batch), log_std is one learnable vector (d), shared by all columns.
// log_prob and entropy are summed over the d action dimensions (sum_independent_dims).
#include <Eigen/Core>

#include "rlrun/rng.hpp"

namespace rlrun {

class DiagGaussian {
 public:
  // Copies mean and log_std (buffers reused for a repeated shape).
  void set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
           const Eigen::Ref<const Eigen::VectorXf>& log_std);

  Eigen::Index dim() const { return mean_.rows(); }
  Eigen::Index batch() const { return mean_.cols(); }
  const Eigen::MatrixXf& mean() const { return mean_; }
  const Eigen::VectorXf& log_std() const { return log_std_; }
  const Eigen::VectorXf& std() const { return std_; }

  // out(j) = sum_i log N(actions(i, j); mean(i, j), exp(log_std(i))), with torch's Normal
  // formula -(a - m)^2 / (2 s^2) - log s - log sqrt(2 pi).
  void log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out) const;
  // out(j) = sum_i (0.5 + 0.5 log(2 pi) + log_std(i)); the same for every column.
  void entropy(Eigen::Ref<Eigen::RowVectorXf> out) const;
  // out = mean + std * eps, eps ~ N(0, 1) drawn column by column from rng.
  void sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> out) const;
  // out = mean (SB3 mode(), used for deterministic actions).
  void mode(Eigen::Ref<Eigen::MatrixXf> out) const;

  // Gradients of L = sum_j (grad_log_prob(j) log_prob_j + grad_entropy(j) entropy_j):
  //   dL/dmean(i,j)  = grad_log_prob(j) (a - m) / s^2                      (written, d x batch)
  //   dL/dlog_std(i) = sum_j grad_log_prob(j) ((a - m)^2 / s^2 - 1) + grad_entropy(j)
  // Both outputs are resized if needed and overwritten (not accumulated).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                Eigen::MatrixXf& grad_mean, Eigen::VectorXf& grad_log_std) const;

 private:
  Eigen::MatrixXf mean_;
  Eigen::VectorXf log_std_;
  Eigen::VectorXf std_;
  Eigen::VectorXf inv_var_;  // 1 / s^2
};

}  // namespace rlrun
