#include "rlrun/nn/state_dependent_noise.hpp"
#include "rlrun/nn/log_sqrt_2pi.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rlrun {

namespace {
// TanhBijector.inverse clamps to [-1 + eps, 1 - eps] with th.finfo(float32).eps.
constexpr float kFloatEps = std::numeric_limits<float>::epsilon();

// TanhBijector.atanh: 0.5 * (log1p(x) - log1p(-x)), as torch evaluates it.
float atanh_as_torch(float x) { return 0.5f * (std::log1p(x) - std::log1p(-x)); }
}  // namespace

StateDependentNoise::StateDependentNoise(int latent_dim, int action_dim, float log_std_init,
                                         const StateDependentNoiseOptions& options)
    : options_(options), action_dim_(action_dim) {
  if (latent_dim <= 0 || action_dim <= 0)
    throw std::invalid_argument("StateDependentNoise: sizes must be positive, got latent " +
                                std::to_string(latent_dim) + ", action " +
                                std::to_string(action_dim));
  const int cols = options.full_std ? action_dim : 1;
  log_std_ = Eigen::MatrixXf::Constant(latent_dim, cols, log_std_init);
  log_std_grad_ = Eigen::MatrixXf::Zero(latent_dim, cols);
}

void StateDependentNoise::std_matrix(Eigen::MatrixXf& out) const {
  out.resize(latent_dim(), action_dim_);
  for (Eigen::Index k = 0; k < log_std_.rows(); ++k) {
    for (Eigen::Index c = 0; c < log_std_.cols(); ++c) {
      const float x = log_std_(k, c);
      float s;
      if (options_.use_expln) {
        // expln (gSDE paper, SB3 get_std): exp below 0, log1p(x + eps) + 1 above, so the std
        // keeps above zero and grows only logarithmically.
        s = x <= 0.0f ? std::exp(x) : std::log1p(x + kEpsilon) + 1.0f;
      } else {
        s = std::exp(x);
      }
      if (options_.full_std) {
        out(k, c) = s;
      } else {
        out.row(k).setConstant(s);  // th.ones(latent_sde_dim, action_dim) * std
      }
    }
  }
}

void StateDependentNoise::std_derivative(Eigen::MatrixXf& out) const {
  out.resize(log_std_.rows(), log_std_.cols());
  for (Eigen::Index k = 0; k < log_std_.size(); ++k) {
    const float x = log_std_.data()[k];
    // expln's branches: d exp(x) = exp(x) for x <= 0, d log1p(x + eps) = 1 / (1 + x + eps) above
    // (torch's masks pass the gradient of the active branch only).
    out.data()[k] = options_.use_expln && x > 0.0f ? 1.0f / (1.0f + x + kEpsilon) : std::exp(x);
  }
}

double StateDependentNoise::mean_std() const {
  Eigen::MatrixXf s;
  std_matrix(s);
  return static_cast<double>(s.mean());
}

void StateDependentNoise::sample_weights(Rng& rng, int batch_size) {
  if (batch_size < 1)
    throw std::invalid_argument("StateDependentNoise::sample_weights: batch_size must be >= 1");
  const int latent = latent_dim();
  eps_mat_.resize(latent, action_dim_);
  eps_matrices_.resize(latent, static_cast<Eigen::Index>(action_dim_) * batch_size);
  // weights_dist.rsample() then rsample((batch_size,)): row-major draws, as torch fills them.
  for (int k = 0; k < latent; ++k)
    for (int i = 0; i < action_dim_; ++i) eps_mat_(k, i) = static_cast<float>(rng.normal());
  for (int b = 0; b < batch_size; ++b)
    for (int k = 0; k < latent; ++k)
      for (int i = 0; i < action_dim_; ++i)
        eps_matrices_(k, b * action_dim_ + i) = static_cast<float>(rng.normal());
  set_weights(eps_mat_, eps_matrices_);
}

void StateDependentNoise::set_weights(const Eigen::Ref<const Eigen::MatrixXf>& eps_mat,
                                      const Eigen::Ref<const Eigen::MatrixXf>& eps_matrices) {
  if (eps_mat.rows() != latent_dim() || eps_mat.cols() != action_dim_ ||
      eps_matrices.rows() != latent_dim() || eps_matrices.cols() % action_dim_ != 0 ||
      eps_matrices.cols() == 0)
    throw std::invalid_argument("StateDependentNoise::set_weights: shapes do not fit");
  if (eps_mat.data() != eps_mat_.data()) eps_mat_ = eps_mat;
  if (eps_matrices.data() != eps_matrices_.data()) eps_matrices_ = eps_matrices;
  std_matrix(std_);
  // Normal(zeros_like(std), std).rsample() = std * eps.
  exploration_mat_ = std_.cwiseProduct(eps_mat_);
  exploration_matrices_.resize(eps_matrices_.rows(), eps_matrices_.cols());
  const int n = num_exploration_matrices();
  for (int b = 0; b < n; ++b)
    exploration_matrices_.middleCols(b * action_dim_, action_dim_) =
        std_.cwiseProduct(eps_matrices_.middleCols(b * action_dim_, action_dim_));
}

void StateDependentNoise::restore_weights(
    const Eigen::Ref<const Eigen::MatrixXf>& eps_mat,
    const Eigen::Ref<const Eigen::MatrixXf>& eps_matrices,
    const Eigen::Ref<const Eigen::MatrixXf>& exploration_mat,
    const Eigen::Ref<const Eigen::MatrixXf>& exploration_matrices) {
  if (exploration_mat.rows() != eps_mat.rows() || exploration_mat.cols() != eps_mat.cols() ||
      exploration_matrices.rows() != eps_matrices.rows() ||
      exploration_matrices.cols() != eps_matrices.cols())
    throw std::invalid_argument("StateDependentNoise::restore_weights: shapes do not fit");
  set_weights(eps_mat, eps_matrices);  // checks the shapes
  exploration_mat_ = exploration_mat;
  exploration_matrices_ = exploration_matrices;
}

int StateDependentNoise::num_exploration_matrices() const {
  return action_dim_ == 0 ? 0 : static_cast<int>(exploration_matrices_.cols() / action_dim_);
}

bool StateDependentNoise::batched_noise(Eigen::Index n) const {
  // get_noise: "if len(latent_sde) == 1 or len(latent_sde) != len(exploration_matrices)": mm.
  return n != 1 && n == num_exploration_matrices();
}

void StateDependentNoise::set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
                              const Eigen::Ref<const Eigen::MatrixXf>& latent) {
  if (mean.rows() != action_dim_ || latent.rows() != latent_dim() || mean.cols() != latent.cols())
    throw std::invalid_argument("StateDependentNoise::set: mean is " + std::to_string(mean.rows()) +
                                "x" + std::to_string(mean.cols()) + ", latent " +
                                std::to_string(latent.rows()) + "x" +
                                std::to_string(latent.cols()));
  mean_ = mean;
  latent_ = latent;
  std_matrix(std_);
  std_sq_ = std_.array().square().matrix();
  latent_sq_ = latent_.array().square().matrix();
  // variance = th.mm(latent_sde ** 2, get_std(log_std) ** 2); Normal(mean, sqrt(variance + eps)).
  sigma_.resize(action_dim_, mean.cols());
  sigma_.noalias() = std_sq_.transpose() * latent_sq_;
  sigma_ = (sigma_.array() + kEpsilon).sqrt().matrix();
}

void StateDependentNoise::noise(Eigen::Ref<Eigen::MatrixXf> out) const {
  if (exploration_mat_.size() == 0)
    throw std::logic_error("StateDependentNoise: no exploration matrix (call sample_weights)");
  if (batched_noise(latent_.cols())) {
    // th.bmm(latent_sde.unsqueeze(1), exploration_matrices): env j uses its own matrix.
    for (Eigen::Index j = 0; j < latent_.cols(); ++j)
      out.col(j).noalias() =
          exploration_matrices_.middleCols(j * action_dim_, action_dim_).transpose() *
          latent_.col(j);
  } else {
    out.noalias() = exploration_mat_.transpose() * latent_;
  }
}

void StateDependentNoise::sample(Eigen::Ref<Eigen::MatrixXf> actions) {
  pre_squash_.resize(action_dim_, batch());
  noise(pre_squash_);
  pre_squash_ += mean_;
  if (options_.squash_output)
    sampled_ = pre_squash_.array().tanh().matrix();
  else
    sampled_ = pre_squash_;
  actions = sampled_;
}

void StateDependentNoise::mode(Eigen::Ref<Eigen::MatrixXf> actions) const {
  if (options_.squash_output)
    actions = mean_.array().tanh().matrix();
  else
    actions = mean_;
}

float StateDependentNoise::inverse_tanh(float action) {
  return atanh_as_torch(std::clamp(action, -1.0f + kFloatEps, 1.0f - kFloatEps));
}

void StateDependentNoise::log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                   Eigen::Ref<Eigen::RowVectorXf> out) const {
  for (Eigen::Index j = 0; j < batch(); ++j) {
    float gaussian = 0.0f, correction = 0.0f;
    for (Eigen::Index i = 0; i < action_dim_; ++i) {
      const float g = options_.squash_output ? inverse_tanh(actions(i, j)) : actions(i, j);
      const float s = sigma_(i, j);
      const float z = g - mean_(i, j);
      gaussian += -(z * z) / (2.0f * s * s) - std::log(s) - kLogSqrt2Pi;
      if (options_.squash_output) {
        const float t = std::tanh(g);
        correction += std::log(1.0f - t * t + kEpsilon);
      }
    }
    out(j) = gaussian - correction;
  }
}

void StateDependentNoise::entropy(Eigen::Ref<Eigen::RowVectorXf> out) const {
  if (options_.squash_output)
    throw std::logic_error("StateDependentNoise: no analytic entropy with squash_output");
  for (Eigen::Index j = 0; j < batch(); ++j)
    out(j) =
        static_cast<float>(action_dim_) * (0.5f + kLogSqrt2Pi) + sigma_.col(j).array().log().sum();
}

void StateDependentNoise::backward_scored(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                                          const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                                          const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                                          Eigen::MatrixXf& grad_mean,
                                          Eigen::MatrixXf* grad_latent) {
  const Eigen::Index n = batch();
  grad_mean.resize(action_dim_, n);
  grad_var_.resize(action_dim_, n);
  const bool with_entropy = !options_.squash_output;
  for (Eigen::Index j = 0; j < n; ++j) {
    const float glp = grad_log_prob(j);
    const float gent = with_entropy ? grad_entropy(j) : 0.0f;
    for (Eigen::Index i = 0; i < action_dim_; ++i) {
      const float g = options_.squash_output ? inverse_tanh(actions(i, j)) : actions(i, j);
      const float v = sigma_(i, j) * sigma_(i, j);
      const float z = g - mean_(i, j);
      // log N = -z^2 / (2 v) - log(v) / 2 - c and entropy = log(v) / 2 + c, v = variance + eps.
      grad_mean(i, j) = glp * z / v;
      grad_var_(i, j) = (glp * (z * z / v - 1.0f) + gent) / (2.0f * v);
    }
  }
  backward_std(grad_var_, nullptr, grad_latent);
}

void StateDependentNoise::backward_sampled(
    const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
    const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob, Eigen::MatrixXf& grad_mean,
    Eigen::MatrixXf* grad_latent) {
  const Eigen::Index n = batch();
  if (sampled_.cols() != n || grad_actions.cols() != n)
    throw std::logic_error("StateDependentNoise::backward_sampled: no matching sample()");
  grad_mean.resize(action_dim_, n);
  grad_var_.resize(action_dim_, n);
  grad_u_.resize(action_dim_, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const float glp = grad_log_prob(j);
    for (Eigen::Index i = 0; i < action_dim_; ++i) {
      const float m = mean_(i, j);
      const float v = sigma_(i, j) * sigma_(i, j);
      const float a = sampled_(i, j);
      float g, grad_u;
      if (options_.squash_output) {
        // log_prob re-derives g = atanh(clamp(tanh(u))) from the action, so the path to u runs
        // through tanh, the clamp (no gradient outside [-1 + eps, 1 - eps]) and atanh, and the
        // squash correction log(1 - tanh(g)^2 + eps) is a function of g.
        const bool inside = a >= -1.0f + kFloatEps && a <= 1.0f - kFloatEps;
        const float c = std::clamp(a, -1.0f + kFloatEps, 1.0f - kFloatEps);
        g = atanh_as_torch(c);
        const float t = std::tanh(g);
        const float one_minus_t2 = 1.0f - t * t;
        const float grad_g =
            glp * (-(g - m) / v + 2.0f * t * one_minus_t2 / (one_minus_t2 + kEpsilon));
        const float one_minus_a2 = 1.0f - a * a;
        const float dg_du =
            inside ? one_minus_a2 * 0.5f * (1.0f / (1.0f + c) + 1.0f / (1.0f - c)) : 0.0f;
        grad_u = grad_g * dg_du + grad_actions(i, j) * one_minus_a2;
      } else {
        g = a;  // the action is u itself
        grad_u = glp * (-(g - m) / v) + grad_actions(i, j);
      }
      const float z = g - m;
      grad_u_(i, j) = grad_u;  // u = mean + noise: also dL/dnoise
      grad_mean(i, j) = grad_u + glp * z / v;
      grad_var_(i, j) = glp * (z * z / v - 1.0f) / (2.0f * v);
    }
  }
  backward_std(grad_var_, &grad_u_, grad_latent);
}

void StateDependentNoise::variance_tangent(const Eigen::Ref<const Eigen::MatrixXf>& d_log_std,
                                           Eigen::MatrixXf& d_variance) const {
  // variance(i, j) = sum_k s(k, j)^2 std(k, i)^2, std(k, i) = get_std(log_std(k, c(i))) with
  // c(i) = i (full_std) or 0: d variance(i, j) = sum_k s(k, j)^2 2 std(k, i) std'(k, c(i))
  // d log_std(k, c(i)).
  Eigen::MatrixXf factor;
  std_derivative(factor);
  Eigen::MatrixXf d_std_sq(latent_dim(), action_dim_);
  for (Eigen::Index i = 0; i < action_dim_; ++i) {
    const Eigen::Index c = options_.full_std ? i : 0;
    d_std_sq.col(i) =
        (2.0f * std_.col(i).array() * factor.col(c).array() * d_log_std.col(c).array()).matrix();
  }
  d_variance.noalias() = d_std_sq.transpose() * latent_sq_;
}

void StateDependentNoise::backward_std(const Eigen::MatrixXf& grad_var,
                                       const Eigen::MatrixXf* grad_noise,
                                       Eigen::MatrixXf* grad_latent) {
  const Eigen::Index n = grad_var.cols();
  const bool to_latent = options_.learn_features && grad_latent != nullptr;
  // variance(i, j) = sum_k s(k, j)^2 std(k, i)^2:
  //   dL/dstd(k, i) = 2 std(k, i) sum_j s(k, j)^2 dL/dvariance(i, j)
  //   dL/ds(k, j)   = 2 s(k, j) sum_i std(k, i)^2 dL/dvariance(i, j)
  grad_std_.resize(latent_dim(), action_dim_);
  grad_std_.noalias() = latent_sq_ * grad_var.transpose();
  grad_std_ = (2.0f * grad_std_.array() * std_.array()).matrix();
  if (to_latent) {
    latent_term_.resize(latent_dim(), n);
    latent_term_.noalias() = std_sq_ * grad_var;
    *grad_latent = (2.0f * latent_.array() * latent_term_.array()).matrix();
  }
  if (grad_noise != nullptr) {
    // noise = E^T s with E = std * eps: dL/dE = s (dL/dnoise)^T, dL/dstd += dL/dE * eps,
    // dL/ds += E dL/dnoise; per column with its own matrix in the batched case.
    if (batched_noise(n)) {
      for (Eigen::Index j = 0; j < n; ++j) {
        const Eigen::Index first = j * action_dim_;
        for (Eigen::Index i = 0; i < action_dim_; ++i)
          grad_std_.col(i).array() +=
              latent_.col(j).array() * (*grad_noise)(i, j) * eps_matrices_.col(first + i).array();
        if (to_latent)
          grad_latent->col(j).noalias() +=
              exploration_matrices_.middleCols(j * action_dim_, action_dim_) * grad_noise->col(j);
      }
    } else {
      latent_term_.resize(latent_dim(), action_dim_);
      latent_term_.noalias() = latent_ * grad_noise->transpose();
      grad_std_.array() += latent_term_.array() * eps_mat_.array();
      if (to_latent) grad_latent->noalias() += exploration_mat_ * *grad_noise;
    }
  }
  // Through get_std into log_std (summed over the actions when one std serves them all).
  std_derivative(std_grad_factor_);
  if (options_.full_std) {
    log_std_grad_.array() += grad_std_.array() * std_grad_factor_.array();
  } else {
    log_std_grad_.col(0).array() +=
        grad_std_.rowwise().sum().array() * std_grad_factor_.col(0).array();
  }
}

}  // namespace rlrun
