#pragma once
// RewardShaping: adds configurable terms to the reward without writing C++ (the course's
// shaped CartPole: "penalty when the cart stays right of 0.5 for 10 steps"):
//   wrappers: [{id: RewardShaping, terms: [
//       {type: obs_above_for, index: 0, threshold: 0.5, steps: 10, penalty: -1.0},
//       {type: action_sq, coef: -0.001}]}]
// Term types and their parameters: shaping_term.hpp. Applied after the Monitor, so
// monitor.csv, rollout/ep_rew_mean and evaluations report the env's true reward: train on the
// shaped reward, compare on the original one. Streak counters restart at reset().
#include <vector>

#include "rlrun/env/wrapper.hpp"
#include "rlrun/wrappers/shaping_term.hpp"

namespace rlrun {

class RewardShaping : public Wrapper {
 public:
  // Observations and actions pass unchanged (rlrun export).
  bool exports_unchanged() const override { return true; }
  struct Config {
    std::vector<ShapingTerm> terms;  // added to the reward in order
    template <class V>
    void visit(V& v) {
      v("terms", terms,
        "list of {type: ..., <params>}; types obs_above_for / obs_below_for {index, threshold, "
        "steps, penalty, repeat}, obs_abs {index, coef}, action_sq {coef}, constant {value}");
    }
  };
  // Throws std::invalid_argument for an observation index outside the observation, obs terms
  // on a non-Box observation or action_sq on a non-Box action space.
  RewardShaping(EnvPtr inner, const Config& config);

  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;

  // The shaping added on the last step (sum of all terms).
  double last_shaping() const { return last_shaping_; }

 protected:
  void write_own_state(StateWriter& out) const override;
  void read_own_state(const StateReader& in) override;

 private:
  enum class Kind { kObsAboveFor, kObsBelowFor, kObsAbs, kActionSq, kConstant };
  std::vector<ShapingTerm> terms_;
  std::vector<Kind> kinds_;      // terms_[k].type, decoded once
  std::vector<int64_t> streak_;  // per term: consecutive steps the condition has held
  double last_shaping_ = 0.0;
};

}  // namespace rlrun
