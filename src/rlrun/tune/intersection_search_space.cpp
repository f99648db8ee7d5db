#include "rlrun/tune/intersection_search_space.hpp"

namespace rlrun::tune {

SearchSpace intersection_search_space(const std::vector<FrozenTrial>& trials, bool include_pruned) {
  bool first = true;
  SearchSpace space;
  for (const FrozenTrial& trial : trials) {
    const bool counts = trial.state == TrialState::kComplete ||
                        (include_pruned && trial.state == TrialState::kPruned);
    if (!counts) continue;
    if (first) {
      space = trial.distributions;
      first = false;
      continue;
    }
    // Optuna keeps a name when trial.distributions.get(name) == distribution: same kind and
    // same attributes (low, high, log, step; choices).
    for (auto it = space.begin(); it != space.end();) {
      auto found = trial.distributions.find(it->first);
      if (found == trial.distributions.end() || !(found->second == it->second))
        it = space.erase(it);
      else
        ++it;
    }
  }
  return space;
}

}  // namespace rlrun::tune
