// check_env (gymnasium/utils/env_checker.py in spirit): passes the classic envs, flags each
// deliberately broken fake in tests/fakes/broken_envs.hpp with a message saying why.
#include <catch2/catch.hpp>
#include <memory>
#include <string>
#include <vector>

#include "fakes/broken_envs.hpp"
#include "rlrun/env/env_checker.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"
#include "rlrun/wrappers/time_limit.hpp"

using namespace rlrun;
using namespace rlrun::testing;

namespace {

std::string joined(const std::vector<std::string>& problems) {
  std::string s;
  for (const auto& p : problems) s += p + "\n";
  return s;
}

template <class E>
EnvPtr limited() {
  return std::make_unique<TimeLimit>(std::make_unique<E>(), E::kMaxEpisodeSteps);
}

}  // namespace

TEST_CASE("check_env passes the classic-control envs", "[envs][env_checker]") {
  std::vector<EnvPtr> envs;
  envs.push_back(limited<CartPole>());
  envs.push_back(limited<Pendulum>());
  envs.push_back(limited<MountainCar>());
  envs.push_back(limited<MountainCarContinuous>());
  envs.push_back(limited<Acrobot>());
  envs.push_back(std::make_unique<CartPole>());  // unwrapped, too
  for (auto& env : envs) {
    for (uint64_t seed : {0, 123}) {
      const auto problems = check_env(*env, seed, 300);
      INFO(env->id() << " seed " << seed << ":\n" << joined(problems));
      CHECK(problems.empty());
    }
  }
  // Short time limits make the check cross many episode ends.
  TimeLimit short_pendulum(std::make_unique<Pendulum>(), 7);
  CHECK(check_env(short_pendulum).empty());
}

TEST_CASE("check_env catches broken envs", "[envs][env_checker]") {
  SECTION("a correct fake passes, a fixed start is not mistaken for ignoring the seed") {
    BrokenEnvBase ok;
    CHECK(joined(check_env(ok)) == "");
    FixedStartEnv fixed;
    CHECK(joined(check_env(fixed)) == "");
  }
  SECTION("observation outside the space") {
    ObsOutOfSpaceEnv env;
    CHECK_THAT(joined(check_env(env)),
               Catch::Contains("is not inside Box(-1.0, 1.0, (2,), float32)"));
  }
  SECTION("seed ignored: random resets") {
    SeedIgnoringEnv env;
    CHECK_THAT(joined(check_env(env)), Catch::Contains("reset(seed) is not deterministic"));
  }
  SECTION("seed ignored: every seed gives the same start") {
    ConstantSeedEnv env;
    CHECK_THAT(joined(check_env(env)), Catch::Contains("ignores the seed"));
  }
  SECTION("non-deterministic steps") {
    NondeterministicStepEnv env;
    CHECK_THAT(joined(check_env(env)), Catch::Contains("gave different observations"));
  }
  SECTION("non-finite reward") {
    NanRewardEnv env;
    CHECK_THAT(joined(check_env(env)), Catch::Contains("non-finite reward"));
  }
  SECTION("cannot reset after an episode ended") {
    NoSecondEpisodeEnv env;
    CHECK_THAT(joined(check_env(env)), Catch::Contains("simulator died"));
  }
}
