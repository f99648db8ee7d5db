#pragma once
// GridWorld-v0: the "wrap your own simulator" tutorial's 5x5 grid (a task with no Gym API of
// its own, wrapped as an env). The agent starts at (0, 0) (or a random non-goal cell) and
// walks to the terminal cell (size-1, size-1); a move into the outer wall leaves it in place.
// The env itself truncates after `max_steps` steps, because the tutorial's timeout carries a
// penalty that a TimeLimit wrapper could not add.
//
//   observation  MultiDiscrete([size, size]): row, column (one float each). PPO and A2C encode
//                it as SB3's preprocess_obs does (concatenated one-hots); for the algorithms
//                that take Box observations the OneHotObservation wrapper does the same.
//   action       Discrete(4): 0 up (row - 1), 1 right (column + 1), 2 down (row + 1),
//                3 left (column - 1)
//   reward       move_reward per move, wall_reward for a move into the wall, plus
//                goal_reward on reaching the goal and timeout_reward on the truncating step.
//                With the defaults the return from (0, 0) is -(steps taken), optimum -8.
//   info         is_success (reached the goal), bumped (this move hit the wall), and the
//                action mask of the new state (env/action_mask.hpp, for MaskablePPO):
//                action_mask.0 ... action_mask.3, 0 for the moves into the wall, 1 otherwise
#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env.hpp"
#include "rlrun/env_seeding.hpp"
#include "rlrun/info.hpp"
#include "rlrun/space.hpp"

namespace rlrun {

class GridWorld : public Env {
 public:
  struct Config {
    int size = 5;                    // grid side; the goal is cell (size-1, size-1)
    bool random_start = false;       // start in a uniformly random non-goal cell instead of (0,0)
    int max_steps = 50;              // the env truncates after this many steps
    double move_reward = -1.0;       // reward of a move to a neighbouring cell
    double wall_reward = -1.0;       // reward of a move into the wall (the agent stays)
    double goal_reward = 0.0;        // added on the step that reaches the goal
    double timeout_reward = -100.0;  // added on the step that truncates the episode

    template <class V>
    void visit(V& v) {
      v("size", size, "grid side; the goal is the far corner (size-1, size-1)", in_range(2, 1000));
      v("random_start", random_start, "start in a random non-goal cell instead of (0, 0)");
      v("max_steps", max_steps, "the env truncates the episode after this many steps", at_least(1));
      v("move_reward", move_reward, "reward of a move to a neighbouring cell");
      v("wall_reward", wall_reward, "reward of a move into the wall (the agent stays)");
      v("goal_reward", goal_reward, "added on the step that reaches the goal");
      v("timeout_reward", timeout_reward, "added on the step that truncates the episode");
    }
  };

  enum Action : int { kUp = 0, kRight, kDown, kLeft, kNumActions };

  GridWorld() : GridWorld(Config{}) {}
  // Throws std::invalid_argument unless size >= 2 and max_steps >= 1.
  explicit GridWorld(const Config& config);

  const Space& observation_space() const override { return observation_space_; }
  const Space& action_space() const override { return action_space_; }
  const Info& info() const override { return info_; }
  std::string id() const override { return "GridWorld-v0"; }

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override {
    return {kCellPixels * config_.size, kCellPixels * config_.size, 4.0};
  }
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  // Moves on the shortest path from (row, col) to the goal: the best return is
  // this many move_rewards plus goal_reward.
  int shortest_path_length(int row, int col) const;

  const Config& config() const { return config_; }
  int row() const { return row_; }
  int col() const { return col_; }
  int elapsed_steps() const { return steps_; }

 private:
  static constexpr int kCellPixels = 80;

  void write_observation(std::span<float> obs) const;
  void draw(int row, int col, Frame& frame) const;

  Config config_;
  Space observation_space_;
  Space action_space_;
  Info info_;
  EnvSeeding seeding_;  // Gymnasium seeding rules + the env's Rng
  // Sets is_success, bumped and the action mask of the current cell.
  void write_info(bool at_goal, bool bumped);

  int key_success_, key_bumped_;
  int key_mask_[kNumActions];
  bool has_state_ = false;
  int row_ = 0, col_ = 0;
  int steps_ = 0;
};

}  // namespace rlrun
