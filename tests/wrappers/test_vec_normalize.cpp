// env.normalize (wrappers/vec_normalize.hpp) against SB3's VecNormalize with several envs: the
// observation statistics take the whole batch, then every env is normalised with the same
// statistics. The expected values come from numpy running VecNormalize's formulas over the
// same raw transitions (tests/data/vec_normalize_reference.py, /usr/bin/python3).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "rlrun/algos/common/replay_buffer.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/env/vec_env.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/normalize_reward.hpp"
#include "rlrun/wrappers/vec_normalize.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"
#include "wrappers/scripted_env.hpp"

using namespace rlrun;
using rlrun::testing::ScriptedEnv;

namespace {

const std::string kSource = RLRUN_SOURCE_DIR;
constexpr int kCopies = 5;
constexpr int kDim = 3;

// Copy c: its own observations, rewards and episode length (2 + c), so the envs finish at
// different steps.
std::unique_ptr<ScriptedEnv> scripted(int c) {
  std::vector<std::vector<float>> resets, steps;
  std::vector<double> rewards;
  for (int k = 0; k < 3; ++k)
    resets.push_back({0.5f * static_cast<float>(c) - static_cast<float>(k),
                      1.25f * static_cast<float>(k), 3.0f - static_cast<float>(c)});
  for (int t = 0; t < 7; ++t) {
    steps.push_back({0.1f * static_cast<float>(t * (c + 1)),
                     static_cast<float>(c) - 0.7f * static_cast<float>(t),
                     static_cast<float>((t * 37 + c * 11) % 13) / 3.0f});
    rewards.push_back(static_cast<double>((t * 5 + c * 3) % 7) - 2.5);
  }
  return std::make_unique<ScriptedEnv>(resets, steps, rewards, 2 + c);
}

std::string floats(const Eigen::MatrixXf& m) {
  std::string s;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      s.append(s.empty() ? "" : " ").append(python_float_repr(static_cast<double>(m(i, j))));
  return s;
}

std::vector<double> parse(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

}  // namespace

TEST_CASE("env.normalize matches SB3 VecNormalize's batch update with several envs",
          "[wrappers][normalize][vec_normalize]") {
  NormalizeSetting setting;
  setting.enabled = true;
  const double gamma = 0.9;
  std::vector<EnvPtr> normalized_envs, raw_envs;
  for (int c = 0; c < kCopies; ++c) {
    normalized_envs.push_back(add_normalization(scripted(c), setting, gamma));
    raw_envs.push_back(scripted(c));
  }
  VecEnv vec(std::move(normalized_envs));
  share_model_statistics(vec);
  install_batch_normalization(vec, setting);
  VecEnv raw(std::move(raw_envs));

  std::ostringstream input;
  input << gamma << ' ' << kCopies << ' ' << kDim << '\n';
  std::vector<std::string> got;
  vec.reset();
  input << "reset " << floats(raw.reset()) << '\n';
  got.push_back(floats(vec.obs()));
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, kCopies);
  for (int t = 0; t < 12; ++t) {
    vec.step(actions);
    raw.step(actions);
    std::string rewards, dones, finals;
    Eigen::MatrixXf raw_final = raw.final_obs();
    Eigen::MatrixXf got_final(kDim, 0);
    for (int c = 0; c < kCopies; ++c) {
      rewards.append(c ? " " : "").append(python_float_repr(raw.rewards()(c)));
      dones.append(c ? " " : "").append(raw.done(c) ? "1" : "0");
      REQUIRE(vec.done(c) == raw.done(c));
      if (!raw.done(c)) raw_final.col(c).setZero();
      if (vec.done(c)) {
        got_final.conservativeResize(kDim, got_final.cols() + 1);
        got_final.col(got_final.cols() - 1) = vec.final_obs().col(c);
      }
    }
    input << "step " << floats(raw.obs()) << '|' << rewards << '|' << dones << '|'
          << floats(raw_final) << '\n';
    // SB3 get_original_obs / get_original_reward: what the envs gave, as a replay buffer keeps it.
    CHECK(vec.original_obs() == raw.obs());
    CHECK(vec.original_rewards() == raw.rewards());
    for (int c = 0; c < kCopies; ++c)
      if (raw.done(c)) CHECK(vec.original_final_obs().col(c) == raw.final_obs().col(c));
    std::string got_rewards;
    for (int c = 0; c < kCopies; ++c)
      got_rewards.append(c ? " " : "").append(python_float_repr(vec.rewards()(c)));
    got.push_back(floats(vec.obs()) + "|" + got_rewards + "|" + floats(got_final));
  }
  rlrun::testing::TempDir dir("vec_normalize");
  const std::string path = dir / "batches.txt";
  std::ofstream(path) << input.str();
  const auto r = rlrun::testing::run_command("/usr/bin/python3 " + kSource +
                                             "/tests/data/vec_normalize_reference.py " + path);
  REQUIRE(r.exit_code == 0);
  std::istringstream expected(r.output);
  std::string line;
  int k = 0;
  while (std::getline(expected, line)) {
    if (line.empty()) continue;
    REQUIRE(k < static_cast<int>(got.size()));
    INFO("batch " << k << " (0 = reset)");
    const std::string body = line.substr(line.find(' ') + 1);
    // Compared as numbers: the same values, printed by numpy and by rlrun.
    std::string want = body, have = got[static_cast<size_t>(k)];
    for (char& ch : want) ch = ch == '|' ? ' ' : ch;
    for (char& ch : have) ch = ch == '|' ? ' ' : ch;
    CHECK(parse(have) == parse(want));
    ++k;
  }
  CHECK(k == 13);
  // Every env finished at least once in 12 steps (lengths 2..6): terminal observations checked.
  CHECK(find_wrapper<NormalizeObservation>(vec.env(3))->statistics().count() ==
        Approx(13 * kCopies + 1e-4).epsilon(1e-12));
}

TEST_CASE("env.normalize with a replay buffer: originals stored, batches normalised when sampled",
          "[wrappers][normalize][vec_normalize][off_policy]") {
  // SB3 off_policy_algorithm._store_transition stores VecNormalize's original observations and
  // rewards; ReplayBuffer._normalize_obs / _normalize_reward normalise a batch with the
  // statistics of the time it is sampled.
  NormalizeSetting setting;
  setting.enabled = true;
  std::vector<EnvPtr> envs;
  for (int c = 0; c < kCopies; ++c) envs.push_back(add_normalization(scripted(c), setting, 0.99));
  VecEnv vec(std::move(envs));
  share_model_statistics(vec);
  install_batch_normalization(vec, setting);
  ReplayBuffer buffer(1000, kCopies, kDim, 1);
  Eigen::MatrixXf last_original = vec.reset();
  last_original = vec.original_obs();
  std::vector<Eigen::VectorXf> stored;  // every original observation given to the buffer
  std::vector<float> stored_rewards;
  const Eigen::MatrixXf actions = Eigen::MatrixXf::Zero(1, kCopies);
  for (int t = 0; t < 10; ++t) {
    for (int c = 0; c < kCopies; ++c) stored.push_back(last_original.col(c));
    vec.step(actions);
    buffer.add(last_original, actions, vec);
    for (int c = 0; c < kCopies; ++c)
      stored_rewards.push_back(static_cast<float>(vec.original_rewards()(c)));
    last_original = vec.original_obs();
  }
  Rng rng(5);
  ReplayBatch batch;
  buffer.sample(64, rng, batch);
  const VecStepHook& hook = *vec.step_hook();
  Eigen::MatrixXf normalized = batch.obs;
  Eigen::RowVectorXf scaled = batch.rewards;
  hook.normalize_obs(normalized);
  hook.normalize_rewards(scaled);
  const NormalizeObservation& stats = *find_wrapper<NormalizeObservation>(vec.env(0));
  for (int j = 0; j < 64; ++j) {
    // The batch holds stored originals ...
    bool found = false;
    for (const Eigen::VectorXf& o : stored) found = found || o == batch.obs.col(j);
    CHECK(found);
    CHECK(std::find(stored_rewards.begin(), stored_rewards.end(), batch.rewards(j)) !=
          stored_rewards.end());
    // ... and normalising it uses the current statistics.
    Eigen::VectorXf expected = batch.obs.col(j);
    stats.normalize(std::span<float>(expected.data(), static_cast<size_t>(kDim)));
    CHECK(normalized.col(j) == expected);
  }
  CHECK(scaled != batch.rewards);
}

TEST_CASE("env.normalize: an evaluation env is frozen and leaves rewards unscaled",
          "[wrappers][normalize][vec_normalize]") {
  NormalizeSetting setting;
  setting.enabled = true;
  EnvPtr trained = add_normalization(scripted(1), setting, 0.99);
  std::vector<float> obs(kDim);
  trained->reset(std::nullopt, obs);
  const std::vector<float> action{0.0f};
  for (int t = 0; t < 5; ++t) trained->step(action, obs);
  TensorMap saved;
  save_model_statistics(*trained, saved);

  EnvPtr eval = add_normalization(scripted(1), setting, 0.99);
  load_model_statistics(*eval, saved, /*training=*/false);
  auto* obs_norm = find_wrapper<NormalizeObservation>(*eval);
  const double count = obs_norm->statistics().count();
  eval->reset(std::nullopt, obs);
  auto reference_env = scripted(1);
  std::vector<float> raw(kDim);
  reference_env->reset(std::nullopt, raw);
  for (int t = 0; t < 4; ++t) {
    const StepResult r = eval->step(action, obs);
    const StepResult want = reference_env->step(action, raw);
    CHECK(r.reward == want.reward);  // rl-zoo's eval env: norm_reward=False
    std::vector<float> normalized = raw;
    obs_norm->normalize(normalized);
    CHECK(obs == normalized);
  }
  CHECK(obs_norm->statistics().count() == count);  // frozen
}

TEST_CASE("env.normalize: true, false or a map", "[wrappers][normalize][vec_normalize][config]") {
  auto read = [](const std::string& text) {
    NormalizeSetting s;
    decode(ConfigNode::load_string(text, "test"), s);
    return s;
  };
  CHECK_FALSE(read("false").enabled);
  const NormalizeSetting on = read("true");
  CHECK((on.enabled && on.norm_obs && on.norm_reward && on.clip_obs == 10.0 && !on.gamma));
  const NormalizeSetting map = read("{norm_reward: false, gamma: 0.98}");
  CHECK((map.enabled && map.norm_obs && !map.norm_reward && *map.gamma == 0.98));
  YAML::Emitter written;
  written << encode(map);
  CHECK(std::string(written.c_str()).find("norm_reward: false") != std::string::npos);
  CHECK(encode(read("false")).as<bool>() == false);
  CHECK_THROWS_WITH(read("{norm_rewards: true}"),
                    Catch::Contains("test:1:2") && Catch::Contains("did you mean 'norm_reward'"));
  CHECK_THROWS_WITH(read("[1]"), Catch::Contains("expected true, false or a map"));
}
