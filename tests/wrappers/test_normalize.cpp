// NormalizeObservation / NormalizeReward against SB3's VecNormalize. The expected numbers come
// from numpy running SB3's formulas (running_mean_std.py, vec_normalize.py) over a
// DummyVecEnv of the same scripted env (script in the comment at the end of this file);
// with one env rlrun must agree bit for bit.
#include <catch2/catch.hpp>

#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/normalize_reward.hpp"
#include "wrappers/scripted_env.hpp"

using namespace rlrun;
using rlrun::testing::ScriptedEnv;

namespace {

std::unique_ptr<ScriptedEnv> scripted() {
  return std::make_unique<ScriptedEnv>(
      std::vector<std::vector<float>>{{1.0f, -2.0f}, {2.0f, 2.0f}, {-0.5f, 0.75f}},
      std::vector<std::vector<float>>{{1.5f, 0.5f},
                                      {3.0f, -1.0f},
                                      {0.25f, 4.0f},
                                      {-1.0f, 1.0f},
                                      {0.5f, 0.5f},
                                      {2.5f, -3.0f},
                                      {1.0f, 1.0f}},
      std::vector<double>{1.0, 0.5, 2.0, -1.0, 3.0, 0.0, 1.5}, 3);
}

void check_obs(const Eigen::VectorXf& got, double a, double b) {
  CHECK(got(0) == static_cast<float>(a));
  CHECK(got(1) == static_cast<float>(b));
}

}  // namespace

TEST_CASE("NormalizeObservation + NormalizeReward match SB3 VecNormalize with one env",
          "[wrappers][normalize]") {
  NormalizeReward::Config reward_config;
  reward_config.gamma = 0.9;
  std::vector<EnvPtr> envs;
  envs.push_back(std::make_unique<NormalizeReward>(
      std::make_unique<NormalizeObservation>(scripted()), reward_config));
  VecEnv vec(std::move(envs));
  auto* obs_norm = find_wrapper<NormalizeObservation>(vec.env(0));
  auto* rew_norm = find_wrapper<NormalizeReward>(vec.env(0));
  REQUIRE(obs_norm);
  REQUIRE(rew_norm);
  CHECK(obs_norm->observation_space().describe() == "Box(-10.0, 10.0, (2,), float32)");

  vec.reset();
  check_obs(vec.obs().col(0), 0.007070714142173529, -0.008944093249738216);
  // Per step: normalised observation (after the auto-reset), normalised reward.
  const double expected_obs[7][2] = {
      {0.9992512464523315, 0.999970018863678},    {1.3727695941925049, -0.16224682331085205},
      {0.16907890141010284, 1.4021440744400024},  {-1.733661413192749, 0.6301305890083313},
      {-0.5345045924186707, 0.25400322675704956}, {-1.1043040752410889, 0.40584349632263184},
      {0.051649369299411774, 0.556698739528656}};
  const double expected_reward[7] = {
      10.0, 2.496258403996981, 2.030892758195361, -0.6608652525713191, 2.1365260904950847,
      0.0,  1.24861552293566};
  const Eigen::MatrixXf action = Eigen::MatrixXf::Zero(1, 1);
  for (int t = 0; t < 7; ++t) {
    INFO("step " << t);
    vec.step(action);
    check_obs(vec.obs().col(0), expected_obs[t][0], expected_obs[t][1]);
    CHECK(vec.rewards()(0) == expected_reward[t]);  // step 0: 1 / sqrt(1e-4-ish var) clipped to 10
    CHECK(vec.done(0) == ((t + 1) % 3 == 0));
  }
  // The statistics after 8 observations (3 resets + 5 non-final steps) and 7 returns.
  const RunningMeanStd& obs_rms = obs_norm->statistics();
  CHECK(obs_rms.mean()(0) == 0.9374882813964825);
  CHECK(obs_rms.mean()(1) == 0.34374570317871034);
  CHECK(obs_rms.var()(0) == 1.4648489255792279);
  CHECK(obs_rms.var()(1) == 1.3896450439692682);
  CHECK(obs_rms.count() == 8.0001);
  const RunningMeanStd& ret_rms = rew_norm->statistics();
  CHECK(ret_rms.mean()(0) == 1.4499792860101999);
  CHECK(ret_rms.var()(0) == 1.4431951324976031);
  CHECK(ret_rms.count() == 7.0001);
}

TEST_CASE("NormalizeObservation: the final observation uses the statistics before the reset one",
          "[wrappers][normalize]") {
  // The documented difference from VecNormalize (whose terminal_observation is normalised after
  // the auto-reset observation was added): numpy values of that variant.
  std::vector<EnvPtr> envs;
  envs.push_back(std::make_unique<NormalizeObservation>(scripted()));
  VecEnv vec(std::move(envs));
  vec.reset();
  const Eigen::MatrixXf action = Eigen::MatrixXf::Zero(1, 1);
  for (int t = 0; t < 3; ++t) vec.step(action);
  REQUIRE(vec.done(0));
  check_obs(vec.final_obs().col(0), -1.862874984741211, 4.704346656799316);
  for (int t = 3; t < 6; ++t) vec.step(action);
  REQUIRE(vec.done(0));
  check_obs(vec.final_obs().col(0), 1.0690559148788452, -2.413008451461792);
}

TEST_CASE("NormalizeObservation: clipping, frozen statistics and their round trip",
          "[wrappers][normalize]") {
  NormalizeObservation::Config config;
  config.clip_obs = 0.5;
  NormalizeObservation env(scripted(), config);
  CHECK(env.observation_space().describe() == "Box(-0.5, 0.5, (2,), float32)");
  std::vector<float> obs(2);
  env.reset(std::nullopt, obs);
  // After reset (1, -2) and step (1.5, 0.5) the statistics are ~mean (1.25, -0.75), std
  // (0.25, 1.25): the step's observation is one std above the mean, clipped to 0.5.
  std::vector<float> action{0.0f};
  env.step(action, obs);
  CHECK(obs[0] == 0.5f);
  CHECK(obs[1] == 0.5f);
  CHECK(std::vector<float>(env.original_obs().begin(), env.original_obs().end()) ==
        std::vector<float>{1.5f, 0.5f});

  // Frozen: stepping leaves the statistics alone.
  TensorMap saved;
  save_model_statistics(env, saved);
  CHECK(saved.count("wrappers/NormalizeObservation/mean") == 1);
  CHECK(saved.count("wrappers/NormalizeObservation/var") == 1);
  CHECK(saved.count("wrappers/NormalizeObservation/count") == 1);
  env.set_training(false);
  const double count = env.statistics().count();
  env.step(action, obs);
  env.reset(std::nullopt, obs);
  CHECK(env.statistics().count() == count);

  // Another wrapper gets the same statistics and is frozen by load_model_statistics.
  NormalizeObservation other(scripted(), config);
  load_model_statistics(other, saved, /*training=*/false);
  CHECK_FALSE(other.training());
  CHECK(other.statistics().mean() == env.statistics().mean());
  CHECK(other.statistics().var() == env.statistics().var());
  CHECK(other.statistics().count() == count);

  // A file without the statistics is refused with the key that is missing.
  NormalizeObservation third(scripted(), config);
  CHECK_THROWS_WITH(load_model_statistics(third, TensorMap{}, false),
                    Catch::Contains("wrappers/NormalizeObservation/mean"));
  CHECK_THROWS_AS(
      NormalizeObservation(std::make_unique<ScriptedEnv>(std::vector<std::vector<float>>{{0.0f}},
                                                         std::vector<std::vector<float>>{{0.0f}},
                                                         std::vector<double>{0.0}, 1),
                           NormalizeObservation::Config{-1.0, 1e-8, {}, {}}),
      std::invalid_argument);
}

TEST_CASE(
    "NormalizeObservation: freeze_after stops the updates after N observations, also "
    "after a save and load",
    "[wrappers][normalize]") {
  NormalizeObservation::Config frozen_config;
  frozen_config.freeze_after = 4;
  NormalizeObservation frozen(scripted(), frozen_config);
  NormalizeObservation running(scripted());
  std::vector<float> a(2), b(2), action{0.0f};
  frozen.reset(std::nullopt, a);
  running.reset(std::nullopt, b);
  // Episodes of 3 steps: reset, 2 steps, (the final observation is not counted) reset = 4
  // observations; the frozen wrapper has the running one's statistics up to there.
  for (int t = 0; t < 3; ++t) {
    const StepResult ra = frozen.step(action, a);
    running.step(action, b);
    if (ra.terminated || ra.truncated) {
      frozen.reset(std::nullopt, a);
      running.reset(std::nullopt, b);
    }
  }
  CHECK(frozen.statistics().count() == running.statistics().count());
  CHECK(frozen.statistics().mean() == running.statistics().mean());
  CHECK(frozen.statistics().count() >= 4.0);
  CHECK(frozen.statistics().count() < 5.0);
  const Eigen::VectorXd mean_at_freeze = frozen.statistics().mean();
  for (int t = 0; t < 3; ++t) {
    frozen.step(action, a);
    running.step(action, b);
  }
  CHECK(frozen.statistics().mean() == mean_at_freeze);
  CHECK(frozen.statistics().count() < 5.0);
  CHECK(running.statistics().count() > 5.0);
  CHECK(frozen.training());  // still training: only the statistics stand still

  // A resumed run (statistics loaded, training) freezes where the original did.
  TensorMap saved;
  save_model_statistics(frozen, saved);
  NormalizeObservation resumed(scripted(), frozen_config);
  load_model_statistics(resumed, saved, /*training=*/true);
  resumed.reset(std::nullopt, a);
  resumed.step(action, a);
  CHECK(resumed.statistics().mean() == mean_at_freeze);
  CHECK(resumed.statistics().count() == frozen.statistics().count());
}

TEST_CASE("Normalize wrappers: the n envs of a VecEnv share one set of statistics",
          "[wrappers][normalize]") {
  std::vector<EnvPtr> envs;
  for (int i = 0; i < 3; ++i)
    envs.push_back(
        std::make_unique<NormalizeReward>(std::make_unique<NormalizeObservation>(scripted())));
  VecEnv vec(std::move(envs));
  share_model_statistics(vec);
  vec.reset();
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, 3);
  vec.step(actions);
  for (int i = 0; i < 3; ++i) {
    // 3 reset observations + 3 step observations in one object.
    CHECK(find_wrapper<NormalizeObservation>(vec.env(i))->statistics().count() ==
          Approx(6.0001).epsilon(1e-12));
    CHECK(find_wrapper<NormalizeReward>(vec.env(i))->statistics().count() ==
          Approx(3.0001).epsilon(1e-12));
  }
  // Same statistics as one batch update (SB3's update with all envs): mean of 3x reset[0] and
  // 3x step[0] with the 1e-4 prior sample at 0.
  const auto& mean = find_wrapper<NormalizeObservation>(vec.env(2))->statistics().mean();
  CHECK(mean(0) == Approx((3 * 1.0 + 3 * 1.5) / 6.0001).epsilon(1e-12));
  CHECK(mean(1) == Approx((3 * -2.0 + 3 * 0.5) / 6.0001).epsilon(1e-12));
  // Model-file keys: one prefix per statistics wrapper, in YAML order.
  TensorMap saved;
  save_model_statistics(vec.env(1), saved);
  CHECK(saved.count("wrappers/NormalizeObservation/mean") == 1);
  CHECK(saved.count("wrappers/NormalizeReward/var") == 1);
}

// The numpy script behind the numbers (SB3's formulas; n_envs = 1, gamma = 0.9):
//   rms = RMS((2,)); ret = RMS(()); returns = zeros(1)
//   obs = reset0; rms.update(obs); out = clip((obs - mean) / sqrt(var + 1e-8), -10, 10)
//   per step: new_obs = reset_k if done else obs; rms.update(new_obs); out = normalize(new_obs)
//             returns = returns * 0.9 + r; ret.update(returns); r' = clip(r / sqrt(ret.var + 1e-8))
//             returns[done] = 0
// with RMS.update = SB3 update_from_moments(np.mean, np.var, n), all float64, obs float32, and
// the rewards float64 (numpy >= 2 divides DummyVecEnv's float32 rewards by the float64 std in
// float64, NEP 50; numpy 1.x would round the quotient to float32).
