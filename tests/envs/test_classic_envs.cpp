// Unit tests of the classic-control envs: the rules of each env (termination, clipping,
// rewards), spaces, seeding, initial-state ranges and the Config visitors. The physics itself
// is checked against Gymnasium in test_gym_reference.cpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rlrun/envs/classic/acrobot.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/envs/classic/mountain_car.hpp"
#include "rlrun/envs/classic/mountain_car_continuous.hpp"
#include "rlrun/envs/classic/pendulum.hpp"

using namespace rlrun;

namespace {

using Vec = std::vector<float>;

Vec obs_of(const Env& env) { return Vec(env.observation_space().flat_dim()); }

std::vector<std::unique_ptr<ClassicControlEnv>> all_envs() {
  std::vector<std::unique_ptr<ClassicControlEnv>> envs;
  envs.push_back(std::make_unique<CartPole>());
  envs.push_back(std::make_unique<Pendulum>());
  envs.push_back(std::make_unique<MountainCar>());
  envs.push_back(std::make_unique<MountainCarContinuous>());
  envs.push_back(std::make_unique<Acrobot>());
  return envs;
}

// Collects the names a Config::visit reports.
struct NameCollector {
  std::vector<std::string> names;
  template <class T>
  void operator()(const char* name, T&, const char* doc) {
    names.push_back(name);
    CHECK(std::string(doc).size() > 0);
  }
};

}  // namespace

TEST_CASE("classic envs have Gymnasium's ids, spaces and time limits", "[envs]") {
  CartPole cartpole;
  CHECK(cartpole.id() == "CartPole-v1");
  CHECK(cartpole.action_space().describe() == "Discrete(2)");
  CHECK(CartPole::kMaxEpisodeSteps == 500);
  const float theta = static_cast<float>(2 * 12 * 2 * std::numbers::pi / 360);
  constexpr float kInf = std::numeric_limits<float>::infinity();
  CHECK(cartpole.observation_space().low() == Vec{-4.8f, -kInf, -theta, -kInf});
  CHECK(cartpole.observation_space().high() == Vec{4.8f, kInf, theta, kInf});

  Pendulum pendulum;
  CHECK(pendulum.id() == "Pendulum-v1");
  CHECK(pendulum.action_space().describe() == "Box(-2.0, 2.0, (1,), float32)");
  CHECK(pendulum.observation_space().high() == Vec{1.0f, 1.0f, 8.0f});
  CHECK(Pendulum::kMaxEpisodeSteps == 200);

  MountainCar car;
  CHECK(car.id() == "MountainCar-v0");
  CHECK(car.action_space().describe() == "Discrete(3)");
  CHECK(car.observation_space().low() == Vec{-1.2f, -0.07f});
  CHECK(car.observation_space().high() == Vec{0.6f, 0.07f});
  CHECK(MountainCar::kMaxEpisodeSteps == 200);

  MountainCarContinuous continuous_car;
  CHECK(continuous_car.id() == "MountainCarContinuous-v0");
  CHECK(continuous_car.action_space().describe() == "Box(-1.0, 1.0, (1,), float32)");
  CHECK(continuous_car.observation_space() == car.observation_space());
  CHECK(MountainCarContinuous::kMaxEpisodeSteps == 999);

  Acrobot acrobot;
  CHECK(acrobot.id() == "Acrobot-v1");
  CHECK(acrobot.action_space().describe() == "Discrete(3)");
  CHECK(acrobot.observation_space().high() == Vec{1, 1, 1, 1,
                                                  static_cast<float>(4 * std::numbers::pi),
                                                  static_cast<float>(9 * std::numbers::pi)});
  CHECK(Acrobot::kMaxEpisodeSteps == 500);
}

TEST_CASE("Config structs hold Gymnasium's constructor defaults", "[envs]") {
  CHECK(CartPole::Config{}.sutton_barto_reward == false);
  CHECK(Pendulum::Config{}.g == 10.0);
  CHECK(MountainCar::Config{}.goal_velocity == 0.0);
  CHECK(MountainCarContinuous::Config{}.goal_velocity == 0.0);

  NameCollector names;
  CartPole::Config{}.visit(names);
  Pendulum::Config{}.visit(names);
  MountainCar::Config{}.visit(names);
  MountainCarContinuous::Config{}.visit(names);
  Acrobot::Config{}.visit(names);
  CHECK(names.names ==
        std::vector<std::string>{"sutton_barto_reward", "g", "goal_velocity", "goal_velocity"});
}

TEST_CASE("CartPole terminates outside |x| <= 2.4 and |theta| <= 12 degrees", "[envs]") {
  CartPole env;
  Vec obs = obs_of(env);
  env.reset(0, obs);
  const Vec push_right{1.0f};

  SECTION("cart position") {
    env.set_state(std::vector<double>{2.39, 1.0, 0.0, 0.0}, obs);  // x -> 2.41
    const StepResult r = env.step(push_right, obs);
    CHECK(r.terminated);
    CHECK_FALSE(r.truncated);
    CHECK(r.reward == 1.0);                          // the terminating step still pays 1
    CHECK(env.step(push_right, obs).reward == 0.0);  // stepping past termination pays 0
  }
  SECTION("inside the bounds it keeps going") {
    env.set_state(std::vector<double>{2.3, 1.0, 0.0, 0.0}, obs);  // x -> 2.32
    CHECK_FALSE(env.step(push_right, obs).terminated);
  }
  SECTION("pole angle") {
    const double threshold = 12 * 2 * std::numbers::pi / 360;
    env.set_state(std::vector<double>{0.0, 0.0, threshold - 0.001, 0.1}, obs);  // +0.002
    CHECK(env.step(push_right, obs).terminated);
    env.reset(0, obs);
    env.set_state(std::vector<double>{0.0, 0.0, -threshold + 0.001, -0.1}, obs);
    CHECK(env.step(push_right, obs).terminated);
  }
  SECTION("Sutton & Barto reward") {
    CartPole sb(CartPole::Config{.sutton_barto_reward = true});
    sb.reset(0, obs);
    CHECK(sb.step(push_right, obs).reward == 0.0);
    sb.set_state(std::vector<double>{2.39, 1.0, 0.0, 0.0}, obs);
    CHECK(sb.step(push_right, obs).reward == -1.0);
    CHECK(sb.step(push_right, obs).reward == -1.0);
  }
  SECTION("reset clears the post-termination count") {
    env.set_state(std::vector<double>{2.39, 1.0, 0.0, 0.0}, obs);
    env.step(push_right, obs);
    env.reset(1, obs);
    env.set_state(std::vector<double>{2.39, 1.0, 0.0, 0.0}, obs);
    CHECK(env.step(push_right, obs).reward == 1.0);
  }
}

TEST_CASE("Pendulum clips the torque and pays -(theta^2 + 0.1 thdot^2 + 0.001 u^2)", "[envs]") {
  Pendulum a, b;
  Vec obs_a = obs_of(a), obs_b = obs_of(b);
  a.reset(0, obs_a);
  b.reset(0, obs_b);
  const std::vector<double> start{0.5, -1.0};
  a.set_state(start, obs_a);
  b.set_state(start, obs_b);
  const StepResult ra = a.step(Vec{7.5f}, obs_a);
  const StepResult rb = b.step(Vec{2.0f}, obs_b);
  CHECK(obs_a == obs_b);
  CHECK(ra.reward == rb.reward);
  CHECK(ra.reward == Approx(-(0.25 + 0.1 * 1.0 + 0.001 * 4.0)).epsilon(1e-12));
  CHECK_FALSE(ra.terminated);
  CHECK_FALSE(ra.truncated);

  SECTION("the cost wraps the angle; the state does not") {
    Pendulum p;
    Vec obs = obs_of(p);
    p.reset(0, obs);
    p.set_state(std::vector<double>{2 * std::numbers::pi + 0.5, -1.0}, obs);
    CHECK(p.step(Vec{2.0f}, obs).reward == Approx(rb.reward).epsilon(1e-12));
    std::vector<double> state(2);
    p.get_state(state);
    CHECK(state[0] > 2 * std::numbers::pi);
  }
  SECTION("angular speed is clipped to 8") {
    Pendulum p;
    Vec obs = obs_of(p);
    p.reset(0, obs);
    p.set_state(std::vector<double>{std::numbers::pi / 2, 7.9}, obs);
    p.step(Vec{2.0f}, obs);
    CHECK(obs[2] == 8.0f);
  }
  SECTION("gravity comes from the Config") {
    Pendulum moon(Pendulum::Config{.g = 1.62});
    Vec obs = obs_of(moon);
    moon.reset(0, obs);
    moon.set_state(std::vector<double>{1.0, 0.0}, obs);
    moon.step(Vec{0.0f}, obs);
    CHECK(obs[2] == Approx(3 * 1.62 / 2 * std::sin(1.0) * 0.05).epsilon(1e-6));
  }
}

TEST_CASE("MountainCar walls, goal and reward", "[envs]") {
  MountainCar env;
  Vec obs = obs_of(env);
  env.reset(0, obs);
  SECTION("the left wall stops the car") {
    env.set_state(std::vector<double>{-1.19, -0.05}, obs);
    const StepResult r = env.step(Vec{0.0f}, obs);
    CHECK(obs[0] == -1.2f);
    CHECK(obs[1] == 0.0f);
    CHECK(r.reward == -1.0);
    CHECK_FALSE(r.terminated);
  }
  SECTION("reaching position 0.5 terminates") {
    env.set_state(std::vector<double>{0.49, 0.02}, obs);
    const StepResult r = env.step(Vec{2.0f}, obs);
    CHECK(r.terminated);
    CHECK(r.reward == -1.0);
  }
  SECTION("speed is clipped to 0.07") {
    env.set_state(std::vector<double>{-0.5, 0.0699}, obs);
    env.step(Vec{2.0f}, obs);
    CHECK(obs[1] == 0.07f);
  }
  SECTION("an action outside Discrete(3) is rejected") {
    CHECK_THROWS_AS(env.step(Vec{3.0f}, obs), std::invalid_argument);
    CHECK_THROWS_AS(env.step(Vec{0.5f}, obs), std::invalid_argument);
  }
}

TEST_CASE("MountainCarContinuous clips the force but not the action in the reward", "[envs]") {
  MountainCarContinuous a, b;
  Vec obs_a = obs_of(a), obs_b = obs_of(b);
  a.reset(0, obs_a);
  b.reset(0, obs_b);
  const std::vector<double> start{-0.5, 0.0};
  a.set_state(start, obs_a);
  b.set_state(start, obs_b);
  const StepResult ra = a.step(Vec{2.0f}, obs_a);
  const StepResult rb = b.step(Vec{1.0f}, obs_b);
  CHECK(obs_a == obs_b);
  CHECK(ra.reward == Approx(-0.4).epsilon(1e-12));
  CHECK(rb.reward == Approx(-0.1).epsilon(1e-12));

  SECTION("the goal pays 100 minus the action cost") {
    a.set_state(std::vector<double>{0.44, 0.02}, obs_a);
    const StepResult r = a.step(Vec{0.5f}, obs_a);
    CHECK(r.terminated);
    CHECK(r.reward == Approx(100.0 - 0.025).epsilon(1e-12));
  }
  SECTION("goal_velocity from the Config") {
    MountainCarContinuous strict(MountainCarContinuous::Config{.goal_velocity = 0.05});
    Vec obs = obs_of(strict);
    strict.reset(0, obs);
    strict.set_state(std::vector<double>{0.44, 0.02}, obs);
    CHECK_FALSE(strict.step(Vec{0.5f}, obs).terminated);
  }
}

TEST_CASE("Acrobot wraps angles, bounds speeds and terminates above the bar", "[envs]") {
  Acrobot env;
  Vec obs = obs_of(env);
  env.reset(0, obs);
  std::vector<double> state(4);
  SECTION("angles stay in [-pi, pi], speeds within bounds") {
    env.set_state(std::vector<double>{3.1, -3.1, 12.0, -28.0}, obs);
    for (int t = 0; t < 20; ++t) {
      env.step(Vec{2.0f}, obs);
      env.get_state(state);
      CHECK(std::abs(state[0]) <= std::numbers::pi);
      CHECK(std::abs(state[1]) <= std::numbers::pi);
      CHECK(std::abs(state[2]) <= 4 * std::numbers::pi);
      CHECK(std::abs(state[3]) <= 9 * std::numbers::pi);
      CHECK(env.observation_space().contains(obs));
    }
  }
  SECTION("the tip above one link length terminates with reward 0") {
    env.set_state(std::vector<double>{std::numbers::pi, 0.0, 0.0, 0.0}, obs);  // straight up
    const StepResult r = env.step(Vec{1.0f}, obs);
    CHECK(r.terminated);
    CHECK(r.reward == 0.0);
  }
  SECTION("hanging down pays -1") {
    const StepResult r = env.step(Vec{1.0f}, obs);
    CHECK_FALSE(r.terminated);
    CHECK(r.reward == -1.0);
  }
  SECTION("set_state right after reset stores float32, as Gymnasium's state array does") {
    env.set_state(std::vector<double>{0.1, 0.2, 0.3, 0.4}, obs);
    env.get_state(state);
    CHECK(state[0] == static_cast<double>(0.1f));
    env.step(Vec{1.0f}, obs);
    env.set_state(std::vector<double>{0.1, 0.2, 0.3, 0.4}, obs);  // float64 after a step
    env.get_state(state);
    CHECK(state[0] == 0.1);
  }
}

TEST_CASE("classic envs: seeding, initial states and API misuse", "[envs]") {
  for (auto& env : all_envs()) {
    INFO(env->id());
    Vec a = obs_of(*env), b = obs_of(*env), c = obs_of(*env);

    // Same seed, same start; the unseeded reset that follows continues the same stream.
    env->reset(7, a);
    env->reset(std::nullopt, b);
    env->reset(7, c);
    CHECK(a == c);
    env->reset(std::nullopt, c);
    CHECK(b == c);
    CHECK(a != b);
    env->reset(8, c);
    CHECK(a != c);

    // A first reset without any seed draws one from std::random_device.
    auto fresh = all_envs();
    for (auto& f : fresh)
      if (f->id() == env->id()) {
        Vec d = obs_of(*f), e = obs_of(*f);
        f->reset(std::nullopt, d);
        auto other = all_envs();
        for (auto& g : other)
          if (g->id() == env->id()) g->reset(std::nullopt, e);
        CHECK(d != e);
      }

    // Initial states stay in Gymnasium's uniform ranges.
    std::vector<double> s(env->state_dim());
    for (int i = 0; i < 200; ++i) {
      env->reset(std::nullopt, a);
      CHECK(env->observation_space().contains(a));
      env->get_state(s);
      if (env->id() == "CartPole-v1" || env->id() == "Acrobot-v1") {
        const double bound = env->id() == "CartPole-v1" ? 0.05 : 0.1;
        for (double v : s) CHECK(std::abs(v) <= bound);
        // acrobot.py: uniform(...).astype(np.float32) — the start state holds float32 values
        // (builds before the ClassicSpec refactor drew float64 ones: acrobot_dqn's results
        // changed with the fix).
        if (env->id() == "Acrobot-v1")
          for (double v : s) CHECK(v == static_cast<double>(static_cast<float>(v)));
      } else if (env->id() == "Pendulum-v1") {
        CHECK(std::abs(s[0]) <= std::numbers::pi);
        CHECK(std::abs(s[1]) <= 1.0);
      } else {
        CHECK(s[0] >= -0.6);
        CHECK(s[0] <= -0.4);
        CHECK(s[1] == 0.0);
      }
    }
    CHECK(env->info().keys().empty());
    CHECK_THROWS_AS(env->set_state(std::vector<double>(env->state_dim() + 1), a),
                    std::invalid_argument);
  }

  CartPole never_reset;
  Vec obs(4);
  CHECK_THROWS_AS(never_reset.step(Vec{1.0f}, obs), std::logic_error);
}
