#pragma once
// Gymnasium's scripted walker, BipedalWalkerHeuristics.step_heuristic
// (gymnasium/envs/box2d/bipedal_walker.py, run by the file's __main__): a three-state gait
// (stay on one leg, put the other down, push off) with PD targets for the hips and knees, a
// PD term that keeps the hull level and a vertical-speed damper on the knees. It reads only
// the observation but remembers its gait state, so it restarts at every episode. Gymnasium
// calls it "suboptimal, [it has] no notion of balance": it walks forward on normal terrain and
// usually fails on hardcore obstacles. `--policy heuristic` in eval and record.
#include <array>
#include <span>

#include "rlrun/env.hpp"
#include "rlrun/env/policy.hpp"

namespace rlrun {

class WalkingHeuristic {
 public:
  // Back to Gymnasium's initial gait state (moving leg 0, standing on leg 1).
  void restart();
  // The action for observation `s` (24 values); clipped to [-1, 1].
  std::array<float, 4> act(std::span<const float> s);

 private:
  enum GaitState { kStayOnOneLeg = 1, kPutOtherDown = 2, kPushOff = 3 };
  static constexpr double kSpeed = 0.29;             // SPEED: "will fall forward on higher speed"
  static constexpr double kSupportKneeAngle = +0.1;  // SUPPORT_KNEE_ANGLE

  GaitState state_ = kStayOnOneLeg;
  int moving_leg_ = 0;
  int supporting_leg_ = 1;
  double supporting_knee_angle_ = kSupportKneeAngle;
};

// As a policy acting on `env` (BipedalWalker-v3 or its hardcore alias), run as Gymnasium's
// __main__ runs it: the first action after a reset is 0 (and the gait restarts), then the
// heuristic of each new observation. Throws UsageError for any other env.
PolicyFn walking_heuristic_actions(Env& env);

}  // namespace rlrun
