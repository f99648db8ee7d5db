// End-to-end tests of the training callbacks (checkpoint, eval stop rules, obs_log) and of the
// normalisation statistics stored in model files, running the real binary.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rlrun/core/npy.hpp"
#include "rlrun/core/zip_archive.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/model_loader.hpp"
#include "rlrun/runtime/run/evaluator.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "runtime/cli_runner.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

int count_lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

std::vector<std::string> files_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

Tensor load_npy(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  return decode_npy(bytes, path);
}

// A small PPO CartPole experiment; `extra` adds sections or wrappers.
std::string cartpole(const TempDir& dir, const std::string& name, int64_t steps,
                     const std::string& env_extra, const std::string& extra) {
  const std::string path = dir / (name + ".yaml");
  write_text(path, "run: {name: " + name + ", seed: 2, total_timesteps: " + std::to_string(steps) +
                       ", out_dir: " + dir.str() +
                       "/runs}\n"
                       "env: {id: CartPole-v1, n_envs: 2" +
                       env_extra +
                       "}\n"
                       "algo: {id: PPO, n_steps: 50, batch_size: 50, n_epochs: 1}\n" +
                       extra);
  return path;
}

}  // namespace

TEST_CASE("cli: checkpoint writes checkpoints/step_N.zip and keeps the newest `keep`",
          "[cli][callbacks]") {
  TempDir dir("checkpoint");
  const auto r =
      run_rlrun("train " + cartpole(dir, "ckpt", 1000, "", "checkpoint: {freq: 200, keep: 2}\n"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/ckpt/seed2";
  // Saved at 200, 400, ..., 1000 total steps; the older three were removed; no temp files.
  CHECK(files_in(run + "/checkpoints") ==
        std::vector<std::string>{"step_1000.zip", "step_800.zip"});
  CHECK(r.output.find("checkpoint saved to " + run +
                      "/checkpoints/step_800.zip (removed step_400.zip)") != std::string::npos);
  // A checkpoint is a model file eval can use.
  const auto e = run_rlrun("eval --model " + run + "/checkpoints/step_800.zip --episodes 1");
  INFO(e.output);
  CHECK(e.exit_code == 0);
  CHECK(read_text(run + "/config.yaml").find("checkpoint:") != std::string::npos);

  // keep: 0 keeps all; freq counts TOTAL steps (n_envs = 2: 100 VecEnv steps per 200).
  REQUIRE(
      run_rlrun("train " + cartpole(dir, "all", 600, "", "checkpoint: {freq: 200}\n")).exit_code ==
      0);
  CHECK(files_in(dir / "runs/all/seed2/checkpoints") ==
        std::vector<std::string>{"step_200.zip", "step_400.zip", "step_600.zip"});
}

TEST_CASE("cli: eval.reward_threshold stops training after the evaluation that reaches it",
          "[cli][callbacks]") {
  TempDir dir("threshold");
  // Any CartPole policy lasts more than 5 steps: the first evaluation (at 200 steps) stops it.
  const auto r =
      run_rlrun("train " + cartpole(dir, "stop", 100000, "",
                                    "eval: {freq: 200, n_episodes: 2, reward_threshold: 5}\n"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/stop/seed2";
  CHECK(count_lines(read_text(run + "/evaluations.csv")) == 2);  // header + one evaluation
  CHECK(r.output.find("stopped early: best mean reward") != std::string::npos);
  CHECK(r.output.find("reached eval.reward_threshold 5") != std::string::npos);
  CHECK(read_model(run + "/model.zip").meta.num_timesteps == 200);
  CHECK(fs::exists(run + "/best_model.zip"));
}

TEST_CASE("cli: eval.max_no_improvement_evals stops as SB3's StopTrainingOnNoModelImprovement",
          "[cli][callbacks]") {
  TempDir dir("noimprove");
  // An untrained MountainCar policy never reaches the flag: every evaluation returns -200, so
  // only the first is an improvement. SB3 counting: stop when the count of evaluations in a
  // row without a new best exceeds 2, i.e. at the 4th evaluation (400 steps).
  const std::string path = dir / "mc.yaml";
  write_text(path,
             "run: {name: mc, seed: 1, total_timesteps: 100000, out_dir: " + dir.str() +
                 "/runs}\n"
                 "env: {id: MountainCar-v0}\n"
                 "algo: {id: PPO, n_steps: 100, batch_size: 50, n_epochs: 1, learning_rate: 0.0}\n"
                 "eval: {freq: 100, n_episodes: 1, max_no_improvement_evals: 2}\n");
  const auto r = run_rlrun("train " + path);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string evals = read_text(dir / "runs/mc/seed1/evaluations.csv");
  INFO(evals);
  CHECK(count_lines(evals) == 5);
  CHECK(evals.find("400,-200,0,200,\n") != std::string::npos);
  CHECK(r.output.find("stopped early: no new best model in the last 3 evaluations") !=
        std::string::npos);
  // With min_evals 2 the first two evaluations are not counted: stop at the 5th.
  const auto later = run_rlrun("train " + path + " --set eval.min_evals=2 --set run.name=mc2");
  REQUIRE(later.exit_code == 0);
  CHECK(count_lines(read_text(dir / "runs/mc2/seed1/evaluations.csv")) == 6);
  // The evaluation columns: mean length and an empty success rate (MountainCar has none).
  CHECK(evals.rfind("timesteps,mean_reward,std_reward,mean_ep_length,success_rate\n", 0) == 0);
}

namespace {

// The steps of the evaluation best_model.zip must hold: the first row of evaluations.csv with
// the best value of `column` (larger or smaller is better).
int64_t first_best_row(const std::string& evaluations_csv, const std::string& column,
                       bool minimize) {
  std::stringstream lines(read_text(evaluations_csv));
  std::string line;
  std::getline(lines, line);
  const std::vector<std::string> header = split_csv_line(line);
  const size_t k =
      static_cast<size_t>(std::find(header.begin(), header.end(), column) - header.begin());
  REQUIRE(k < header.size());
  int64_t best_steps = -1;
  double best = 0;
  while (std::getline(lines, line)) {
    const std::vector<std::string> cells = split_csv_line(line);
    const double v = std::stod(cells.at(k));
    if (best_steps < 0 || (minimize ? v < best : v > best))
      best = v, best_steps = std::stoll(cells[0]);
  }
  return best_steps;
}

}  // namespace

TEST_CASE(
    "cli: eval.best_metric chooses best_model.zip by a column, in best_direction, across a resume",
    "[cli][callbacks]") {
  TempDir dir("best_metric");
  // CartPole's episodes grow longer as PPO learns: the shortest evaluation is an early one and
  // the longest a late one, so the two directions pick different models.
  const std::string shortest = cartpole(
      dir, "short", 1200, "",
      "eval: {freq: 200, n_episodes: 2, best_metric: mean_ep_length, best_direction: minimize}\n"
      "checkpoint: {freq: 600}\n");
  const auto r = run_rlrun("--threads 1 train " + shortest);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/short/seed2";
  const int64_t best_short = first_best_row(run + "/evaluations.csv", "mean_ep_length", true);
  CHECK(read_model(run + "/best_model.zip").meta.num_timesteps == best_short);
  CHECK(r.output.find("(new best mean_ep_length ") != std::string::npos);

  // The default is SB3's: the largest mean reward.
  const auto longest = run_rlrun("--threads 1 train " + shortest +
                                 " --set run.name=long --set eval.best_metric=mean_reward"
                                 " --set eval.best_direction=maximize");
  REQUIRE(longest.exit_code == 0);
  const int64_t best_long =
      first_best_row(dir / "runs/long/seed2/evaluations.csv", "mean_reward", false);
  CHECK(read_model(dir / "runs/long/seed2/best_model.zip").meta.num_timesteps == best_long);
  CHECK(best_long != best_short);

  // Resumed, the run remembers its best: a longer later evaluation does not replace the model.
  const auto more =
      run_rlrun("--threads 1 train --resume " + run + " --set run.total_timesteps=2400");
  INFO(more.output);
  REQUIRE(more.exit_code == 0);
  CHECK(read_model(run + "/best_model.zip").meta.num_timesteps ==
        first_best_row(run + "/evaluations.csv", "mean_ep_length", true));

  // A column the env does not have is refused before training, naming the ones it has.
  const auto typo =
      run_rlrun("train " + shortest + " --set run.name=typo --set eval.best_metric=mean_ep_lenght");
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find("eval.best_metric: 'mean_ep_lenght' is not a column of evaluations.csv") !=
        std::string::npos);
  CHECK(typo.output.find("did you mean 'mean_ep_length'?") != std::string::npos);
  CHECK(typo.output.find("--set eval.best_metric=mean_ep_lenght: ") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "runs/typo/seed2"));
  // Misspelt in the file, the message points at it (line 4: run, env, algo, eval).
  const auto in_file =
      run_rlrun("train " + cartpole(dir, "typo_file", 1200, "",
                                    "eval: {freq: 200, best_metric: mean_rewrd}\n"));
  CHECK(in_file.exit_code == 2);
  CHECK(in_file.output.find(
            dir / "typo_file.yaml:4:32: eval.best_metric: 'mean_rewrd' is not a column") !=
        std::string::npos);
  CHECK(in_file.output.find("did you mean 'mean_reward'?") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "runs/typo_file/seed2"));
  const auto direction =
      run_rlrun("train " + shortest + " --set run.name=dir --set eval.best_direction=min");
  CHECK(direction.exit_code == 2);
  CHECK(direction.output.find("did you mean 'minimize'") != std::string::npos);
}

TEST_CASE("cli: obs_log saves the env's own observations of env 0 as float32 .npy chunks",
          "[cli][callbacks]") {
  TempDir dir("obslog");
  // The policy sees normalised, stacked observations; the log holds CartPole's raw 4 numbers.
  const auto r = run_rlrun(
      "train " + cartpole(dir, "obs", 400,
                          ", wrappers: [{id: NormalizeObservation}, {id: FrameStack, n_stack: 3}]",
                          "obs_log: {freq: 120}\n"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string log_dir = dir / "runs/obs/seed2/obs_log";
  // Chunks at 120, 240, 360 total steps (60 rows each: 2 envs) and the rest at the end.
  REQUIRE(files_in(log_dir) == std::vector<std::string>{"obs_0000000120.npy", "obs_0000000240.npy",
                                                        "obs_0000000360.npy",
                                                        "obs_0000000400.npy"});
  std::vector<float> rows;
  for (const auto& [file, n] :
       std::vector<std::pair<std::string, int64_t>>{{"obs_0000000120.npy", 60},
                                                    {"obs_0000000240.npy", 60},
                                                    {"obs_0000000360.npy", 60},
                                                    {"obs_0000000400.npy", 20}}) {
    const Tensor t = load_npy(log_dir + "/" + file);
    CHECK(t.dtype == DType::kFloat32);
    CHECK(t.shape == std::vector<int64_t>{n, 4});
    rows.insert(rows.end(), t.data<float>(), t.data<float>() + t.numel());
  }
  // Raw CartPole states: x(t+1) = x(t) + 0.02 * x_dot(t) (Gymnasium's Euler step) holds
  // between consecutive rows, except across an episode end.
  int consistent = 0, pairs = 0;
  for (size_t k = 0; k + 1 < rows.size() / 4; ++k, ++pairs) {
    const float x = rows[4 * k], x_dot = rows[4 * k + 1], x_next = rows[4 * (k + 1)];
    if (std::abs(x + 0.02f * x_dot - x_next) < 1e-5f) ++consistent;
  }
  CHECK(consistent >= pairs * 8 / 10);
}

TEST_CASE("cli: NormalizeObservation statistics are stored in model.zip and used frozen by eval",
          "[cli][callbacks][normalize]") {
  TempDir dir("normalize");
  const auto r = run_rlrun(
      "train " +
      cartpole(dir, "norm", 1000,
               ", wrappers: [{id: NormalizeObservation}, {id: NormalizeReward, gamma: 0.98}]",
               "eval: {freq: 500, n_episodes: 2}\n"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/norm/seed2";
  for (const std::string file : {"model.zip", "best_model.zip"}) {
    const ZipMembers members = read_zip(run + "/" + file);
    for (const char* name :
         {"wrappers/NormalizeObservation/mean.npy", "wrappers/NormalizeObservation/var.npy",
          "wrappers/NormalizeObservation/count.npy", "wrappers/NormalizeReward/var.npy"})
      CHECK(members.count(name) == 1);
  }
  // The model's env gets exactly the stored statistics, frozen: evaluating leaves them alone.
  const Registry& registry = builtin_registry();
  const ModelFile model = read_model(run + "/model.zip");
  const Tensor& count = model.wrapper_statistics.at("wrappers/NormalizeObservation/count");
  // 2 envs: 2 reset observations + 1000 step observations, minus the final ones, plus 1e-4.
  const double stored_count = *count.data<double>();
  CHECK(stored_count > 900);
  CHECK(stored_count < 1003);
  const Experiment experiment = experiment_from_model(model, registry);
  EnvPtr env = make_model_env(model, experiment, registry);
  auto* normalize = find_wrapper<NormalizeObservation>(*env);
  REQUIRE(normalize);
  CHECK_FALSE(normalize->training());
  CHECK(normalize->statistics().count() == stored_count);
  const Tensor& mean = model.wrapper_statistics.at("wrappers/NormalizeObservation/mean");
  for (int i = 0; i < 4; ++i) CHECK(normalize->statistics().mean()(i) == mean.data<double>()[i]);
  auto algorithm = algorithm_from_model(model, experiment, registry, env->observation_space(),
                                        env->action_space());
  evaluate_policy(*algorithm, *env, 2, true, 7);
  CHECK(normalize->statistics().count() == stored_count);

  const auto e = run_rlrun("eval --model " + run + "/model.zip --episodes 2");
  INFO(e.output);
  CHECK(e.exit_code == 0);
  // A model file whose statistics were removed is refused, naming what is missing.
  ZipMembers members = read_zip(run + "/model.zip");
  members.erase("wrappers/NormalizeObservation/mean.npy");
  write_zip_atomic(dir / "broken.zip", members);
  const auto broken = run_rlrun("eval --model " + dir / "broken.zip");
  CHECK(broken.exit_code == 1);
  CHECK(broken.output.find("wrappers/NormalizeObservation/mean") != std::string::npos);
}

TEST_CASE("cli: callback sections are parsed strictly", "[cli][callbacks]") {
  TempDir dir("callback_config");
  const auto typo =
      run_rlrun("train " + cartpole(dir, "a", 100, "", "checkpoint: {freq: 100, kep: 2}\n"));
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find("did you mean 'keep'") != std::string::npos);
  const auto section =
      run_rlrun("train " + cartpole(dir, "b", 100, "", "checkpoints: {freq: 100}\n"));
  CHECK(section.exit_code == 2);
  CHECK(section.output.find("did you mean 'checkpoint'") != std::string::npos);
  const auto no_eval =
      run_rlrun("train " + cartpole(dir, "c", 100, "", "eval: {reward_threshold: 100}\n"));
  CHECK(no_eval.exit_code == 2);
  CHECK(no_eval.output.find("set eval.freq > 0") != std::string::npos);
  const auto env =
      run_rlrun("train " + cartpole(dir, "d", 100, "", "obs_log: {freq: 10, env: 2}\n"));
  CHECK(env.exit_code == 2);
  CHECK(env.output.find("must be a training env index, 0..1") != std::string::npos);
  const auto wrapper =
      run_rlrun("train " + cartpole(dir, "e", 100, ", wrappers: [{id: NormalizeObservaton}]", ""));
  CHECK(wrapper.exit_code == 2);
  CHECK(wrapper.output.find("did you mean 'NormalizeObservation'") != std::string::npos);
}

TEST_CASE("cli: evaluations.csv has a success rate where the env reports is_success",
          "[cli][callbacks]") {
  TempDir dir("success");
  const std::string path = dir / "grasp.yaml";
  write_text(path, "run: {name: grasp, seed: 1, total_timesteps: 400, out_dir: " + dir.str() +
                       "/runs}\n"
                       "env: {id: Grasp2D-v0, n_envs: 2}\n"
                       "algo: {id: PPO, n_steps: 100, batch_size: 50, n_epochs: 1}\n"
                       "eval: {freq: 200, n_episodes: 2}\n");
  const auto r = run_rlrun("train " + path);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string run = dir / "runs/grasp/seed1";
  std::ifstream evals(run + "/evaluations.csv");
  std::string line;
  std::getline(evals, line);
  int rows = 0;
  while (std::getline(evals, line)) {
    ++rows;
    // timesteps,mean,std,mean_length,success_rate: the last cell is a fraction of 2 episodes.
    const std::string success = line.substr(line.rfind(',') + 1);
    INFO(line);
    REQUIRE_FALSE(success.empty());
    CHECK((success == "0" || success == "0.5" || success == "1"));
  }
  CHECK(rows == 2);
  CHECK(read_text(run + "/progress.csv").find("eval/success_rate") != std::string::npos);
  CHECK(r.output.find("success rate") != std::string::npos);
}
