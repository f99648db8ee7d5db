#pragma once
// One term of the RewardShaping wrapper, as written in YAML:
//   {type: obs_above_for, index: 0, threshold: 0.5, steps: 10, penalty: -1.0}
//       adds `penalty` on every step on which obs[index] > threshold has held for `steps`
//       consecutive steps (with `repeat: false`, only on the step the streak reaches `steps`)
//   {type: obs_below_for, ...}   the same with obs[index] < threshold
//   {type: obs_abs, index: 2, coef: -0.1}   adds coef * |obs[index]| every step
//   {type: action_sq, coef: -0.001}         adds coef * sum(action^2) every step (Box actions)
//   {type: constant, value: -0.01}          adds value every step
// Every term ADDS to the reward: penalties are negative numbers. The observation is the one
// the step returned, as seen at the wrapper's place in the stack.
#include <string>
#include <vector>

#include "rlrun/core/config_checks.hpp"
#include "rlrun/core/config_fields.hpp"

namespace rlrun {

struct ShapingTerm {
  std::string type;        // obs_above_for | obs_below_for | obs_abs | action_sq | constant
  int index = 0;           // observation element (obs_* terms)
  double threshold = 0.0;  // obs_above_for / obs_below_for: the level
  int steps = 1;           // obs_above_for / obs_below_for: consecutive steps before it counts
  double penalty = -1.0;   // obs_above_for / obs_below_for: added to the reward
  bool repeat = true;      // obs_above_for / obs_below_for: every step of the streak, or once
  double coef = 0.0;       // obs_abs / action_sq: coefficient
  double value = 0.0;      // constant: added every step

  // The fields that `type` uses (strict parsing rejects the others).
  template <class V>
  void visit_fields(V& v) {
    if (type == "obs_above_for" || type == "obs_below_for") {
      v("index", index, "observation element");
      v("threshold", threshold, "level the element must stay above (below)");
      v("steps", steps, "consecutive steps before the penalty applies", at_least(1));
      v("penalty", penalty, "added to the reward (negative = penalty)");
      v("repeat", repeat, "apply on every step of the streak (false: once per streak)");
    } else if (type == "obs_abs") {
      v("index", index, "observation element");
      v("coef", coef, "reward += coef * |obs[index]|");
    } else if (type == "action_sq") {
      v("coef", coef, "reward += coef * sum(action^2)");
    } else if (type == "constant") {
      v("value", value, "added to every step's reward");
    }
  }
};

// The registered term types, for errors and `rlrun list RewardShaping`.
const std::vector<std::string>& shaping_term_types();

void decode(const ConfigNode& n, ShapingTerm& out);
YAML::Node encode(const ShapingTerm& term);

}  // namespace rlrun
