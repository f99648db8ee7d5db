#pragma once
// `eval --policy a,b,c`: several policies' evaluations side by side, one row per policy, as a
// Markdown table (it reads as one in a terminal too: the cells are padded to their column).
#include <string>
#include <utility>
#include <vector>

#include "rlrun/runtime/run/evaluator.hpp"

namespace rlrun::cli {

// Columns: policy, mean_reward, std_reward, mean_ep_length, success_rate when any policy's env
// reports is_success, then the env's metrics (each the mean over the policy's episodes) in the
// first run's order; every run comes from the same env id, so they share the keys.
std::string comparison_table(const std::vector<std::pair<std::string, EvalResult>>& runs);

}  // namespace rlrun::cli
