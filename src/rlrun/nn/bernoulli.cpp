#include "rlrun/nn/bernoulli.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun {

void Bernoulli::set_logits(const Eigen::Ref<const Eigen::MatrixXf>& logits) {
  if (logits.rows() == 0) throw std::invalid_argument("Bernoulli::set_logits: no bits");
  logits_ = logits;
  probs_.resize(logits.rows(), logits.cols());
  softplus_.resize(logits.rows(), logits.cols());
  for (Eigen::Index k = 0; k < logits_.size(); ++k) {
    const float z = logits_(k);
    // torch.sigmoid; exp of a negative argument never overflows.
    const float e = std::exp(-std::abs(z));
    probs_(k) = z >= 0.0f ? 1.0f / (1.0f + e) : e / (1.0f + e);
    softplus_(k) = std::max(z, 0.0f) + std::log1p(e);
  }
}

float Bernoulli::bit(float action) const {
  if (action != 0.0f && action != 1.0f)
    throw std::out_of_range("Bernoulli: action " + std::to_string(action) + " is not 0 or 1");
  return action;
}

void Bernoulli::log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                         Eigen::Ref<Eigen::RowVectorXf> out) const {
  for (Eigen::Index j = 0; j < batch(); ++j) {
    float sum = 0.0f;
    for (Eigen::Index i = 0; i < num_bits(); ++i)
      sum += bit(actions(i, j)) * logits_(i, j) - softplus_(i, j);
    out(j) = sum;
  }
}

void Bernoulli::entropy(Eigen::Ref<Eigen::RowVectorXf> out) const {
  out = (softplus_.array() - logits_.array() * probs_.array()).colwise().sum().matrix();
}

void Bernoulli::sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions) const {
  for (Eigen::Index j = 0; j < batch(); ++j)
    for (Eigen::Index i = 0; i < num_bits(); ++i)
      actions(i, j) = rng.uniform() < static_cast<double>(probs_(i, j)) ? 1.0f : 0.0f;
}

void Bernoulli::mode(Eigen::Ref<Eigen::MatrixXf> actions) const {
  actions = (probs_.array() > 0.5f).cast<float>().matrix();
}

void Bernoulli::backward(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                         const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                         const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                         Eigen::MatrixXf& grad_logits) const {
  grad_logits.resize(num_bits(), batch());
  for (Eigen::Index j = 0; j < batch(); ++j) {
    for (Eigen::Index i = 0; i < num_bits(); ++i) {
      const float p = probs_(i, j);
      grad_logits(i, j) = grad_log_prob(j) * (bit(actions(i, j)) - p) -
                          grad_entropy(j) * logits_(i, j) * p * (1.0f - p);
    }
  }
}

}  // namespace rlrun
