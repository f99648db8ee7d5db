#pragma once
// generalized State-Dependent Exploration (gSDE; Raffin, Kober and Stulp 2021,
// arXiv:2005.05719) exactly as SB3's StateDependentNoiseDistribution
// (stable_baselines3/common/distributions.py, 2.4.1). The noise of an action is a linear function
// of the policy's latent features s (the last hidden layer, SB3's latent_sde), with weights that
// are drawn only now and then (reset_noise), so the exploration is smooth in time:
//
//   std      = get_std(log_std): exp(log_std) or expln(log_std); log_std is a learned
//              (latent_dim x action_dim) matrix, or (latent_dim x 1) broadcast over the actions
//              when full_std is false
//   E        = std * eps, eps ~ N(0, 1) (latent_dim x action_dim): the exploration matrix, plus
//              one such matrix per env for batched acting (sample_weights)
//   noise    = E^T s (th.mm), or E_j^T s_j per column j when the batch has exactly as many
//              columns as there are per-env matrices and more than one (th.bmm; get_noise)
//   u        = mean + noise; action = u, or tanh(u) with squash_output (SAC)
//   variance = (s^2)^T-weighted std^2: variance(i, j) = sum_k s(k, j)^2 std(k, i)^2, and the
//              actions are scored under Normal(mean, sqrt(variance + 1e-6)) per dimension
//   log_prob = sum_i log N(g_i; mean_i, sigma_i) [- sum_i log(1 - tanh(g_i)^2 + 1e-6)], where
//              g = atanh(clamp(action, -1 + eps_f32, 1 - eps_f32)) with squash_output, else g =
//              action (TanhBijector.inverse, then the squash correction)
//   entropy  = sum_i (0.5 + log sqrt(2 pi) + log sigma_i) (none with squash_output)
//   mode     = mean, or tanh(mean)
//
// learn_features false (PPO, A2C) detaches s in the noise and the variance: gradients reach the
// mean and log_std only. learn_features true (SAC's actor) lets them flow into s as well.
// Gradients follow torch's autograd of that graph, including the pathwise ones of a sample: E was
// drawn with rsample, so a loss of the sampled action reaches log_std through E = std * eps
// (eps is kept) as well as through the variance.
//
// Shapes: one sample per column. mean and actions are action_dim x n, s is latent_dim x n.
#include <Eigen/Core>

#include "rlrun/nn/param_block.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

// SB3 StateDependentNoiseDistribution's constructor flags.
struct StateDependentNoiseOptions {
  bool full_std = true;         // one std per (latent feature, action); false: per feature
  bool use_expln = false;       // expln instead of exp for a positive std
  bool squash_output = false;   // tanh on the actions (SAC), with the log-det correction
  bool learn_features = false;  // gradients into the latent features (SAC: true)
};

class StateDependentNoise {
 public:
  // SB3's epsilon (variance floor, expln guard, log-det correction).
  static constexpr float kEpsilon = 1e-6f;

  StateDependentNoise() = default;
  // proba_distribution_net: log_std = log_std_init * ones(latent_dim, full_std ? action_dim : 1).
  // No exploration matrices yet: call sample_weights. Throws std::invalid_argument for
  // non-positive sizes.
  StateDependentNoise(int latent_dim, int action_dim, float log_std_init,
                      const StateDependentNoiseOptions& options);

  int latent_dim() const { return static_cast<int>(log_std_.rows()); }
  int action_dim() const { return action_dim_; }
  const StateDependentNoiseOptions& options() const { return options_; }

  // The learned parameter (SB3's `log_std`) and its gradient.
  Eigen::MatrixXf& log_std() { return log_std_; }
  const Eigen::MatrixXf& log_std() const { return log_std_; }
  Eigen::MatrixXf& log_std_grad() { return log_std_grad_; }
  const Eigen::MatrixXf& log_std_grad() const { return log_std_grad_; }
  ParamBlock block() { return {log_std_.data(), log_std_grad_.data(), log_std_.size()}; }
  void zero_grad() { log_std_grad_.setZero(); }

  // get_std: latent_dim x action_dim (broadcast over the actions without full_std).
  void std_matrix(Eigen::MatrixXf& out) const;
  // get_std(log_std).mean(): SAC's train/std.
  double mean_std() const;

  // sample_weights(log_std, batch_size): a new exploration matrix and batch_size per-env ones,
  // eps drawn from rng in torch's order (the matrix first, then the batch, each row-major).
  void sample_weights(Rng& rng, int batch_size);
  // The same with given standard-normal draws: eps_mat latent_dim x action_dim, eps_matrices
  // latent_dim x (action_dim * batch_size) (matrix b = columns [b A, (b + 1) A)).
  void set_weights(const Eigen::Ref<const Eigen::MatrixXf>& eps_mat,
                   const Eigen::Ref<const Eigen::MatrixXf>& eps_matrices);
  // Puts back saved matrices as they were (a checkpoint): E was std * eps with the std of its
  // draw, which later optimizer steps do not change. Throws std::invalid_argument for shapes
  // that do not fit.
  void restore_weights(const Eigen::Ref<const Eigen::MatrixXf>& eps_mat,
                       const Eigen::Ref<const Eigen::MatrixXf>& eps_matrices,
                       const Eigen::Ref<const Eigen::MatrixXf>& exploration_mat,
                       const Eigen::Ref<const Eigen::MatrixXf>& exploration_matrices);
  const Eigen::MatrixXf& exploration_mat() const { return exploration_mat_; }
  const Eigen::MatrixXf& exploration_matrices() const { return exploration_matrices_; }
  int num_exploration_matrices() const;
  // The draws behind them (what a checkpoint stores: the matrices are std * eps).
  const Eigen::MatrixXf& eps_mat() const { return eps_mat_; }
  const Eigen::MatrixXf& eps_matrices() const { return eps_matrices_; }

  // proba_distribution(mean_actions, log_std, latent_sde): copies both and computes sigma.
  void set(const Eigen::Ref<const Eigen::MatrixXf>& mean,
           const Eigen::Ref<const Eigen::MatrixXf>& latent);
  Eigen::Index batch() const { return mean_.cols(); }
  const Eigen::MatrixXf& mean() const { return mean_; }
  // sqrt(variance + 1e-6), action_dim x n.
  const Eigen::MatrixXf& sigma() const { return sigma_; }

  // get_noise(latent_sde) of the current latent (action_dim x n): the mm / bmm rule above.
  void noise(Eigen::Ref<Eigen::MatrixXf> out) const;
  // sample(): mean + noise, tanh'd with squash_output. Kept for backward_sampled.
  void sample(Eigen::Ref<Eigen::MatrixXf> actions);
  // mode(): mean, or tanh(mean).
  void mode(Eigen::Ref<Eigen::MatrixXf> actions) const;
  // log_prob(actions), summed over the action dimensions.
  void log_prob(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                Eigen::Ref<Eigen::RowVectorXf> out) const;
  // entropy(); throws std::logic_error with squash_output (SB3 returns None there).
  void entropy(Eigen::Ref<Eigen::RowVectorXf> out) const;

  // Gradients of L = sum_j grad_log_prob(j) log_prob_j + grad_entropy(j) entropy_j for given
  // actions (PPO's evaluate_actions): grad_mean (action_dim x n) is written, the log_std gradient
  // ADDED to log_std_grad(), and with learn_features dL/dlatent written to *grad_latent.
  void backward_scored(const Eigen::Ref<const Eigen::MatrixXf>& actions,
                       const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                       const Eigen::Ref<const Eigen::RowVectorXf>& grad_entropy,
                       Eigen::MatrixXf& grad_mean, Eigen::MatrixXf* grad_latent = nullptr);
  // Gradients of L(actions, log_prob) for the last sample() and its log_prob (SB3's
  // log_prob_from_params, SAC's actor loss), given dL/dactions and dL/dlog_prob: pathwise through
  // the noise (E and the latent) and through the variance. Outputs as in backward_scored.
  void backward_sampled(const Eigen::Ref<const Eigen::MatrixXf>& grad_actions,
                        const Eigen::Ref<const Eigen::RowVectorXf>& grad_log_prob,
                        Eigen::MatrixXf& grad_mean, Eigen::MatrixXf* grad_latent = nullptr);

  // TRPO's Fisher-vector product (the variance's part of it), at the last set():
  // d_variance (action_dim x n) = d(variance)/d(log_std) * d_log_std for a direction shaped as
  // log_std(), and the reverse, which ADDS J^T grad_var to log_std_grad() (the latent is
  // detached here, learn_features or not).
  void variance_tangent(const Eigen::Ref<const Eigen::MatrixXf>& d_log_std,
                        Eigen::MatrixXf& d_variance) const;
  void add_variance_gradient(const Eigen::MatrixXf& grad_var) {
    backward_std(grad_var, nullptr, nullptr);
  }

 private:
  // d std / d log_std for every entry of log_std_ (exp or expln).
  void std_derivative(Eigen::MatrixXf& out) const;
  // Adds the gradient of L through variance (dL/dvariance = grad_var, action_dim x n) and, when
  // grad_e is given, through E (dL/dE per exploration matrix used) to log_std_grad_ and latent.
  void backward_std(const Eigen::MatrixXf& grad_var, const Eigen::MatrixXf* grad_noise,
                    Eigen::MatrixXf* grad_latent);
  // Whether get_noise uses the per-env matrices for a batch of n columns.
  bool batched_noise(Eigen::Index n) const;
  // TanhBijector.inverse then log_prob_correction for one entry: g and log(1 - tanh(g)^2 + eps).
  static float inverse_tanh(float action);

  StateDependentNoiseOptions options_;
  int action_dim_ = 0;
  Eigen::MatrixXf log_std_, log_std_grad_;
  Eigen::MatrixXf eps_mat_, eps_matrices_;
  Eigen::MatrixXf exploration_mat_, exploration_matrices_;
  // The distribution of the last set(): mean, latent, std^2 (latent_dim x action_dim), sigma.
  Eigen::MatrixXf mean_, latent_, std_, std_sq_, latent_sq_, sigma_;
  // The last sample: u = mean + noise, and the action.
  Eigen::MatrixXf pre_squash_, sampled_;
  // Backward workspaces.
  Eigen::MatrixXf grad_var_, grad_u_, grad_std_, std_grad_factor_, latent_term_;
};

}  // namespace rlrun
