#pragma once
// Random actions for every agent of an env, legal ones when the env masks its actions
// (env/action_mask.hpp): what check-env's determinism rollouts, its random baseline and
// `eval --policy random` take. sb3-contrib's MaskablePPO never plays an illegal move, and a game
// may raise on one (PettingZoo classic's envs assert), so a random player keeps to the mask too.
// Discrete spaces only are masked here (a uniform pick among the legal actions); other spaces,
// and envs that report no mask, get space.sample().
#include <span>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/rng.hpp"

namespace rlrun {

class RandomActions {
 public:
  explicit RandomActions(const Space& action_space);

  // `agents` actions (agent-major) for the state whose Info is `info`.
  void sample(const Info& info, int agents, Rng& rng, std::span<float> actions);

 private:
  Space space_;
  ActionMaskReader reader_;
  std::vector<float> masks_;
};

}  // namespace rlrun
