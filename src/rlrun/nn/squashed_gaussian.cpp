#include "rlrun/nn/squashed_gaussian.hpp"
#include "rlrun/nn/log_sqrt_2pi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rlrun {

void SquashedGaussian::clamp_log_std(const Eigen::Ref<const Eigen::MatrixXf>& raw,
                                     Eigen::Ref<Eigen::MatrixXf> out) {
  out = raw.cwiseMax(kLogStdMin).cwiseMin(kLogStdMax);
}

void SquashedGaussian::clamp_log_std_backward(const Eigen::Ref<const Eigen::MatrixXf>& raw,
                                              Eigen::Ref<Eigen::MatrixXf> grad) {
  grad =
      (raw.array() >= kLogStdMin && raw.array() <= kLogStdMax).select(grad.array(), 0.0f).matrix();
}

void SquashedGaussian::set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
                           const Eigen::Ref<const Eigen::MatrixXf>& log_std) {
  if (mean.rows() != log_std.rows() || mean.cols() != log_std.cols()) {
    throw std::invalid_argument("SquashedGaussian::set: mean and log_std shapes differ");
  }
  mean_ = mean;
  log_std_ = log_std;
  std_ = log_std_.array().exp().matrix();
}

void SquashedGaussian::sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions) {
  noise_.resize(dim(), batch());
  for (Eigen::Index j = 0; j < batch(); ++j) {
    for (Eigen::Index i = 0; i < dim(); ++i) noise_(i, j) = static_cast<float>(rng.normal());
  }
  actions_ = (mean_.array() + std_.array() * noise_.array()).tanh().matrix();
  actions = actions_;
}

void SquashedGaussian::sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& noise,
                                         Eigen::Ref<Eigen::MatrixXf> actions) {
  noise_ = noise;
  actions_ = (mean_.array() + std_.array() * noise_.array()).tanh().matrix();
  actions = actions_;
}

void SquashedGaussian::log_prob(Eigen::Ref<Eigen::RowVectorXf> out) const {
  // log N(u; m, s) with (u - m) / s = eps exactly: the stored noise, not a recomputed ratio.
  out = (-0.5f * noise_.array().square() - log_std_.array() - kLogSqrt2Pi -
         (1.0f - actions_.array().square() + kEpsilon).log())
            .colwise()
            .sum()
            .matrix();
}

void SquashedGaussian::log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                Eigen::Ref<Eigen::RowVectorXf> out) const {
  constexpr float kFloatEps = std::numeric_limits<float>::epsilon();
  for (Eigen::Index j = 0; j < batch(); ++j) {
    float sum = 0.0f;
    for (Eigen::Index i = 0; i < dim(); ++i) {
      const float a = actions(i, j);
      const float u = std::atanh(std::clamp(a, -1.0f + kFloatEps, 1.0f - kFloatEps));
      const float z = (u - mean_(i, j)) / std_(i, j);
      sum += -0.5f * z * z - log_std_(i, j) - kLogSqrt2Pi - std::log(1.0f - a * a + kEpsilon);
    }
    out(j) = sum;
  }
}

void SquashedGaussian::mode(Eigen::Ref<Eigen::MatrixXf> actions) const {
  actions = mean_.array().tanh().matrix();
}

void SquashedGaussian::backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                Eigen::MatrixXf& grad_mean, Eigen::MatrixXf& grad_log_std) const {
  const auto a = actions_.array();
  const auto one_minus_a2 = 1.0f - a.square();
  // dlogp/du per element, then scaled per column by dL/dlogp.
  grad_mean =
      (grad_actions.array() * one_minus_a2 +
       (2.0f * a * one_minus_a2 / (one_minus_a2 + kEpsilon)).rowwise() * grad_log_prob.array())
          .matrix();
  grad_log_std =
      (grad_mean.array() * std_.array() * noise_.array()).rowwise() - grad_log_prob.array();
}

}  // namespace rlrun
