#include "rlrun/algos/td3/td3_target.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

void sample_target_smoothing_noise(Rng& rng, float noise_std, float noise_clip,
                                   Eigen::MatrixXf& noise) {
  // SB3 DDPG passes target_policy_noise 0.1 with target_noise_clip 0: the clamp makes the noise
  // zero whatever was drawn, so skip drawing.
  if (noise_std == 0.0f || noise_clip == 0.0f) {
    noise.setZero();
    return;
  }
  // torch: actions.clone().normal_(0, std).clamp(-clip, clip), one draw per element.
  for (Eigen::Index k = 0; k < noise.size(); ++k) {
    const float z = noise_std * static_cast<float>(rng.normal());
    noise.data()[k] = std::clamp(z, -noise_clip, noise_clip);
  }
}

void smoothed_target_actions(const Eigen::Ref<const Eigen::MatrixXf>& target_actions,
                             const Eigen::Ref<const Eigen::MatrixXf>& noise,
                             Eigen::MatrixXf& next_actions) {
  next_actions = (target_actions + noise).cwiseMax(-1.0f).cwiseMin(1.0f);
}

void td3_target(const std::vector<const Eigen::MatrixXf*>& next_q,
                const Eigen::Ref<const Eigen::RowVectorXf>& rewards,
                const Eigen::Ref<const Eigen::RowVectorXf>& dones, float gamma,
                Eigen::Ref<Eigen::MatrixXf> y) {
  const Eigen::Index batch = rewards.size();
  bool sizes_ok = !next_q.empty() && dones.size() == batch && y.rows() == 1 && y.cols() == batch;
  for (const Eigen::MatrixXf* q : next_q) sizes_ok = sizes_ok && q->cols() == batch;
  if (!sizes_ok)
    throw std::invalid_argument("td3_target: critic values, rewards, dones and y differ in size");
  for (Eigen::Index j = 0; j < batch; ++j) {
    // th.min over the critics (th.cat(..., dim=1) then min along dim 1).
    float min_q = (*next_q[0])(0, j);
    for (std::size_t i = 1; i < next_q.size(); ++i) min_q = std::min(min_q, (*next_q[i])(0, j));
    // Same association as torch: rewards + ((1 - dones) * gamma) * next_q.
    y(0, j) = rewards(j) + ((1.0f - dones(j)) * gamma) * min_q;
  }
}

}  // namespace rlrun
