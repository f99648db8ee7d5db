// What TRPO (algos/trpo/trpo.cpp) needs of an ActorCriticPolicy beyond PPO's: the actor's
// parameters as one vector, the old distribution, the mean KL divergence to it and exact
// Fisher-vector products.
//
// sb3-contrib 2.4 (trpo/trpo.py) gets F v by double backward through kl_div =
// kl_divergence(new, old).mean() at new = old. There the KL's gradient in the distribution's
// parameters is zero, so its Hessian in the network's parameters is exactly J^T M J: J the
// Jacobian of the distribution's parameters (logits, means, log-stds), M the Hessian of the KL
// in them, i.e. the distribution's Fisher information (Amari 1998; Martens 2020, "New insights
// and perspectives on the natural gradient method", JMLR 21). Here J v is a forward-mode pass
// (Mlp::jvp), M is written out per distribution and J^T by the ordinary backward pass:
//   categorical (logits z, probs p): M u = p * u - p (p . u)
//   Bernoulli (logit z, prob p):     M u = p (1 - p) u
//   Normal (mean m, std s):          M = 1 / s^2 for m; 2 for log s (a state-independent
//                                    log_std); 1 / (2 s^4) for the variance (gSDE's)
// and everything is divided by what .mean() divides by: the samples for categoricals (torch's
// KL of a Categorical is per sample, SB3 sums a MultiDiscrete's parts), the samples times the
// action entries for Bernoulli and Normal (torch's KL is per entry there).
#include <cmath>
#include <stdexcept>

#include "rlrun/algos/common/actor_critic_policy.hpp"

namespace rlrun {

namespace {

// log_softmax of rows [first, first + size) of column j, in double.
void log_softmax(const Eigen::MatrixXf& logits, Eigen::Index first, Eigen::Index size,
                 Eigen::Index j, Eigen::VectorXd& out) {
  out = logits.col(j).segment(first, size).cast<double>();
  const double max = out.maxCoeff();
  out.array() -= max + std::log((out.array() - max).exp().sum());
}

// log(sigmoid(x)) without overflow.
double log_sigmoid(double x) {
  return x >= 0 ? -std::log1p(std::exp(-x)) : x - std::log1p(std::exp(x));
}

}  // namespace

Eigen::Index ActorCriticPolicy::actor_param_count() const {
  if (extractor_.learned())
    throw std::logic_error("ActorCriticPolicy: TRPO's actor vector has no learned extractor");
  Eigen::Index n = actor_.num_params();
  if (head_ == Head::kDiagGaussian) n += log_std_.size();
  if (use_sde()) n += sde_.log_std().size();
  return n;
}

void ActorCriticPolicy::get_actor_params(Eigen::VectorXf& theta) const {
  theta.resize(actor_param_count());
  theta.head(actor_.num_params()) = actor_.params();
  if (head_ == Head::kDiagGaussian) theta.tail(log_std_.size()) = log_std_;
  if (use_sde()) theta.tail(sde_.log_std().size()) = sde_.log_std().reshaped();
}

void ActorCriticPolicy::set_actor_params(const Eigen::VectorXf& theta) {
  if (theta.size() != actor_param_count())
    throw std::invalid_argument("ActorCriticPolicy::set_actor_params: wrong size");
  actor_.params() = theta.head(actor_.num_params());
  if (head_ == Head::kDiagGaussian) log_std_ = theta.tail(log_std_.size());
  if (use_sde()) sde_.log_std().reshaped() = theta.tail(sde_.log_std().size());
}

void ActorCriticPolicy::get_actor_grads(Eigen::VectorXf& grad) const {
  grad.resize(actor_param_count());
  grad.head(actor_.num_params()) = actor_.grads();
  if (head_ == Head::kDiagGaussian) grad.tail(log_std_grad_.size()) = log_std_grad_;
  if (use_sde()) grad.tail(sde_.log_std_grad().size()) = sde_.log_std_grad().reshaped();
}

ActionDistributionParams ActorCriticPolicy::distribution() const {
  return {actor_.output(), gaussian_sigma()};
}

Eigen::MatrixXf ActorCriticPolicy::gaussian_sigma() const {
  if (head_ == Head::kDiagGaussian)
    return log_std_.array().exp().matrix().replicate(1, actor_.output().cols());
  if (use_sde()) return sde_.sigma();
  return {};
}

std::vector<int64_t> ActorCriticPolicy::categorical_part_sizes() const {
  return head_ == Head::kCategorical ? std::vector<int64_t>{actor_.output().rows()}
                                     : categorical_parts_;
}

double ActorCriticPolicy::mean_kl(const ActionDistributionParams& old) const {
  const ActionDistributionParams now = distribution();
  const Eigen::Index n = now.head.cols();
  double sum = 0.0;
  if (gaussian()) {
    // torch _kl_normal_normal: (r + ((m_p - m_q) / s_q)^2 - 1 - log r) / 2, r = (s_p / s_q)^2.
    const Eigen::ArrayXXd r =
        (now.sigma.cast<double>().array() / old.sigma.cast<double>().array()).square();
    const Eigen::ArrayXXd t =
        ((now.head - old.head).cast<double>().array() / old.sigma.cast<double>().array()).square();
    return (0.5 * (r + t - 1.0 - r.log())).mean();
  }
  if (head_ == Head::kBernoulli) {
    // torch _kl_bernoulli_bernoulli: p log(p / q) + (1 - p) log((1 - p) / (1 - q)).
    for (Eigen::Index k = 0; k < now.head.size(); ++k) {
      const double a = now.head.data()[k], b = old.head.data()[k];
      const double p = std::exp(log_sigmoid(a));
      sum += p * (log_sigmoid(a) - log_sigmoid(b)) + (1 - p) * (log_sigmoid(-a) - log_sigmoid(-b));
    }
    return sum / static_cast<double>(now.head.size());
  }
  // Categorical, or a MultiDiscrete's categoricals summed: sum p (log p - log q).
  const std::vector<int64_t> parts = categorical_part_sizes();
  Eigen::VectorXd log_p, log_q;
  for (Eigen::Index j = 0; j < n; ++j) {
    Eigen::Index first = 0;
    for (const int64_t size : parts) {
      log_softmax(now.head, first, size, j, log_p);
      log_softmax(old.head, first, size, j, log_q);
      sum += (log_p.array().exp() * (log_p - log_q).array()).sum();
      first += size;
    }
  }
  return sum / static_cast<double>(n);
}

void ActorCriticPolicy::fisher_vector_product(const Eigen::VectorXf& v, Eigen::VectorXf& out) {
  const Eigen::Index n = actor_.output().cols(), rows = actor_.output().rows();
  const Eigen::MatrixXf& head = actor_.output();
  Eigen::MatrixXf tangent;  // J v in the actor's output (logits or means)
  actor_.jvp(v.head(actor_.num_params()), tangent);
  actor_.zero_grad();
  log_std_grad_.setZero();
  if (use_sde()) sde_.zero_grad();
  Eigen::MatrixXf& g = grad_head_;  // M J v / (what the mean divides by)
  g.resize(rows, n);
  if (gaussian()) {
    const double scale = 1.0 / (static_cast<double>(n) * static_cast<double>(rows));
    const Eigen::MatrixXf sigma = gaussian_sigma();
    g = (tangent.array() / sigma.array().square() * static_cast<float>(scale)).matrix();
    const Eigen::VectorXf d_log_std = v.tail(actor_param_count() - actor_.num_params());
    if (head_ == Head::kDiagGaussian) {
      log_std_grad_ = (2.0 * static_cast<double>(n) * scale) * d_log_std;
    } else {
      Eigen::MatrixXf d_variance;
      sde_.variance_tangent(d_log_std.reshaped(sde_.log_std().rows(), sde_.log_std().cols()),
                            d_variance);
      sde_.add_variance_gradient(
          (d_variance.array() / (2.0f * sigma.array().pow(4)) * static_cast<float>(scale))
              .matrix());
    }
  } else if (head_ == Head::kBernoulli) {
    const Eigen::ArrayXXf p = (1.0f + (-head.array()).exp()).inverse();
    g = (p * (1.0f - p) * tangent.array() / static_cast<float>(n * rows)).matrix();
  } else {
    const std::vector<int64_t> parts = categorical_part_sizes();
    Eigen::VectorXd log_p;
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::Index first = 0;
      for (const int64_t size : parts) {
        log_softmax(head, first, size, j, log_p);
        const Eigen::VectorXf p = log_p.array().exp().cast<float>().matrix();
        const auto u = tangent.col(j).segment(first, size);
        g.col(j).segment(first, size) =
            (p.array() * u.array() - p.array() * p.dot(u)) / static_cast<float>(n);
        first += size;
      }
    }
  }
  actor_.backward(g);
  get_actor_grads(out);
}

void ActorCriticPolicy::backward_values(const Eigen::Ref<const Eigen::RowVectorXf>& grad_values) {
  if (extractor_.learned() || separate_value_extractor_)
    throw std::logic_error("ActorCriticPolicy::backward_values: not with a learned extractor");
  critic_.backward(grad_values);
}

std::vector<ParamBlock> ActorCriticPolicy::critic_blocks() { return {critic_.block()}; }

}  // namespace rlrun
