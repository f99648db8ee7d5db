#pragma once
// DictReach-v0: a goal-conditioned probe with a Dict observation and a Box action, the shape of
// panda-gym / Gymnasium-Robotics reach tasks without the physics. A point moves in the square
// [-1, 1]^2 towards a goal; both are drawn uniformly at reset.
//
//   observation  Dict('goal': Box(-1, 1, (2,)), 'position': Box(-1, 1, (2,)))
//   action       Box(-1, 1, (2,)): the move, scaled by step_size (clipped to the bounds)
//   reward       -|position - goal| after the move
//   terminated   when the point is within goal_tolerance of the goal (info is_success = 1)
//   info         is_success, distance
// The registered TimeLimit truncates after 50 steps. A Dict of Box keys reaches the networks as
// SB3's CombinedExtractor feeds it: goal then position, concatenated.
#include <array>
#include <optional>
#include <span>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env_base.hpp"

namespace rlrun {

class DictReach : public EnvBase {
 public:
  static constexpr int kMaxEpisodeSteps = 50;

  struct Config {
    double step_size = 0.1;        // displacement per unit of action
    double goal_tolerance = 0.05;  // success radius
    template <class V>
    void visit(V& v) {
      v("step_size", step_size, "displacement of the point per unit of action",
        in_range(0, 2).open_low());
      v("goal_tolerance", goal_tolerance, "the episode ends with success within this distance",
        in_range(0, 2).open_low());
    }
  };

  explicit DictReach(const Config& config);
  DictReach() : DictReach(Config{}) {}

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  bool can_save_state() const override { return true; }
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

  RenderSpec render_spec() const override { return {400, 400, 20.0}; }
  bool render(Frame& frame) const override;
  bool render_observation(std::span<const float> obs, Frame& frame) const override;

  double distance() const;

 private:
  void write_observation(std::span<float> obs) const;
  void draw(std::span<const float> goal, std::span<const float> position, Frame& frame) const;

  Config config_;
  int key_success_, key_distance_;
  bool has_state_ = false;
  std::array<float, 2> goal_{}, position_{};
};

}  // namespace rlrun
