#pragma once
// RescaleAction: gymnasium/wrappers/transform_action.py. The agent acts in
// Box(min_action, max_action); each action is mapped affinely onto the inner env's bounds and
// clipped to them:
//     inner = clip(low + (high - low) * (action - min_action) / (max_action - min_action), low, high)
// E.g. `{id: RescaleAction, min_action: -1, max_action: 1}` gives any Box env a [-1, 1] action
// space. min_action / max_action are one number for every dimension or one per dimension.
#include <vector>

#include "rlrun/core/config_fields.hpp"
#include "rlrun/wrappers/action_wrapper.hpp"

namespace rlrun {

// A bound written in YAML as one number (every dimension) or a list (one per dimension).
struct ActionBound {
  std::vector<double> values;
};
inline void decode(const ConfigNode& n, ActionBound& out) {
  if (n.is_sequence()) {
    decode(n, out.values);
    if (out.values.empty()) n.fail("expected a number or a non-empty list of numbers");
  } else {
    out.values = {n.as_double()};
  }
}
inline YAML::Node encode(const ActionBound& b) {
  return b.values.size() == 1 ? encode(b.values[0]) : encode(b.values);
}

class RescaleAction : public ActionWrapper {
 public:
  struct Config {
    ActionBound min_action{{-1.0}};  // one value, or one per action dimension
    ActionBound max_action{{1.0}};   // one value, or one per action dimension
    template <class V>
    void visit(V& v) {
      v("min_action", min_action, "lower bound of the new action space (a number or a list)");
      v("max_action", max_action, "upper bound of the new action space (a number or a list)");
    }
  };
  // Throws std::invalid_argument for a non-Box or unbounded inner space, a bound list of the
  // wrong length, or min_action >= max_action.
  RescaleAction(EnvPtr inner, const Config& config);
  explicit RescaleAction(EnvPtr inner) : RescaleAction(std::move(inner), Config()) {}

  std::string export_action(PolicyGraph& graph, const std::string& action) const override;

 private:
  // The action mapped affinely onto the inner env's bounds and clipped to them.
  std::span<const float> map_action(std::span<const float> action) override;
  std::vector<float> gradient_, intercept_;  // Gymnasium's: inner = gradient * action + intercept
  // The inner env's bounds, copied once: asking for its action space on every step went
  // through the whole wrapper chain (1 % of PPO Pendulum's profile).
  std::vector<float> inner_low_, inner_high_;
  std::vector<float> inner_action_;
};

}  // namespace rlrun
