#include "named_policy.hpp"

#include <memory>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/random_actions.hpp"
#include "rlrun/rng.hpp"

namespace rlrun::cli {

NamedPolicy named_policy(const std::string& name, Env& env, const Registry& registry,
                         const PolicyOptions& options) {
  if (name == "random") {
    auto rng = std::make_shared<Rng>(options.seed ^ 0x5eedull);
    const Space space = env.action_space();
    // Legal actions of the state the env is in, when it masks them (env/random_actions.hpp).
    auto random_actions = std::make_shared<RandomActions>(space);
    Env* played = &env;
    return {
        [rng, space, random_actions, played](const Eigen::MatrixXf& obs, Eigen::MatrixXf& action) {
          // One column per observation column (per agent of a multi-agent env).
          action.resize(space.flat_dim(), obs.cols());
          random_actions->sample(played->info(), static_cast<int>(obs.cols()), *rng,
                                 {action.data(), static_cast<size_t>(action.size())});
        },
        "random policy"};
  }
  // The env's own baselines, as its folder registered them (env/env_entry.hpp).
  std::string offered = "random";
  if (const EnvEntry* entry = registry.find_env(env.id())) {
    for (const PolicyEntry& policy : entry->policies) {
      if (policy.name == name) {
        std::string label = name;
        for (const auto& [key, value] : options.settings)
          if (key == "green_time") {  // appended in pieces: GCC 12 -Wrestrict false positive
            label += ' ';
            label += std::to_string(static_cast<int>(value));
            label += " s";
          }
        return {policy.make(env, options), label};
      }
      offered += ", " + policy.name;
    }
  }
  throw UsageError("policy '" + name + "' does not come with " + env.id() +
                   "; its policies: " + offered);
}

}  // namespace rlrun::cli
