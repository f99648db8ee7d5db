// RandomSampler as Optuna 3.1's (optuna/samplers/_random.py through optuna/_transform.py):
// draws stay in range and on the step grid, the grid's end points get a full cell, log ranges
// are uniform in log space, and a trial's draw depends only on (seed, trial number).
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <vector>

#include "rlrun/tune/random_sampler.hpp"

using namespace rlrun::tune;

TEST_CASE("random sampler: every kind stays in range and on its grid", "[tune]") {
  RandomSampler sampler;
  const std::vector<FrozenTrial> none;
  const StudyView study{StudyDirection::kMinimize, none};
  const std::vector<Distribution> kinds = {
      make_float_distribution("f", -2.0, 3.0, false, std::nullopt),
      make_float_distribution("fs", 0.1, 1.0, false, 0.3),  // grid 0.1, 0.4, 0.7, 1.0
      make_float_distribution("fl", 1e-5, 1e-1, true, std::nullopt),
      make_int_distribution("i", -3, 4, false, 1),
      make_int_distribution("is", 0, 9, false, 3),  // grid 0, 3, 6, 9
      make_int_distribution("il", 1, 1000, true, 1),
      make_categorical_distribution("c", {"a", 1, nullptr})};
  for (int trial = 0; trial < 300; ++trial) {
    sampler.reseed(11, trial);
    for (const Distribution& d : kinds) {
      const double x = sampler.sample_independent(study, "p", d);
      INFO(distribution_to_json(d) << " -> " << x);
      REQUIRE(contains(d, x));
    }
  }
}

TEST_CASE("random sampler: grid end points get as much mass as inner points", "[tune]") {
  RandomSampler sampler(5);
  const std::vector<FrozenTrial> none;
  const StudyView study{StudyDirection::kMinimize, none};
  const Distribution d = make_int_distribution("is", 0, 9, false, 3);
  std::map<double, int> counts;
  const int n = 8000;
  for (int i = 0; i < n; ++i) ++counts[sampler.sample_independent(study, "is", d)];
  REQUIRE(counts.size() == 4);
  for (const auto& [value, count] : counts) CHECK(count == Approx(n / 4).margin(n / 4 * 0.1));

  const Distribution c = make_categorical_distribution("c", {"a", "b", "c"});
  std::map<double, int> choices;
  for (int i = 0; i < n; ++i) ++choices[sampler.sample_independent(study, "c", c)];
  REQUIRE(choices.size() == 3);
  for (const auto& [value, count] : choices) CHECK(count == Approx(n / 3).margin(n / 3 * 0.1));

  // Log-uniform: half the draws below the geometric mean of the range.
  const Distribution fl = make_float_distribution("fl", 1e-4, 1.0, true, std::nullopt);
  int below = 0;
  for (int i = 0; i < n; ++i) below += sampler.sample_independent(study, "fl", fl) < 1e-2;
  CHECK(below == Approx(n / 2).margin(n * 0.03));
}

TEST_CASE("random sampler: a trial's draw depends only on the seed and the trial number",
          "[tune]") {
  const std::vector<FrozenTrial> none;
  const StudyView study{StudyDirection::kMinimize, none};
  const Distribution d = make_float_distribution("f", 0.0, 1.0, false, std::nullopt);
  RandomSampler a, b;
  a.reseed(42, 7);
  const double first = a.sample_independent(study, "f", d);
  for (int i = 0; i < 10; ++i) b.sample_independent(study, "f", d);  // b's stream moved on
  b.reseed(42, 7);
  CHECK(b.sample_independent(study, "f", d) == first);
  b.reseed(42, 8);
  CHECK(b.sample_independent(study, "f", d) != first);
  b.reseed(43, 7);
  CHECK(b.sample_independent(study, "f", d) != first);
}
