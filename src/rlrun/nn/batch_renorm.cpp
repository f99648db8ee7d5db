#include "rlrun/nn/batch_renorm.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rlrun {

BatchRenorm::BatchRenorm(int features, const BatchRenormOptions& options)
    : options_(options),
      params_(2 * features),
      grads_(Eigen::VectorXf::Zero(2 * features)),
      ra_mean_(Eigen::VectorXf::Zero(features)),
      ra_var_(Eigen::VectorXf::Ones(features)) {
  if (features < 1) throw std::invalid_argument("BatchRenorm: features must be >= 1");
  params_.head(features).setOnes();
  params_.tail(features).setZero();
}

void BatchRenorm::copy_state_from(const BatchRenorm& other) {
  params_ = other.params_;
  ra_mean_ = other.ra_mean_;
  ra_var_ = other.ra_var_;
  steps_ = other.steps_;
}

void BatchRenorm::batch_statistics(const Eigen::Ref<const Eigen::MatrixXf>& x) {
  const auto n = static_cast<float>(x.cols());
  batch_mean_ = x.rowwise().sum() / n;
  // torch's x.var(dim=0): unbiased.
  batch_var_ = (x.colwise() - batch_mean_).array().square().rowwise().sum() / (n - 1.0f);
}

const Eigen::MatrixXf& BatchRenorm::forward(const Eigen::Ref<const Eigen::MatrixXf>& x,
                                            bool training) {
  const int nf = features();
  if (x.rows() != nf) throw std::invalid_argument("BatchRenorm: input has the wrong width");
  const float eps = options_.eps;
  last_training_ = training;
  if (training) {
    if (x.cols() < 2) throw std::invalid_argument("BatchRenorm: train mode needs a batch of 2+");
    batch_statistics(x);
    r_.setOnes(nf);
    d_.setZero(nf);
    // sb3-contrib: `if self.steps > self.warmup_steps` (renorm), else plain batch norm.
    if (steps_ > options_.warmup_steps) {
      for (int f = 0; f < nf; ++f) {
        const float running_std = std::sqrt(ra_var_(f) + eps);
        const float batch_std = std::sqrt(batch_var_(f) + eps);
        r_(f) = std::clamp(batch_std / running_std, 1.0f / kRMax, kRMax);
        d_(f) = std::clamp((batch_mean_(f) - ra_mean_(f)) / running_std, -kDMax, kDMax);
      }
    }
    mean_used_ = batch_mean_.array() - d_.array() * batch_var_.array().sqrt() / r_.array();
    inv_std_ = (batch_var_.array() / r_.array().square() + eps).sqrt().inverse();
    ra_mean_.array() += options_.momentum * (batch_mean_ - ra_mean_).array();
    ra_var_.array() += options_.momentum * (batch_var_ - ra_var_).array();
    ++steps_;
  } else {
    mean_used_ = ra_mean_;
    inv_std_ = (ra_var_.array() + eps).sqrt().inverse();
  }
  x_hat_ = ((x.colwise() - mean_used_).array().colwise() * inv_std_.array()).matrix();
  y_ = ((x_hat_.array().colwise() * scale().array()).colwise() + bias().array()).matrix();
  return y_;
}

// With s = sqrt(custom_var + eps), x_hat = (x - m) / s and g = scale * dL/dy:
//   dL/dm = -sum(g) / s,  dL/dv = -sum(g * x_hat) / (2 s^2)
//   dm/dx_j = 1/n - d / (2 r sqrt(var)) * dvar/dx_j,  dv/dx_j = dvar/dx_j / r^2,
//   dvar/dx_j = 2 (x_j - mean) / (n - 1)
// (warm-up: r = 1, d = 0, the batch-norm backward). Where var is 0, torch's sqrt backward
// multiplies 0 by inf; its limit 0 is taken instead (x_j - mean is 0 there).
void BatchRenorm::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_y, Eigen::MatrixXf& grad_x,
                           bool param_grads) {
  const int nf = features();
  const Eigen::Index n = grad_y.cols();
  sum_gy_ = grad_y.rowwise().sum();
  sum_gy_xhat_ = (grad_y.array() * x_hat_.array()).rowwise().sum();
  if (param_grads) {
    grads_.head(nf) += sum_gy_xhat_;
    grads_.tail(nf) += sum_gy_;
  }
  // grad_x = a * dL/dy + b * x_hat + c, per feature.
  a_ = scale().array() * inv_std_.array();
  b_.setZero(nf);
  c_.setZero(nf);
  if (last_training_) {
    for (int f = 0; f < nf; ++f) {
      const double scale = params_(f), inv_std = inv_std_(f);
      const double dm = -scale * sum_gy_(f) * inv_std;
      const double dv = -0.5 * scale * sum_gy_xhat_(f) * inv_std * inv_std;
      const double r = r_(f), var = batch_var_(f);
      const double cm = var > 0.0 ? -static_cast<double>(d_(f)) / (2.0 * r * std::sqrt(var)) : 0.0;
      const double per_centered = 2.0 / static_cast<double>(n - 1) * (dv / (r * r) + dm * cm);
      // x - mean = x_hat / inv_std + (custom_mean - mean).
      const double shift = static_cast<double>(mean_used_(f)) - batch_mean_(f);
      b_(f) = static_cast<float>(per_centered / inv_std);
      c_(f) = static_cast<float>(dm / static_cast<double>(n) + per_centered * shift);
    }
  }
  grad_x =
      ((grad_y.array().colwise() * a_.array() + x_hat_.array().colwise() * b_.array()).colwise() +
       c_.array())
          .matrix();
}

Eigen::VectorXf BatchRenorm::eval_scale() const {
  return scale().array() / (ra_var_.array() + options_.eps).sqrt();
}

Eigen::VectorXf BatchRenorm::eval_shift() const {
  return bias().array() - ra_mean_.array() * eval_scale().array();
}

void BatchRenorm::save(const std::string& prefix, TensorMap& tensors) const {
  tensors[prefix + ".scale"] = to_tensor(Eigen::VectorXf(scale()));
  tensors[prefix + ".bias"] = to_tensor(Eigen::VectorXf(bias()));
  tensors[prefix + ".ra_mean"] = to_tensor(ra_mean_);
  tensors[prefix + ".ra_var"] = to_tensor(ra_var_);
  tensors[prefix + ".steps"] = scalar_tensor<int64_t>(steps_);
}

void BatchRenorm::load(const std::string& prefix, const TensorMap& tensors) {
  const int nf = features();
  Eigen::VectorXf gamma(nf), beta(nf), mean(nf), var(nf);
  from_tensor(tensors, prefix + ".scale", gamma);
  from_tensor(tensors, prefix + ".bias", beta);
  from_tensor(tensors, prefix + ".ra_mean", mean);
  from_tensor(tensors, prefix + ".ra_var", var);
  const auto steps = scalar_from<int64_t>(tensors, prefix + ".steps");
  if (steps < 0) throw std::runtime_error("tensor '" + prefix + ".steps' is negative");
  if (!gamma.allFinite() || !beta.allFinite() || !mean.allFinite() || !var.allFinite() ||
      (var.array() < 0.0f).any())
    throw std::runtime_error("tensors '" + prefix +
                             ".*' hold non-finite values or a negative variance");
  params_ << gamma, beta;
  ra_mean_ = mean;
  ra_var_ = var;
  steps_ = steps;
}

}  // namespace rlrun
