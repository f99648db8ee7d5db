#include "rlrun/nn/categorical.hpp"

#include "rlrun/nn/action_masking.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rlrun {

namespace {
// torch.distributions.Categorical.entropy clamps logits at finfo.min before p * log p.
constexpr float kLowest = std::numeric_limits<float>::lowest();
}  // namespace

void Categorical::set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits) {
  const Eigen::Index n = logits.rows();
  const Eigen::Index batch = logits.cols();
  if (n == 0) throw std::invalid_argument("Categorical::set_logits: no actions");
  log_probs_.resize(n, batch);
  probs_.resize(n, batch);
  for (Eigen::Index j = 0; j < batch; ++j) {
    const auto z = logits.col(j);
    const float max = z.maxCoeff();
    auto shifted = log_probs_.col(j);
    shifted = z.array() - max;
    const float lse = std::log(shifted.array().exp().sum());
    shifted.array() -= lse;
    probs_.col(j) = shifted.array().exp().matrix();
  }
}

void Categorical::set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits,
                             const Eigen::Ref<const Eigen::MatrixXf>& masks) {
  mask_logits(logits, masks, masked_);
  set_logits(masked_);
  probs_ = (masks.array() != 0.0f).select(probs_, 0.0f);
}

Eigen::Index Categorical::action_index(float action) const {
  const auto index = static_cast<Eigen::Index>(action);
  if (!(action >= 0.0f) || index >= log_probs_.rows() || static_cast<float>(index) != action) {
    throw std::out_of_range("Categorical: action " + std::to_string(action) +
                            " is not an integer in [0, " + std::to_string(log_probs_.rows()) + ")");
  }
  return index;
}

void Categorical::log_prob(const Eigen::Ref<const Eigen::RowVectorXf>& actions,
                           Eigen::Ref<Eigen::RowVectorXf> out) const {
  for (Eigen::Index j = 0; j < batch(); ++j) out(j) = log_probs_(action_index(actions(j)), j);
}

void Categorical::entropy(Eigen::Ref<Eigen::RowVectorXf> out) const {
  out = -(probs_.array() * log_probs_.array().max(kLowest)).colwise().sum().matrix();
}

void Categorical::sample(Rng& rng, Eigen::Ref<Eigen::RowVectorXf> actions) const {
  const Eigen::Index n = log_probs_.rows();
  for (Eigen::Index j = 0; j < batch(); ++j) {
    // Inverse CDF in double. If rounding leaves u above the last partial sum, the last action
    // with non-zero probability is taken, never one with p = 0.
    const double u = rng.uniform();
    double cumulative = 0.0;
    Eigen::Index chosen = -1;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double p = probs_(i, j);
      if (p <= 0.0) continue;
      chosen = i;
      cumulative += p;
      if (u < cumulative) break;
    }
    actions(j) = static_cast<float>(chosen < 0 ? 0 : chosen);
  }
}

void Categorical::mode(Eigen::Ref<Eigen::RowVectorXf> actions) const {
  for (Eigen::Index j = 0; j < batch(); ++j) {
    Eigen::Index best = 0;
    // Strict '>' keeps the first maximum, like torch.argmax. Compare log-probs (exact ties stay
    // ties, tiny probabilities don't underflow to equal zeros).
    for (Eigen::Index i = 1; i < log_probs_.rows(); ++i) {
      if (log_probs_(i, j) > log_probs_(best, j)) best = i;
    }
    actions(j) = static_cast<float>(best);
  }
}

void Categorical::backward(const Eigen::Ref<const Eigen::RowVectorXf>& actions,
                           const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                           const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                           Eigen::MatrixXf& grad_logits) const {
  grad_logits.resize(log_probs_.rows(), batch());
  for (Eigen::Index j = 0; j < batch(); ++j) {
    const auto p = probs_.col(j).array();
    const auto logp = log_probs_.col(j).array().max(kLowest);
    const float h = -(p * logp).sum();
    const float glp = grad_log_prob(j);
    const float gent = grad_entropy(j);
    auto g = grad_logits.col(j).array();
    g = -glp * p - gent * p * (logp + h);
    g(action_index(actions(j))) += glp;
  }
}

}  // namespace rlrun
