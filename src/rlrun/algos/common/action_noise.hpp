#pragma once
// Exploration noise for off-policy algorithms (stable_baselines3/common/noise.py), added to
// actions scaled to [-1, 1]: NormalActionNoise (i.i.d. N(0, sigma)) and
// OrnsteinUhlenbeckActionNoise (theta 0.15, dt 1e-2, mean 0: temporally correlated, reset at
// each env's episode end). One noise process per env (SB3's VectorizedActionNoise).
// YAML follows rl-zoo: `noise_type: normal | ornstein-uhlenbeck`, `noise_std: 0.1`.
#include <Eigen/Core>
#include <string>

#include "rlrun/algos/common/config_checks.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

struct ActionNoiseConfig {
  std::string noise_type;  // "" (none), "normal" or "ornstein-uhlenbeck"
  double noise_std = 0.1;  // sigma of the noise, per action dimension

  template <class V>
  void visit(V& v) {
    v("noise_type", noise_type, "exploration noise: '' (none), normal or ornstein-uhlenbeck",
      OneOf{{"", "normal", "ornstein-uhlenbeck"}});
    v("noise_std", noise_std, "noise standard deviation (actions scaled to [-1, 1])",
      non_negative());
  }
};

class ActionNoise {
 public:
  // Throws std::invalid_argument for an unknown noise_type.
  ActionNoise(const ActionNoiseConfig& config, int action_dim, int n_envs);
  bool enabled() const { return kind_ != Kind::kNone; }
  // Writes one noise sample per env (action_dim x n_envs).
  void sample(Rng& rng, Eigen::MatrixXf& noise);
  void reset(int env);
  const Eigen::MatrixXf& state() const { return previous_; }
  void set_state(const Eigen::MatrixXf& state) { previous_ = state; }

 private:
  enum class Kind { kNone, kNormal, kOrnsteinUhlenbeck };
  static constexpr float kTheta = 0.15f;
  static constexpr float kDt = 1e-2f;
  Kind kind_ = Kind::kNone;
  float sigma_ = 0.0f;
  Eigen::MatrixXf previous_;  // OU state per env
};

}  // namespace rlrun
