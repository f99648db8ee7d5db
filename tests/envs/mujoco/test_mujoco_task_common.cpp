// What the MuJoCo tasks share: range kwargs ([low, high] with .inf, open intervals), NumPy's
// rounding in the tasks' Python (norm, float64 scalar x**2), the refusal of a model whose joint
// counts the task's arrays do not fit, and a range kwarg through the real rlrun binary.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "envs/mujoco/mujoco_task_test.hpp"
#include "rlrun/core/config_fields.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/envs/mujoco/half_cheetah.hpp"
#include "rlrun/envs/mujoco/hopper.hpp"
#include "rlrun/envs/mujoco/inverted_double_pendulum.hpp"
#include "rlrun/envs/mujoco/inverted_pendulum.hpp"
#include "rlrun/envs/mujoco/mujoco_model.hpp"
#include "rlrun/envs/mujoco/numpy_math.hpp"
#include "rlrun/envs/mujoco/pusher.hpp"
#include "rlrun/envs/mujoco/range_kwarg.hpp"
#include "rlrun/envs/mujoco/reacher.hpp"
#include "rlrun/envs/mujoco/swimmer.hpp"
#include "rlrun/envs/mujoco/walker2d.hpp"
#include "rlrun/state.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
using namespace rlrun::mujoco;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

RangeKwarg parse_interval(const std::string& text) {
  RangeKwarg out;
  decode(ConfigNode::load_string("range: " + text, "exp.yaml").child("range"), out);
  return out;
}

std::string emitted(const RangeKwarg& interval) {
  YAML::Emitter out;
  out << encode(interval);
  return out.c_str();
}

// Builds task T with `xml_file` set to a shipped model of another task.
template <class T>
std::function<void()> build_with(const std::string& model) {
  return [model] {
    typename T::Config config;
    config.xml_file.value = shipped_model_path(model);
    T env(config);
  };
}

}  // namespace

TEST_CASE("MuJoCo range kwargs: [low, high] with .inf, open at both ends", "[mujoco]") {
  CHECK(parse_interval("[0.7, .inf]") == RangeKwarg{0.7, kInf});
  CHECK(parse_interval("[-.inf, +.INF]") == RangeKwarg{-kInf, kInf});
  CHECK(parse_interval("[-1, 1]") == RangeKwarg{-1.0, 1.0});
  CHECK(parse_interval("[2, 2]") == RangeKwarg{2.0, 2.0});  // empty, as Gymnasium allows
  CHECK_THROWS_WITH(parse_interval("[1]"),
                    Catch::Contains("exp.yaml:1:8") && Catch::Contains("expected [low, high]"));
  CHECK_THROWS_WITH(parse_interval("0.7"), Catch::Contains("expected [low, high]"));
  CHECK_THROWS_WITH(parse_interval("[2, 1]"), Catch::Contains("low <= high"));
  CHECK_THROWS_WITH(parse_interval("[0, inf]"),
                    Catch::Contains("expected a number, .inf or -.inf"));
  CHECK_THROWS_WITH(parse_interval("[.nan, 1]"), Catch::Contains("NaN is not a setting"));
  CHECK_THROWS_WITH(parse_interval("[a, 1]"), Catch::Contains("expected a number"));

  CHECK(emitted({0.7, kInf}) == "[0.7, .inf]");
  CHECK(emitted({-kInf, 100.0}) == "[-.inf, 100.0]");
  CHECK(parse_interval(emitted({-kInf, kInf})) == RangeKwarg{-kInf, kInf});

  const RangeKwarg z{0.7, kInf};
  CHECK_FALSE(z.strictly_inside(0.7));
  CHECK(z.strictly_inside(std::nextafter(0.7, 1.0)));
  CHECK(z.strictly_inside(1e300));
  CHECK_FALSE(z.strictly_inside(kInf));
  CHECK_FALSE(z.strictly_inside(std::nan("")));

  // A task's whole resolved config reads back to itself (run directories, model files).
  const YAML::Node written = write_config(Hopper::Config{});
  YAML::Emitter text;
  text << written;
  const Hopper::Config read =
      read_config<Hopper::Config>(ConfigNode::load_string(text.c_str(), "config.yaml"));
  CHECK(read.healthy_z_range == RangeKwarg{0.7, kInf});
  CHECK(read.healthy_state_range == RangeKwarg{-100.0, 100.0});
}

TEST_CASE("MuJoCo tasks round as NumPy does: norm, and a float64 scalar's x**2", "[mujoco]") {
  Rng rng(21);
  int pow_differs_from_product = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = rng.uniform(-10.0, 10.0);
    CHECK(scalar_squared(x) == numpy_scalar_pow2(x));
    pow_differs_from_product += scalar_squared(x) != x * x;
    const std::vector<double> v = random_values(rng, 3, -1.0, 1.0);
    CHECK(euclidean_norm(v) == numpy_norm(v));
  }
  // glibc's pow(x, 2.0) is not always the rounded square (NumPy 1.24 on Debian 12: 186 of
  // 200 000 random values); a compiler that folded it into x * x would lose that.
  CHECK(pow_differs_from_product > 0);
}

TEST_CASE("MuJoCo tasks refuse a model whose joint counts their arrays do not fit", "[mujoco]") {
  // xml_file may name any shipped model, even from untrusted text: the task must not read or
  // write past its observation (Pusher's 21 values in HalfCheetah's 17 did).
  CHECK_THROWS_AS(build_with<HalfCheetah>("pusher.xml")(), ConfigError);
  CHECK_THROWS_WITH(build_with<HalfCheetah>("pusher.xml")(),
                    Catch::Contains("pusher.xml: HalfCheetah-v4 needs a model with nq=9, nv=9, "
                                    "nu=6") &&
                        Catch::Contains("this one has nq=11, nv=11, nu=7"));
  CHECK_THROWS_AS(build_with<Hopper>("walker2d.xml")(), ConfigError);
  CHECK_THROWS_AS(build_with<Walker2d>("hopper.xml")(), ConfigError);
  CHECK_THROWS_AS(build_with<Swimmer>("reacher.xml")(), ConfigError);
  CHECK_THROWS_AS(build_with<InvertedPendulum>("inverted_double_pendulum.xml")(), ConfigError);
  CHECK_THROWS_AS(build_with<InvertedDoublePendulum>("inverted_pendulum.xml")(), ConfigError);
  CHECK_THROWS_AS(build_with<Reacher>("swimmer.xml")(), ConfigError);  // no fingertip body
  CHECK_THROWS_AS(build_with<Pusher>("half_cheetah.xml")(), ConfigError);
  CHECK_NOTHROW(build_with<Hopper>("hopper.xml")());

  // InvertedDoublePendulum reads site_xpos[0]: its model without the tip site is refused too.
  TempDir dir("mujoco_no_site");
  std::string text = read_text(shipped_model_path("inverted_double_pendulum.xml"));
  const std::string site = "<site name=\"tip\" pos=\"0 0 .6\" size=\"0.01 0.01\"/>";
  REQUIRE(text.find(site) != std::string::npos);
  text.replace(text.find(site), site.size(), "");
  std::ofstream(dir / "no_site.xml") << text;
  InvertedDoublePendulum::Config no_site;
  no_site.xml_file.value = dir / "no_site.xml";
  CHECK_THROWS_WITH(InvertedDoublePendulum(no_site), Catch::Contains("needs a model with a site"));
}

namespace {

// Steps `env` and a copy restored from its saved state with the same actions: both must give
// the same observations, rewards, ends and info, bit for bit.
template <class T>
void check_resume(uint64_t seed) {
  T env, copy;
  const size_t n_obs = static_cast<size_t>(env.observation_space().shape()[0]);
  const int n_act = env.action_space().shape()[0];
  const double bound = env.action_space().high()[0];
  std::vector<float> obs(n_obs), obs_copy(n_obs);
  env.reset(seed, obs);
  copy.reset(seed + 1, obs_copy);
  Rng rng(seed);
  for (int i = 0; i < 25; ++i)
    if (env.step(random_controls(rng, n_act, bound), obs).terminated) env.reset(std::nullopt, obs);
  TensorMap tensors;
  StateWriter writer(tensors, "env.");
  env.write_state(writer);
  copy.read_state(StateReader(tensors, "env."));
  for (int i = 0; i < 25; ++i) {
    const std::vector<float> action = random_controls(rng, n_act, bound);
    const StepResult a = env.step(action, obs);
    const StepResult b = copy.step(action, obs_copy);
    INFO(env.id() << " step " << i);
    CHECK(a.reward == b.reward);
    CHECK(a.terminated == b.terminated);
    CHECK(obs == obs_copy);
    CHECK(env.info().values() == copy.info().values());
    if (a.terminated) {
      env.reset(std::nullopt, obs);
      copy.reset(std::nullopt, obs_copy);
      CHECK(obs == obs_copy);
    }
  }
}

}  // namespace

TEST_CASE("MuJoCo tasks: a saved state resumes bit for bit", "[mujoco]") {
  check_resume<Hopper>(1);
  check_resume<Walker2d>(2);
  check_resume<Swimmer>(3);
  check_resume<InvertedPendulum>(4);
  check_resume<InvertedDoublePendulum>(5);
  check_resume<Reacher>(6);
  check_resume<Pusher>(7);
}

TEST_CASE("cli: a MuJoCo range kwarg with .inf trains, is recorded and evaluates", "[mujoco]") {
  TempDir dir("mujoco_range");
  const std::string config = dir / "hopper.yaml";
  std::ofstream(config) << "run: {name: hop, seed: 1, total_timesteps: 128, out_dir: " + dir.str() +
                               "/runs}\n"
                               "env: {id: Hopper-v4, kwargs: {healthy_z_range: [0.5, .inf], "
                               "terminate_when_unhealthy: false}}\n"
                               "algo: {id: PPO, n_steps: 64, batch_size: 32, n_epochs: 1}\n";
  const CommandResult train = run_rlrun("train " + config);
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run = dir / "runs/hop/seed1";
  CHECK(read_text(run + "/config.yaml").find("healthy_z_range: [0.5, .inf]") != std::string::npos);
  const CommandResult eval = run_rlrun("eval --model " + run + "/model.zip --episodes 1");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  // Never terminated: the one episode runs to the time limit.
  CHECK(eval.output.find("mean_ep_length = 1000.0") != std::string::npos);
}
