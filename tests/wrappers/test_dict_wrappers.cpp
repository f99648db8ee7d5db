// FrameStack and NormalizeObservation on Dict observations: key by key, as SB3's
// StackedObservations and VecNormalize(norm_obs_keys) treat Dict spaces.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "rlrun/envs/probe/dict_reach.hpp"
#include "rlrun/envs/probe/simple_multi_obs.hpp"
#include "rlrun/wrappers/frame_stack.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"

using namespace rlrun;

TEST_CASE("FrameStack stacks each key of a Dict of Boxes", "[wrappers]") {
  FrameStack::Config config;
  config.n_stack = 2;
  FrameStack env(std::make_unique<DictReach>(), config);
  const Space& space = env.observation_space();
  REQUIRE(space.keys() == std::vector<std::string>{"goal", "position"});
  CHECK(space.subspaces()[0] == Space::box(-1.0f, 1.0f, {2, 2}));
  CHECK(space.subspaces()[1] == Space::box(-1.0f, 1.0f, {2, 2}));
  std::vector<float> inner(4), obs(8), next(8);
  DictReach plain;
  plain.reset(3, inner);  // the same seed gives the same episode
  env.reset(3, obs);
  // Layout: goal frames (zero padding, then the reset one), position frames.
  CHECK(obs == std::vector<float>{0, 0, inner[0], inner[1], 0, 0, inner[2], inner[3]});
  const std::vector<float> action{1.0f, -1.0f};
  std::vector<float> inner_next(4);
  plain.step(action, inner_next);
  env.step(action, next);
  CHECK(next == std::vector<float>{inner[0], inner[1], inner_next[0], inner_next[1], inner[2],
                                   inner[3], inner_next[2], inner_next[3]});
  CHECK(space.contains(next));
  // SimpleMultiObsEnv has Discrete and MultiBinary keys: SB3 stacks Box keys only.
  CHECK_THROWS_WITH(FrameStack(std::make_unique<SimpleMultiObs>(), config),
                    Catch::Contains("key 'moves' is MultiBinary(4)"));
}

TEST_CASE("NormalizeObservation normalises the Box keys of a Dict", "[wrappers][normalize]") {
  NormalizeObservation env(std::make_unique<SimpleMultiObs>());
  const Space& space = env.observation_space();
  CHECK(space.subspaces()[0] == Space::multi_binary(4));  // moves: unchanged
  CHECK(space.subspaces()[1] == Space::discrete(4));      // row: unchanged
  CHECK(space.subspaces()[2] == Space::box(-10.0f, 10.0f, {5}));
  CHECK(env.statistics().dim() == 5);
  std::vector<float> obs(10);
  env.reset(1, obs);
  const std::span<const float> original = env.original_obs();
  // The first update from the initial statistics (mean 0, var 1, count 1e-4).
  RunningMeanStd expected(5);
  expected.update(original.subspan(5, 5));
  CHECK(env.statistics().mean() == expected.mean());
  for (int i = 0; i < 5; ++i)
    CHECK(obs[static_cast<size_t>(i)] == original[static_cast<size_t>(i)]);
  for (int k = 0; k < 5; ++k) {
    const double z = (original[5 + k] - expected.mean()[k]) / std::sqrt(expected.var()[k] + 1e-8);
    CHECK(obs[static_cast<size_t>(5 + k)] == static_cast<float>(std::clamp(z, -10.0, 10.0)));
  }
  CHECK(space.contains(obs));

  // norm_obs_keys picks keys; each must be a Box key of the Dict.
  NormalizeObservation::Config goal_only;
  goal_only.norm_obs_keys = {"goal"};
  NormalizeObservation reach(std::make_unique<DictReach>(), goal_only);
  CHECK(reach.observation_space().subspaces()[0] == Space::box(-10.0f, 10.0f, {2}));
  CHECK(reach.observation_space().subspaces()[1] == Space::box(-1.0f, 1.0f, {2}));
  CHECK(reach.statistics().dim() == 2);
  NormalizeObservation::Config row;
  row.norm_obs_keys = {"row"};
  CHECK_THROWS_WITH(NormalizeObservation(std::make_unique<SimpleMultiObs>(), row),
                    Catch::Contains("key 'row' is Discrete(4)"));
  NormalizeObservation::Config missing;
  missing.norm_obs_keys = {"rows"};
  CHECK_THROWS_WITH(NormalizeObservation(std::make_unique<SimpleMultiObs>(), missing),
                    Catch::Contains("'rows', which is not a key"));
}
