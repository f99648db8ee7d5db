#include "rlrun/algos/common/action_noise.hpp"

#include <cmath>
#include <stdexcept>

namespace rlrun {

ActionNoise::ActionNoise(const ActionNoiseConfig& config, int action_dim, int n_envs)
    : sigma_(static_cast<float>(config.noise_std)),
      previous_(Eigen::MatrixXf::Zero(action_dim, n_envs)) {
  if (config.noise_type.empty() || config.noise_type == "none")
    kind_ = Kind::kNone;
  else if (config.noise_type == "normal")
    kind_ = Kind::kNormal;
  else if (config.noise_type == "ornstein-uhlenbeck")
    kind_ = Kind::kOrnsteinUhlenbeck;
  else
    throw std::invalid_argument("noise_type '" + config.noise_type +
                                "' is not one of: normal, ornstein-uhlenbeck (or empty for none)");
}

void ActionNoise::sample(Rng& rng, Eigen::MatrixXf& noise) {
  noise.resize(previous_.rows(), previous_.cols());
  for (Eigen::Index e = 0; e < noise.cols(); ++e) {
    for (Eigen::Index i = 0; i < noise.rows(); ++i) {
      const float z = static_cast<float>(rng.normal());
      if (kind_ == Kind::kNormal) {
        noise(i, e) = sigma_ * z;
      } else if (kind_ == Kind::kOrnsteinUhlenbeck) {
        // x += theta (mu - x) dt + sigma sqrt(dt) N(0, 1), mu = 0.
        const float x = previous_(i, e);
        noise(i, e) = x + kTheta * (0.0f - x) * kDt + sigma_ * std::sqrt(kDt) * z;
        previous_(i, e) = noise(i, e);
      } else {
        noise(i, e) = 0.0f;
      }
    }
  }
}

void ActionNoise::reset(int env) { previous_.col(env).setZero(); }

}  // namespace rlrun
