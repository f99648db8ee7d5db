#pragma once
// Lets a Discrete-action algorithm (DQN) drive a Box env: each dimension is cut into `bins`
// evenly spaced values from low to high (both included), and Discrete(bins^dims) enumerates
// their combinations, the first dimension varying fastest. E.g. Pendulum-v1 with 5 bins:
// torques -2, -1, 0, 1, 2. Used by `env.auto_wrap: true` or `{id: BoxAsDiscrete, bins: 5}`.
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/env/wrapper.hpp"

namespace rlrun {

class BoxAsDiscrete : public Wrapper {
 public:
  struct Config {
    int bins = 5;  // values per action dimension
    template <class V>
    void visit(V& v) {
      v("bins", bins, "evenly spaced values per action dimension (low and high included)",
        in_range(2, 1000));
    }
  };
  // Throws std::invalid_argument for a non-Box or unbounded inner space, bins < 2, or more
  // than 2^24 combinations.
  BoxAsDiscrete(EnvPtr inner, const Config& config);
  explicit BoxAsDiscrete(EnvPtr inner) : BoxAsDiscrete(std::move(inner), Config()) {}
  const Space& action_space() const override { return space_; }
  StepResult step(std::span<const float> action, std::span<float> obs) override;

 private:
  Space space_;
  int bins_;
  std::vector<float> box_action_;
};

}  // namespace rlrun
