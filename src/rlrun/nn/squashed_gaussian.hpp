#pragma once
// Tanh-squashed diagonal Gaussian with state-dependent mean and log_std (both d x batch): SB3
// SquashedDiagGaussianDistribution as SAC's actor uses it (sac/policies.py Actor,
// common/distributions.py), same maths as CleanRL's sac_continuous_action.py without the action
// rescaling (SB3 rescales [-1, 1] to the Box bounds outside the policy).
//   u = mean + std * eps (eps ~ N(0, 1), stored),  a = tanh(u)
//   log_prob = sum_i [log N(u; mean, std) - log(1 - a^2 + 1e-6)]
// The 1e-6 is SB3's epsilon "to avoid NaN"; the log-det is computed from a, as SB3 does.
// backward is pathwise (reparameterisation, Haarnoja et al. 2018 eq. 11-13): gradients flow
// through u with eps held fixed, exactly as torch autograd differentiates rsample().
#include <Eigen/Core>

#include "rlrun/rng.hpp"

namespace rlrun {

class SquashedGaussian {
 public:
  // SB3 sac/policies.py LOG_STD_MIN / LOG_STD_MAX: the actor clamps its log_std output.
  static constexpr float kLogStdMin = -20.0f;
  static constexpr float kLogStdMax = 2.0f;
  // SB3's epsilon in the tanh log-det correction.
  static constexpr float kEpsilon = 1e-6f;

  // out = clamp(raw, kLogStdMin, kLogStdMax) (th.clamp); out may alias raw.
  static void clamp_log_std(const Eigen::Ref<const Eigen::MatrixXf>& raw,
                            Eigen::Ref<Eigen::MatrixXf> out);
  // Backward of the clamp: zeroes grad where raw lies outside [kLogStdMin, kLogStdMax]; at the
  // bounds the gradient passes, as in torch's clamp_backward.
  static void clamp_log_std_backward(const Eigen::Ref<const Eigen::MatrixXf>& raw,
                                     Eigen::Ref<Eigen::MatrixXf> grad);

  // Copies mean and (already clamped) log_std, d x batch each.
  void set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
           const Eigen::Ref<const Eigen::MatrixXf>& log_std);

  Eigen::Index dim() const { return mean_.rows(); }
  Eigen::Index batch() const { return mean_.cols(); }

  // Draws eps ~ N(0, 1) (column by column from rng), stores it and writes a = tanh(mean + std eps).
  void sample(Rng& rng, Eigen::Ref<Eigen::MatrixXf> actions);
  // The same with caller-given noise (d x batch); for tests and replay.
  void sample_from_noise(const Eigen::Ref<const Eigen::MatrixXf>& noise,
                         Eigen::Ref<Eigen::MatrixXf> actions);
  // log_prob of the last sample (what SB3's action_log_prob returns), summed over dims.
  void log_prob(Eigen::Ref<Eigen::RowVectorXf> out) const;
  // log_prob of arbitrary actions in (-1, 1), inverted with atanh after clipping to
  // [-1 + float eps, 1 - float eps] like SB3's TanhBijector.inverse. No gradient path.
  void log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out) const;
  // tanh(mean): SB3's deterministic action.
  void mode(Eigen::Ref<Eigen::MatrixXf> actions) const;

  const Eigen::MatrixXf& noise() const { return noise_; }
  const Eigen::MatrixXf& actions() const { return actions_; }  // last sample

  // Pathwise gradients of L(a, log_prob) for the last sample, given dL/da (d x batch) and
  // dL/dlog_prob (row):
  //   dL/du       = dL/da (1 - a^2) + dL/dlogp * 2 a (1 - a^2) / (1 - a^2 + 1e-6)
  //   dL/dmean    = dL/du
  //   dL/dlog_std = dL/du * std * eps - dL/dlogp
  // (the Gaussian term log N(u; mean, std) = -eps^2/2 - log_std - log sqrt(2 pi) depends on the
  // parameters only through -log_std once eps is fixed). Outputs are resized and overwritten.
  void backward(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                Eigen::MatrixXf& grad_mean, Eigen::MatrixXf& grad_log_std) const;

 private:
  Eigen::MatrixXf mean_;
  Eigen::MatrixXf log_std_;
  Eigen::MatrixXf std_;
  Eigen::MatrixXf noise_;
  Eigen::MatrixXf actions_;
};

}  // namespace rlrun
