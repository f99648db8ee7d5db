#include "rlrun/envs/lunar_lander/heuristic_policy.hpp"

#include <algorithm>
#include <cmath>

#include "rlrun/core/errors.hpp"
#include "rlrun/envs/lunar_lander/lunar_lander.hpp"

namespace rlrun {

std::array<float, 2> lunar_lander_heuristic(std::span<const float> s, bool continuous) {
  // "angle should point towards center", at most 0.4 rad ("22 degrees is bad").
  const double angle_targ = std::clamp(s[0] * 0.5 + s[2] * 1.0, -0.4, 0.4);
  // "target y should be proportional to horizontal offset"
  const double hover_targ = 0.55 * std::abs(s[0]);
  double angle_todo = (angle_targ - s[4]) * 0.5 - s[5] * 1.0;
  double hover_todo = (hover_targ - s[1]) * 0.5 - s[3] * 0.5;
  if (s[6] != 0.0f || s[7] != 0.0f) {  // legs have contact: "reduce fall speed, that's all"
    angle_todo = 0;
    hover_todo = -s[3] * 0.5;
  }
  if (continuous)
    return {static_cast<float>(std::clamp(hover_todo * 20 - 1, -1.0, 1.0)),
            static_cast<float>(std::clamp(-angle_todo * 20, -1.0, 1.0))};
  int a = LunarLander::kNoop;
  if (hover_todo > std::abs(angle_todo) && hover_todo > 0.05)
    a = LunarLander::kMainEngine;
  else if (angle_todo < -0.05)
    a = LunarLander::kRightEngine;
  else if (angle_todo > +0.05)
    a = LunarLander::kLeftEngine;
  return {static_cast<float>(a), 0.0f};
}

std::function<void(const Eigen::MatrixXf&, Eigen::MatrixXf&)> lunar_lander_heuristic_actions(
    Env& env) {
  const auto* lander = dynamic_cast<const LunarLander*>(&env.unwrapped());
  if (!lander)
    throw UsageError(
        "the heuristic policy is LunarLander's (LunarLander-v3, "
        "LunarLanderContinuous-v3); this env is " +
        env.unwrapped().id());
  const bool continuous = lander->config().continuous;
  return [continuous](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
    const int dims = continuous ? 2 : 1;
    action.resize(dims, obs.cols());
    for (Eigen::Index j = 0; j < obs.cols(); ++j) {
      const auto a =
          lunar_lander_heuristic(std::span<const float>(obs.col(j).data(), obs.rows()), continuous);
      for (int i = 0; i < dims; ++i) action(i, j) = a[i];
    }
  };
}

}  // namespace rlrun
