#pragma once
// BitFlippingEnv-v0: SB3's test env for Hindsight Experience Replay
// (stable_baselines3/common/envs/bit_flipping_env.py; the toy problem of Andrychowicz et al.
// 2017, arXiv:1707.01495, section 3.1). A vector of n bits starts random; the goal is all ones.
//
//   observation  Dict(achieved_goal, desired_goal, observation: MultiBinary(n)): the state,
//                the state again, and the goal (ones)
//   action       Discrete(n): flip bit i; or (continuous) Box(-1, 1, (n,)): flip every bit
//                whose component is > 0
//   reward       compute_reward(state, goal): 0 when they are equal, else -1 (sparse)
//   terminated   when the state equals the goal (info is_success)
//   truncated    after max_steps (n by default) steps, by the env itself as SB3's
//
// With n = 15 random exploration almost never sees the goal, so an off-policy learner without
// HER stays at -1 everywhere; relabelling with reached states teaches it to flip bits.
#include <optional>
#include <span>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/env_base.hpp"

namespace rlrun {

class BitFlipping : public EnvBase, public GoalEnv {
 public:
  struct Config {
    int n_bits = 10;
    bool continuous = false;  // Box actions (SAC, TD3, DDPG) instead of Discrete (DQN)
    int max_steps = 0;        // 0: n_bits
    template <class V>
    void visit(V& v) {
      v("n_bits", n_bits, "number of bits to flip to ones", in_range(1, 64));
      v("continuous", continuous,
        "Box(-1, 1, (n_bits,)) actions, flipping each bit whose component is > 0");
      v("max_steps", max_steps, "steps per episode, then truncated (0: n_bits)", in_range(0, 1e6));
    }
  };

  explicit BitFlipping(const Config& config);
  BitFlipping() : BitFlipping(Config{}) {}

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  void compute_reward(const Eigen::Ref<const Eigen::MatrixXf>& achieved,
                      const Eigen::Ref<const Eigen::MatrixXf>& desired,
                      Eigen::Ref<Eigen::RowVectorXf> rewards) const override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

 private:
  void write_observation(std::span<float> obs) const;

  Config config_;
  int key_success_;
  bool has_state_ = false;
  int steps_ = 0;
  std::vector<float> state_;
};

}  // namespace rlrun
