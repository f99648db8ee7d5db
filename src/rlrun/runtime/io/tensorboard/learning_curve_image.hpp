#pragma once
// The run's learning curve as a PNG for TensorBoard's Images tab (issue 18's optional images):
// rollout/ep_rew_mean, and eval/mean_reward when the run evaluated, against
// time/total_timesteps from progress.csv, drawn by `rlrun plot`'s code
// (render/learning_curves.hpp).
#include <string>

namespace rlrun {

// PNG bytes, or "" when progress.csv holds fewer than two points of the training return.
std::string learning_curve_png(const std::string& run_dir, const std::string& title);

}  // namespace rlrun
