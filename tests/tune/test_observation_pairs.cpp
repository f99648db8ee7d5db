// TPE's ranking of trials and its below/above split, as Optuna 3.1's _get_observation_pairs
// and _split_observation_pairs (optuna/samplers/_tpe/sampler.py), plus default_gamma.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "rlrun/tune/observation_pairs.hpp"
#include "rlrun/tune/tpe_sampler.hpp"

using namespace rlrun::tune;

namespace {

const Distribution kX = make_float_distribution("x", 0, 10, false, std::nullopt);

FrozenTrial complete(int number, double x, double value) {
  FrozenTrial t;
  t.number = number;
  t.state = TrialState::kComplete;
  t.params["x"] = x;
  t.distributions["x"] = kX;
  t.values = std::vector<double>{value};
  return t;
}

FrozenTrial pruned(int number, double x, std::map<int64_t, double> reports) {
  FrozenTrial t;
  t.number = number;
  t.state = TrialState::kPruned;
  t.params["x"] = x;
  t.distributions["x"] = kX;
  t.intermediate_values = std::move(reports);
  return t;
}

}  // namespace

TEST_CASE("observation pairs: default_gamma is ceil(n / 10) capped at 25", "[tune]") {
  CHECK(default_gamma(0) == 0);
  CHECK(default_gamma(1) == 1);
  CHECK(default_gamma(10) == 1);
  CHECK(default_gamma(11) == 2);
  CHECK(default_gamma(100) == 10);
  CHECK(default_gamma(249) == 25);
  CHECK(default_gamma(1000) == 25);
}

TEST_CASE("observation pairs: complete trials beat pruned ones, later pruning beats earlier",
          "[tune]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<FrozenTrial> trials = {
      pruned(0, 0.0, {{1, 0.1}, {5, 0.4}}),  // last step 5, value 0.4   -> (-5, 0.4)
      complete(1, 1.0, 3.0),                 //                          -> (-inf, 3)
      pruned(2, 2.0, {}),                    // no reports               -> (1, 0)
      complete(3, 3.0, 1.0),                 //                          -> (-inf, 1)
      pruned(4, 4.0, {{5, 0.2}}),            //                          -> (-5, 0.2)
      pruned(5, 5.0, {{9, nan}}),            // NaN report               -> (-9, inf)
      complete(6, 6.0, 2.0),                 //                          -> (-inf, 2)
  };
  FrozenTrial running;  // RUNNING and FAIL trials are not observations
  running.number = 7;
  trials.push_back(running);
  FrozenTrial failed = complete(8, 8.0, -100.0);
  failed.state = TrialState::kFail;
  trials.push_back(failed);

  const ObservationPairs pairs =
      get_observation_pairs({StudyDirection::kMinimize, trials}, {{"x", kX}});
  REQUIRE(pairs.keys.size() == 7);
  CHECK(pairs.keys[0].step == -5);
  CHECK(pairs.keys[1].step == -INFINITY);
  CHECK(pairs.keys[2].step == 1);
  CHECK(pairs.keys[5].score == INFINITY);
  CHECK(pairs.values.at("x") == std::vector<double>{0, 1, 2, 3, 4, 5, 6});

  // Order: 3 (1.0), 6 (2.0), 1 (3.0), 5 (-9, inf), 4 (-5, 0.2), 0 (-5, 0.4), 2 (1, 0).
  BelowAbove split = split_observation_pairs(pairs.keys, 4);
  CHECK(split.below == std::vector<size_t>{1, 3, 5, 6});  // back in trial order
  CHECK(split.above == std::vector<size_t>{0, 2, 4});
  split = split_observation_pairs(pairs.keys, 6);
  CHECK(split.below == std::vector<size_t>{0, 1, 3, 4, 5, 6});
  CHECK(split.above == std::vector<size_t>{2});

  // Maximising flips the sign of values (and of reports); ties keep trial order.
  const ObservationPairs maxi =
      get_observation_pairs({StudyDirection::kMaximize, trials}, {{"x", kX}});
  split = split_observation_pairs(maxi.keys, 1);
  CHECK(split.below == std::vector<size_t>{1});  // value 3.0 is the best when maximising
  std::vector<RankKey> ties = {{-INFINITY, 1.0}, {-INFINITY, 1.0}, {-INFINITY, 1.0}};
  CHECK(split_observation_pairs(ties, 2).below == std::vector<size_t>{0, 1});
}

TEST_CASE("observation pairs: a trial without the parameter, or with other choices, is NaN",
          "[tune]") {
  const Distribution c = make_categorical_distribution("c", {"a", "b"});
  std::vector<FrozenTrial> trials = {complete(0, 1.0, 1.0), complete(1, 2.0, 2.0),
                                     complete(2, 3.0, 3.0)};
  trials[0].params["c"] = 1;
  trials[0].distributions["c"] = c;
  trials[2].params["c"] = 2;  // index 2 of three choices: not a value of `c`
  trials[2].distributions["c"] = make_categorical_distribution("c", {"a", "b", "z"});
  const ObservationPairs pairs =
      get_observation_pairs({StudyDirection::kMinimize, trials}, {{"c", c}, {"x", kX}});
  REQUIRE(pairs.keys.size() == 3);
  CHECK(pairs.values.at("c")[0] == 1);
  CHECK(std::isnan(pairs.values.at("c")[1]));
  CHECK(std::isnan(pairs.values.at("c")[2]));
}
