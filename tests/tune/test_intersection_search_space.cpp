// Optuna 3.1's IntersectionSearchSpace(include_pruned=...) (optuna/samplers/_search_space/
// intersection.py) over trials with conditional parameters and a changed range.
#include <catch2/catch.hpp>
#include <vector>

#include "rlrun/tune/intersection_search_space.hpp"
#include "rlrun/tune/tpe_sampler.hpp"

using namespace rlrun::tune;

namespace {

FrozenTrial trial(int number, TrialState state, const SearchSpace& asked) {
  FrozenTrial t;
  t.number = number;
  t.state = state;
  t.distributions = asked;
  for (const auto& [name, d] : asked) t.params[name] = 0;
  if (state == TrialState::kComplete) t.values = std::vector<double>{0.0};
  return t;
}

}  // namespace

TEST_CASE("intersection search space: conditional and changed parameters fall out", "[tune]") {
  const Distribution lr = make_float_distribution("lr", 1e-5, 1, true, std::nullopt);
  const Distribution policy = make_categorical_distribution("policy", {"mlp", "cnn"});
  const Distribution width = make_int_distribution("width", 16, 256, true, 1);
  const Distribution kernel = make_int_distribution("kernel", 3, 7, false, 2);
  const Distribution gamma_a = make_float_distribution("gamma", 0.9, 0.999, false, std::nullopt);
  const Distribution gamma_b = make_float_distribution("gamma", 0.9, 0.9999, false, std::nullopt);
  const Distribution fixed = make_int_distribution("fixed", 4, 4, false, 1);

  std::vector<FrozenTrial> trials = {
      trial(
          0, TrialState::kComplete,
          {{"lr", lr}, {"policy", policy}, {"width", width}, {"gamma", gamma_a}, {"fixed", fixed}}),
      trial(1, TrialState::kPruned,
            {{"lr", lr},
             {"policy", policy},
             {"kernel", kernel},
             {"gamma", gamma_a},
             {"fixed", fixed}}),
      // Failed and running trials do not count, whatever they asked.
      trial(2, TrialState::kFail, {{"lr", lr}}),
      trial(3, TrialState::kRunning, {{"policy", policy}}),
  };
  SearchSpace space = intersection_search_space(trials, true);
  CHECK(space.size() == 4);
  CHECK(space.count("lr"));
  CHECK(space.count("policy"));
  CHECK(space.count("gamma"));
  CHECK(space.count("fixed"));
  CHECK(!space.count("width"));   // only in trial 0
  CHECK(!space.count("kernel"));  // only in trial 1
  // Without pruned trials, trial 0 alone decides.
  CHECK(intersection_search_space(trials, false).count("width"));

  // A range that changed between trials is no longer joint.
  trials.push_back(trial(4, TrialState::kComplete,
                         {{"lr", lr}, {"policy", policy}, {"gamma", gamma_b}, {"fixed", fixed}}));
  space = intersection_search_space(trials, true);
  CHECK(!space.count("gamma"));
  CHECK(space.count("lr"));

  // TPE's relative space also drops single-valued distributions.
  TpeSampler tpe;
  const SearchSpace relative = tpe.infer_relative_search_space({StudyDirection::kMinimize, trials});
  CHECK(relative.size() == 2);
  CHECK(relative.count("lr"));
  CHECK(relative.count("policy"));
  TpeConfig univariate;
  univariate.multivariate = false;
  TpeSampler independent(univariate);
  CHECK(independent.infer_relative_search_space({StudyDirection::kMinimize, trials}).empty());

  CHECK(intersection_search_space({}, true).empty());
}
