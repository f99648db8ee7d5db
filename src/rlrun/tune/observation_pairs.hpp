#pragma once
// What TPE learns from: Optuna 3.1's _get_observation_pairs and _split_observation_pairs
// (optuna/samplers/_tpe/sampler.py), single-objective, without constraints or constant_liar.
//
// Every COMPLETE and PRUNED trial, in number order, gets a rank key (step, score), compared
// lexicographically, smaller is better:
//  * COMPLETE: (-inf, sign * value) — finished trials beat every pruned one;
//  * PRUNED with reports: (-last_step, sign * last intermediate value) — a trial pruned later
//    beats one pruned earlier; a NaN report scores +inf;
//  * PRUNED without reports: (1, 0) — after all of them;
// with sign = +1 when minimising, -1 when maximising. The best gamma(n) keys (a stable sort,
// ties in trial order) are "below", the rest "above"; both lists keep trial order, which the
// weights function relies on (oldest first).
#include <cstddef>
#include <vector>

#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

struct RankKey {
  double step = 0;   // -inf for COMPLETE, -last_step for PRUNED, 1 for PRUNED without reports
  double score = 0;  // sign * value
};

struct ObservationPairs {
  std::vector<RankKey> keys;  // one per COMPLETE or PRUNED trial, in trial order
  // Parameter -> its internal value in each of those trials, NaN where the trial lacks it.
  std::map<std::string, std::vector<double>> values;
};

// For the parameters of `space`. A trial "has" a parameter when it asked for it with a
// distribution of the same kind (categorical: the same choices) and, for log parameters, a
// positive value; Optuna takes any recorded value, rlrun skips one it cannot place in
// `space` (an index of other choices, a log of zero) instead of reading out of range.
ObservationPairs get_observation_pairs(const StudyView& study, const SearchSpace& space);

struct BelowAbove {
  std::vector<size_t> below;  // indices into the keys, ascending
  std::vector<size_t> above;
};

// The n_below best keys and the rest (numpy's stable argsort of (step, score); NaN last).
BelowAbove split_observation_pairs(const std::vector<RankKey>& keys, int n_below);

}  // namespace rlrun::tune
