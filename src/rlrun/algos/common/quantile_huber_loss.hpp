#pragma once
// The quantile-regression Huber loss of QR-DQN (Dabney et al. 2017, arXiv:1710.10044, eq. 9-10)
// as TQC uses it (Kuznetsov et al. 2020, arXiv:2005.04269, section 3; sb3-contrib common/utils.py
// quantile_huber_loss with sum_over_quantiles=False): for one critic's quantile estimates
// theta_k, k < K, at cumulative probabilities tau_k = (k + 0.5) / K, and target atoms z_t,
// t < T, of the same sample,
//
//   rho(k, t) = |tau_k - 1{delta < 0}| * huber(delta),   delta = z_t - theta_k,
//   huber(d)  = 0.5 d^2 if |d| <= 1 else |d| - 0.5       (kappa = 1; torch.where(|d| > 1, ...))
//
// sb3-contrib's TQC loss is the MEAN of rho over (batch, critics, K, T) — "not summing over
// the quantile dimension as in the paper" (tqc.py) — and its QR-DQN loss sums over the K current
// quantiles and averages over the batch and the T targets (sum_over_quantiles=True, the paper's
// eq. 10). The indicator is detached (no gradient),
// so d rho / d theta_k = -|tau_k - 1{delta < 0}| * clamp(delta, -1, 1).
#include <Eigen/Core>

namespace rlrun {

// Returns scale * sum over samples j, atoms k and targets t of rho for current (K x n: theta_k
// of sample j in column j) and target (T x n), and writes grad = scale * d(sum rho) / d current
// and rho = scale * sum over t of rho(k, t), per atom and sample (both K x n, resized; rho is
// the workspace the loss is summed from). TQC calls it per critic with
// scale = 1 / (n * n_critics * K * T), so the critics' results add up to sb3-contrib's mean;
// QR-DQN with scale = 1 / (n * T).
// Throws std::invalid_argument when the batch sizes differ.
double quantile_huber_loss(const Eigen::Ref<const Eigen::MatrixXf>& current,
                           const Eigen::Ref<const Eigen::MatrixXf>& target, float scale,
                           Eigen::MatrixXf& grad, Eigen::MatrixXf& rho);

}  // namespace rlrun
