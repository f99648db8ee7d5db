// env/numpy_random.hpp against numpy 1.24.2 (np.random.Generator(np.random.PCG64(
// np.random.SeedSequence(seed))).random(3)), and the classic-control envs' reset(seed=s) against
// Gymnasium 1.0.0's (gymnasium.make(id).reset(seed=s), then one reset without a seed): the
// numbers below are what those printed.
#include <catch2/catch.hpp>
#include <memory>
#include <vector>

#include "rlrun/env/numpy_random.hpp"
#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"

using namespace rlrun;

TEST_CASE("NumpyRandom draws numpy's PCG64 stream for a seed", "[seeding]") {
  struct Case {
    uint64_t seed;
    double first[3];
  };
  const Case cases[] = {
      {0, {0.63696168732145431, 0.26978671376387031, 0.040973523936194689}},
      {1, {0.51182162470025672, 0.9504636963259353, 0.14415961271963373}},
      {42, {0.77395604855596334, 0.43887843975205232, 0.85859791991138246}},
      {4294967303ULL, {0.77014095100347413, 0.1119272443176843, 0.18909773329712753}},
      {18446744073709551615ULL, {0.68002667896169311, 0.84531175856247431, 0.007403081599260064}},
  };
  for (const Case& c : cases) {
    INFO(c.seed);
    NumpyRandom random(c.seed);
    for (double expected : c.first) CHECK(random.uniform() == expected);
  }
  // A saved stream continues where it was.
  NumpyRandom a(9);
  a.uniform();
  NumpyRandom b;
  b.set_words(a.words());
  CHECK(a.next_u64() == b.next_u64());
}

TEST_CASE("classic-control envs reset to Gymnasium's initial state for a seed", "[seeding]") {
  struct Case {
    std::unique_ptr<Env> env;
    uint64_t seed;
    std::vector<float> seeded, next;  // reset(seed=seed), then reset()
  };
  std::vector<Case> cases;
  cases.push_back({std::make_unique<CartPole>(),
                   0,
                   {0.0136961685f, -0.0230213292f, -0.0459026471f, -0.0483472347f},
                   {0.0313270241f, 0.0412755571f, 0.0106635774f, 0.0229496565f}});
  cases.push_back({std::make_unique<CartPole>(),
                   123456789,
                   {-0.0472287275f, 0.0406700037f, 0.0381393544f, 0.0124897277f},
                   {0.0290714819f, 0.0325908028f, 0.0341705829f, -0.00282720523f}});
  cases.push_back({std::make_unique<Pendulum>(),
                   7,
                   {0.706682503f, 0.707530797f, 0.794427574f},
                   {-0.160688281f, 0.987005234f, -0.54958564f}});
  cases.push_back(
      {std::make_unique<Acrobot>(),
       0,
       {0.999624848f, 0.0273889117f, 0.998940229f, -0.0460263938f, -0.0918052942f, -0.0966944695f},
       {0.998037875f, 0.0626130626f, 0.996594608f, 0.082457386f, 0.0213271547f, 0.0458993129f}});
  cases.push_back({std::make_unique<MountainCar>(), 7, {-0.474980921f, 0}, {-0.420557231f, 0}});
  cases.push_back(
      {std::make_unique<MountainCarContinuous>(), 0, {-0.472607672f, 0}, {-0.546042681f, 0}});
  for (Case& c : cases) {
    INFO(c.env->id() << " seed " << c.seed);
    std::vector<float> obs(c.seeded.size());
    c.env->reset(c.seed, obs);
    for (size_t i = 0; i < obs.size(); ++i) CHECK(obs[i] == Approx(c.seeded[i]).margin(1e-8));
    c.env->reset(std::nullopt, obs);
    for (size_t i = 0; i < obs.size(); ++i) CHECK(obs[i] == Approx(c.next[i]).margin(1e-8));
  }
}
