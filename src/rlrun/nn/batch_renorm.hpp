#pragma once
// Batch Renormalization (Ioffe 2017, "Batch Renormalization: Towards Reducing Minibatch
// Dependence in Batch-Normalized Models", arXiv:1702.03275) exactly as sb3-contrib 2.4's
// BatchRenorm1d does it (sb3_contrib/common/torch_layers.py, itself from sbx's jax_layers.py),
// the layer CrossQ's networks put before every Linear (Bhatt et al. 2024, "CrossQ: Batch
// Normalization in Deep Reinforcement Learning for Greater Sample Efficiency and Simplicity",
// ICLR 2024, openreview.net/forum?id=PczQtTsTIX).
//
// Layout: one sample per column, features x batch. Per feature, in train mode:
//   mean, var = the batch's mean and UNBIASED variance (torch's x.var(dim=0))
//   while steps <= warmup_steps: plain batch norm, custom_mean = mean, custom_var = var;
//   after: r = clamp(sqrt(var + eps) / sqrt(ra_var + eps), 1/r_max, r_max)      (detached)
//          d = clamp((mean - ra_mean) / sqrt(ra_var + eps), -d_max, d_max)     (detached)
//          custom_mean = mean - d * sqrt(var) / r,  custom_var = var / r^2
//   ra_mean += momentum * (mean - ra_mean); ra_var += momentum * (var - ra_var); steps += 1
// and in eval mode custom_mean, custom_var = ra_mean, ra_var (nothing updated). Then
//   y = scale * (x - custom_mean) / sqrt(custom_var + eps) + bias.
// r_max = 3 and d_max = 5 are sb3-contrib's constants (no linear relaxation schedule, unlike
// the paper). The gradient flows through mean and var (not r, d) as torch's autograd takes it.
#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rlrun/core/tensor.hpp"
#include "rlrun/nn/param_block.hpp"

namespace rlrun {

// sb3-contrib CrossQPolicy's batch_norm_momentum, batch_norm_eps, renorm_warmup_steps.
struct BatchRenormOptions {
  float momentum = 0.01f;
  float eps = 0.001f;
  int64_t warmup_steps = 100000;
};

class BatchRenorm {
 public:
  static constexpr float kRMax = 3.0f;
  static constexpr float kDMax = 5.0f;

  BatchRenorm() = default;
  // scale 1, bias 0, ra_mean 0, ra_var 1, steps 0 (BatchRenorm.__init__).
  BatchRenorm(int features, const BatchRenormOptions& options);

  int features() const { return static_cast<int>(ra_mean_.size()); }
  const BatchRenormOptions& options() const { return options_; }
  // scale then bias, and their gradients (one optimizer block).
  Eigen::VectorXf& params() { return params_; }
  const Eigen::VectorXf& params() const { return params_; }
  const Eigen::VectorXf& grads() const { return grads_; }
  ParamBlock block() { return {params_.data(), grads_.data(), params_.size()}; }
  Eigen::Map<const Eigen::VectorXf> scale() const { return {params_.data(), features()}; }
  Eigen::Map<const Eigen::VectorXf> bias() const {
    return {params_.data() + features(), features()};
  }
  const Eigen::VectorXf& running_mean() const { return ra_mean_; }
  const Eigen::VectorXf& running_var() const { return ra_var_; }
  int64_t steps() const { return steps_; }
  // The same layer's parameters and running statistics (an acting copy's refresh).
  void copy_state_from(const BatchRenorm& other);

  // forward(x) in train mode (training: batch statistics, running statistics updated, kept
  // for backward) or eval mode (running statistics). Returns features x batch; train mode needs
  // a batch of at least 2 (the unbiased variance).
  const Eigen::MatrixXf& forward(const Eigen::Ref<const Eigen::MatrixXf>& x, bool training);
  const Eigen::MatrixXf& output() const { return y_; }
  // The last forward's per-feature normalisation as used: custom_mean and 1/sqrt(custom_var+eps).
  const Eigen::VectorXf& last_mean() const { return mean_used_; }
  const Eigen::VectorXf& last_inv_std() const { return inv_std_; }
  bool last_training() const { return last_training_; }

  // dL/dy of the last forward -> dL/dx (features x batch), and with param_grads dL/dscale,
  // dL/dbias ADDED to grads() (zero_grad() first for loss.backward() after
  // optimizer.zero_grad()).
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_y, Eigen::MatrixXf& grad_x,
                bool param_grads = true);
  void zero_grad() { grads_.setZero(); }

  // eval mode as an affine map y = a * x + c per feature (export: folded into the next Linear).
  Eigen::VectorXf eval_scale() const;
  Eigen::VectorXf eval_shift() const;

  // sb3-contrib's state_dict entries under `prefix` (e.g. critic.qf0.0): scale, bias, ra_mean,
  // ra_var (float32, features) and steps (int64 scalar).
  void save(const std::string& prefix, TensorMap& tensors) const;
  // Throws std::runtime_error for a missing or misshapen tensor, a negative step count or
  // non-finite statistics (a model file is data from anyone).
  void load(const std::string& prefix, const TensorMap& tensors);

 private:
  // The batch statistics of x into batch_mean_ and batch_var_.
  void batch_statistics(const Eigen::Ref<const Eigen::MatrixXf>& x);

  BatchRenormOptions options_;
  Eigen::VectorXf params_, grads_;  // [scale; bias]
  Eigen::VectorXf ra_mean_, ra_var_;
  int64_t steps_ = 0;
  // The last train-mode forward: batch statistics, the renorm factors (r = 1, d = 0 in warm-up)
  // and what was used; x_hat for the backward.
  bool last_training_ = false;
  Eigen::VectorXf batch_mean_, batch_var_, r_, d_, mean_used_, inv_std_;
  Eigen::MatrixXf x_hat_, y_;
  // Backward workspaces: per-feature sums and coefficients.
  Eigen::VectorXf sum_gy_, sum_gy_xhat_, a_, b_, c_;
};

}  // namespace rlrun
