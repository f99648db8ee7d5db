#pragma once
// SimpleMultiObsEnv-v0: SB3's SimpleMultiObsEnv (stable_baselines3/common/envs/multi_input_envs.py)
// with vector keys only. A 4x4 grid world whose inner cells 5, 6, 9, 10 are walls, so the free
// cells form a ring:
//
//     0  1  2  3
//     4  #  #  7        start 0 (or a random free cell), goal 15
//     8  #  #  11       actions Discrete(4): 0 left, 1 down, 2 right, 3 up
//    12 13 14 15
//
// Reward -0.1 per step, 1.0 on the step that reaches the goal (terminated); the registered
// TimeLimit truncates after 100 steps (SB3: max_count). The best return from cell 0 is 0.5
// (six moves).
//
//   observation  Dict('moves': MultiBinary(4), 'row': Discrete(4), 'vec': Box(0, 1, (5,)))
//       vec    the cell's column as a random vector (SB3's "vec": one per column, drawn once
//              when the env is built; here from `vector_seed`, so all copies of a VecEnv agree)
//       row    the cell's row (SB3 shows the row as a random image; rlrun takes vector keys)
//       moves  which of left, down, right, up lead to another cell from here
// So the network sees the Dict through every encoding SB3's MultiInputPolicy uses: a Box as
// it is, a Discrete as a one-hot, MultiBinary bits as floats. SB3 draws the random start from
// cells 0-14, walls included (a start inside a wall never moves); here from the free cells.
#include <array>
#include <cstdint>
#include <optional>
#include <span>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env_base.hpp"

namespace rlrun {

class SimpleMultiObs : public EnvBase {
 public:
  static constexpr int kMaxEpisodeSteps = 100;
  static constexpr int kSide = 4, kVectorSize = 5, kGoal = 15;
  enum Action : int { kLeft = 0, kDown, kRight, kUp, kNumActions };

  struct Config {
    bool random_start = true;  // start in a random free non-goal cell (SB3 default) or in 0
    int64_t vector_seed = 0;   // seed of the column vectors
    template <class V>
    void visit(V& v) {
      v("random_start", random_start, "start in a random free cell instead of cell 0");
      v("vector_seed", vector_seed, "seed of the random vectors that stand for the columns",
        non_negative());
    }
  };

  explicit SimpleMultiObs(const Config& config);
  SimpleMultiObs() : SimpleMultiObs(Config{}) {}

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override { return {320, 320, 4.0}; }
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  int state() const { return state_; }
  // The cell `action` leads to from `cell` (the same cell when the move is blocked).
  static int next_cell(int cell, int action);
  static bool is_wall(int cell) { return cell == 5 || cell == 6 || cell == 9 || cell == 10; }

 private:
  void write_observation(std::span<float> obs) const;
  void draw(int cell, Frame& frame) const;

  Config config_;
  std::array<std::array<float, kVectorSize>, kSide> column_vectors_{};
  int key_success_;
  bool has_state_ = false;
  int state_ = 0;
};

}  // namespace rlrun
