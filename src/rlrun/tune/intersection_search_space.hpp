#pragma once
// Optuna 3.1's IntersectionSearchSpace (optuna/samplers/_search_space/intersection.py): the
// parameters that every finished trial of interest has, with the same distribution in all of
// them. A parameter asked only in some trials (a conditional one: `net_arch` only when
// `policy == mlp`), or asked with a range that changed between trials, falls out, and TPE
// samples it on its own (sample_independent).
//
// Optuna caches the result across calls with a cursor over the trial numbers; recomputing it
// from all trials gives the same answer, and a study here holds at most thousands of trials.
#include <vector>

#include "rlrun/tune/sampler.hpp"

namespace rlrun::tune {

// Over the COMPLETE trials, and the PRUNED ones too with `include_pruned` (TPE's choice); empty
// when there are none. Running, waiting and failed trials never count.
SearchSpace intersection_search_space(const std::vector<FrozenTrial>& trials, bool include_pruned);

}  // namespace rlrun::tune
