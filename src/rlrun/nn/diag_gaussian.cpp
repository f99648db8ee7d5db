#include "rlrun/nn/diag_gaussian.hpp"
#include "rlrun/nn/log_sqrt_2pi.hpp"

#include <cmath>
#include <stdexcept>

namespace rlrun {

void DiagGaussian::set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
                       const Eigen::Ref<const Eigen::VectorXf>& log_std) {
  if (mean.rows() != log_std.size()) {
    throw std::invalid_argument("DiagGaussian::set: mean rows != log_std size");
  }
  mean_ = mean;
  log_std_ = log_std;
  std_ = log_std_.array().exp().matrix();
  inv_var_ = (-2.0f * log_std_.array()).exp().matrix();
}

void DiagGaussian::log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                            Eigen::Ref<Eigen::RowVectorXf> out) const {
  const float constant = -log_std_.sum() - static_cast<float>(dim()) * kLogSqrt2Pi;
  for (Eigen::Index j = 0; j < batch(); ++j) {
    const auto diff = actions.col(j).array() - mean_.col(j).array();
    out(j) = -0.5f * (diff.square() * inv_var_.array()).sum() + constant;
  }
}

void DiagGaussian::entropy(Eigen::Ref<Eigen::RowVectorXf> out) const {
  out.setConstant(static_cast<float>(dim()) * (0.5f + kLogSqrt2Pi) + log_std_.sum());
}

void DiagGaussian::sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> out) const {
  for (Eigen::Index j = 0; j < batch(); ++j) {
    for (Eigen::Index i = 0; i < dim(); ++i) {
      out(i, j) = mean_(i, j) + std_(i) * static_cast<float>(rng.normal());
    }
  }
}

void DiagGaussian::mode(Eigen::Ref<Eigen::MatrixXf> out) const { out = mean_; }

void DiagGaussian::backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                            const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                            const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                            Eigen::MatrixXf& grad_mean, Eigen::VectorXf& grad_log_std) const {
  grad_mean.resize(dim(), batch());
  grad_log_std.setConstant(dim(), grad_entropy.sum() - grad_log_prob.sum());
  for (Eigen::Index j = 0; j < batch(); ++j) {
    const float glp = grad_log_prob(j);
    // z = (a - m) / s^2; dlogp/dm = z, dlogp/dlog_std = (a - m) z - 1 (the -1 is added above).
    auto gm = grad_mean.col(j).array();
    gm = (actions.col(j).array() - mean_.col(j).array()) * inv_var_.array();
    grad_log_std.array() += glp * gm * (actions.col(j).array() - mean_.col(j).array());
    gm *= glp;
  }
}

}  // namespace rlrun
