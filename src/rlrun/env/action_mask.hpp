#pragma once
// How an env tells an agent which actions are legal (sb3-contrib 2.4's invalid-action masking,
// sb3_contrib/common/maskable/; MaskablePPO is its user). An env reports the mask of the state
// its last reset() or step() left it in as numbers of its Info, one key per entry:
// `action_mask.0`, `action_mask.1`, ... with 1 for a legal action and 0 for an illegal one
// (Gymnasium's info["action_mask"] as flat keys, since an Info holds numbers). The entries are
// sb3-contrib's: Discrete(n) n, MultiDiscrete(nvec) sum(nvec) (each dimension's mask in turn),
// MultiBinary(n) 2n (the "0" and "1" outcome of each entry, MaskableBernoulliDistribution).
// A multi-agent env (include/rlrun/env.hpp) reports its agents' masks agent-major: agent a's
// entries are action_mask.<a * size> ... action_mask.<a * size + size - 1>.
//
// The keys travel as every Info value does: wrappers pass their inner env's Info on (Monitor
// copies its keys), and VecEnv's copy c answers env(c).info() for its current state — after an
// auto-reset that is the new episode's first state, the one whose mask the next action needs
// (sb3-contrib calls env.action_masks() after DummyVecEnv's auto-reset, likewise). A Python env
// reports info["action_mask"] or an action_masks() method (envs/python/worker.py turns either
// into these keys).
#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class VecEnv;

// "action_mask.<index>".
std::string action_mask_key(int index);

// Entries of one agent's mask for an action space: n for Discrete, sum(nvec) for
// MultiDiscrete, 2n for MultiBinary; 0 for Box and Dict (no masking).
int action_mask_size(const Space& action_space);

// What is wrong with one agent's mask (action_mask_size(space) floats), or "" if nothing:
// an entry other than 0 or 1, or no legal action (in some dimension, for MultiDiscrete and
// MultiBinary: sb3-contrib would otherwise sample from a uniform over -1e8 logits).
std::string action_mask_problem(const Space& action_space, std::span<const float> mask);

// Reads masks from an env's Info with the key indices looked up once (again when the env
// declares more keys, as a Python env does on its first reply).
class ActionMaskReader {
 public:
  explicit ActionMaskReader(const Space& action_space);

  int size() const { return size_; }
  // Writes `agents` masks (agent-major, agents * size() floats) into `out` and returns "", or
  // returns what is wrong: the Info has no mask, a mask of another length, or a mask
  // action_mask_problem refuses. (No allocation when the masks are fine: rollouts call it
  // every step; the caller names the env and the step in its error.)
  std::string read(const Info& info, int agents, std::span<float> out);

 private:
  void resolve(const Info& info, int total);

  Space action_space_;
  int size_ = 0;
  std::vector<int> indices_;  // index of action_mask.<k>, k < agents * size
  int beyond_ = -1;           // index of the first key past the expected length, or -1
  size_t known_keys_ = 0;
};

// The current masks of every column of `env` (size x num_envs), read from each copy's Info
// with one reader per copy (`readers` is resized to the copies). Throws RuntimeFailure naming
// the env copy and the step: "GridWorld-v0 (env 0) at step 1200: ..." (`step` = the env steps
// so far; negative: "after reset()").
void read_action_masks(const VecEnv& env, std::vector<ActionMaskReader>& readers,
                       Eigen::MatrixXf& masks, int64_t step);

}  // namespace rlrun
