#include "named_policy.hpp"

#include <memory>

#include "rlrun/core/errors.hpp"
#include "rlrun/rng.hpp"
#include "rlrun/envs/gripper/scripted_grasp_policy.hpp"
#include "rlrun/envs/traffic/fixed_time_policy.hpp"

namespace rlrun::cli {

NamedPolicy named_policy(const std::string& name, Env& env, uint64_t seed, int green_time) {
  if (name == "random") {
    auto rng = std::make_shared<Rng>(seed ^ 0x5eedull);
    const Space space = env.action_space();
    return {[rng, space](const Eigen::MatrixXf&, Eigen::MatrixXf& action) {
              action.resize(space.flat_dim(), 1);
              space.sample(*rng, {action.data(), static_cast<size_t>(action.size())});
            },
            "random policy"};
  }
  if (name == "fixed-time")
    return {fixed_time_actions(env, green_time), "fixed-time " + std::to_string(green_time) + " s"};
  if (name == "scripted") return {scripted_grasp_actions(env), "scripted grasp"};
  throw UsageError("--policy " + name + ": expected model, random, fixed-time or scripted");
}

}  // namespace rlrun::cli
