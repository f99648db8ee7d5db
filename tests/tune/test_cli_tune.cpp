// `rlrun tune` end to end, as a user runs it: a study file, workers sharing the journal, Optuna
// reading the result, kill -9 and Ctrl-C in the middle of a trial and the study resumed, a study
// Optuna started and rlrun continued, failed trials, errors in the study file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
using json = nlohmann::json;

namespace {

std::string optuna_script() {
  return std::string("/usr/bin/python3 ") + RLRUN_SOURCE_DIR + "/tests/tune/optuna_study.py";
}

json optuna_dump(const std::string& journal, const std::string& name) {
  const auto r = run_command(optuna_script() + " dump '" + journal + "' " + name);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return json::parse(r.output);
}

// A small study on CartPole PPO: four parameters (one conditional), 4096 steps per seed.
std::string write_study(const TempDir& dir, const std::string& extra, int n_trials = 6,
                        int64_t n_timesteps = 4096, int seeds = 2, int evaluations = 4) {
  const std::string path = dir / "study.yaml";
  std::ofstream(path)
      << "name: small\n"
         "base: "
      << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml\n"
         "out_dir: "
      << dir.str()
      << "/out\n"
         "n_trials: "
      << n_trials
      << "\n"
         "seeds_per_trial: "
      << seeds
      << "\n"
         "n_timesteps: "
      << n_timesteps
      << "\n"
         "n_evaluations: "
      << evaluations
      << "\n"
         "eval_episodes: 2\n"
         "sampler: {type: tpe, seed: 3, n_startup_trials: 3}\n"
         "pruner: {type: median, n_startup_trials: 2}\n"
         "space:\n"
         "  algo.learning_rate: {float: [1.0e-4, 3.0e-3], log: true}\n"
         "  algo.n_epochs: {int: [1, 10]}\n"
         "  algo.policy.net_arch: {categorical: [[32], [64, 64]]}\n"
         "  algo.clip_range: {float: [0.1, 0.3], step: 0.1, if: {algo.n_epochs: [8, 9, 10]}}\n"
      << extra;
  return path;
}

int count_state(const json& dump, const std::string& state) {
  int n = 0;
  for (const auto& t : dump["trials"]) n += t["state"] == state;
  return n;
}

// Runs `rlrun tune` in the background, waits until the journal holds `reports` intermediate
// values, sends `signal`; returns the exit status line ("exit=137").
std::string tune_then_signal(const std::string& study, const std::string& journal, int reports,
                             const std::string& signal, const std::string& log) {
  const std::string cmd = std::string(RLRUN_BINARY) + " --threads 1 tune " + study + " > " + log +
                          " 2>&1 & pid=$!; while n=$(grep -c '\"op_code\": 7' " + journal +
                          " 2>/dev/null); [ \"${n:-0}\" -lt " + std::to_string(reports) +
                          " ] && kill -0 $pid 2>/dev/null; do sleep 0.01; done; kill -" + signal +
                          " $pid; wait $pid; echo exit=$?";
  return run_command(cmd).output;
}

}  // namespace

TEST_CASE("tune: two workers run a study Optuna reads, the report and the best config",
          "[cli][tune]") {
  TempDir dir("tune_small");
  const std::string study = write_study(dir, "");
  const auto r = run_rlrun("tune " + study + " -j 2");
  INFO(r.output << read_text(dir / "out/logs/worker_0.txt")
                << read_text(dir / "out/logs/worker_1.txt"));
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("6 of 6 trials counted"));
  const json dump = optuna_dump(dir / "out/study.journal", "small");
  REQUIRE(dump["trials"].size() == 6);
  CHECK(count_state(dump, "COMPLETE") + count_state(dump, "PRUNED") == 6);
  std::set<std::string> workers;
  for (const auto& t : dump["trials"]) {
    CHECK(t["params"].contains("algo.learning_rate"));
    CHECK(t["params"].contains("algo.policy.net_arch"));
    // The conditional parameter exists exactly when its condition held.
    CHECK(t["params"].contains("algo.clip_range") ==
          (t["params"]["algo.n_epochs"].get<int>() >= 8));
    CHECK_FALSE(t["intermediate_values"].empty());
    workers.insert(t["system_attrs"]["rlrun:worker"]["id"].get<std::string>());
    if (t["state"] == "COMPLETE") {
      // Two seeds, each 4 evaluations: steps 1-8; the value is the mean of the seeds' last ones.
      CHECK(t["intermediate_values"].size() == 8);
      const double mean = (t["intermediate_values"]["4"].get<double>() +
                           t["intermediate_values"]["8"].get<double>()) /
                          2;
      CHECK(t["values"][0].get<double>() == Approx(mean));
    }
  }
  CHECK(workers.size() == 2);  // both workers took trials
  // Optuna's own analysis works on the study: importances (fANOVA) and the history plot.
  const auto tools = run_command(optuna_script() + " tools '" + (dir / "out/study.journal") +
                                 "' small '" + (dir / "optuna_history.png") + "'");
  INFO(tools.output);
  REQUIRE(tools.exit_code == 0);
  const json analysis = json::parse(tools.output);
  CHECK(analysis["importances"].contains("algo.learning_rate"));
  CHECK(std::filesystem::file_size(dir / "optuna_history.png") > 1000);

  const auto report = run_rlrun("tune report " + study + " --plot " + (dir / "history.png") +
                                " --best-config " + (dir / "best.yaml"));
  INFO(report.output);
  REQUIRE(report.exit_code == 0);
  CHECK_THAT(report.output, Catch::Contains("best trial") || Catch::Contains("Best trial"));
  CHECK_THAT(report.output, Catch::Contains("algo.learning_rate"));
  CHECK(std::filesystem::file_size(dir / "history.png") > 1000);
  CHECK(std::filesystem::exists(dir / "best.yaml"));
  const std::string best = read_text(dir / "best.yaml");
  CHECK_THAT(best, Catch::Contains("of study small") && Catch::Contains("n_epochs"));
  // The best config is a ready experiment file.
  const auto train = run_rlrun("train " + (dir / "best.yaml") +
                               " --timesteps 512 --set run.out_dir=" + (dir / "best_runs"));
  INFO(train.output);
  CHECK(train.exit_code == 0);
  // Running the study again adds nothing: it has its 6 trials.
  const auto again = run_rlrun("tune " + study);
  CHECK(again.exit_code == 0);
  CHECK(optuna_dump(dir / "out/study.journal", "small")["trials"].size() == 6);
}

TEST_CASE("tune: kill -9 of a worker mid-trial, then the study resumes with every trial intact",
          "[cli][tune]") {
  TempDir dir("tune_kill");
  // Trials long enough to be killed in the middle: one seed of 200 000 steps, 40 evaluations.
  const std::string study = write_study(dir, "", 3, 200000, 1, 40);
  const std::string journal = dir / "out/study.journal";
  const std::string status = tune_then_signal(study, journal, 3, "KILL", dir / "kill.log");
  INFO(status << read_text(dir / "kill.log"));
  REQUIRE(status.find("exit=137") != std::string::npos);
  const json before = optuna_dump(journal, "small");
  REQUIRE(count_state(before, "RUNNING") == 1);
  const auto resumed = run_rlrun("tune " + study);
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  CHECK_THAT(resumed.output, Catch::Contains("worker is gone; re-queued"));
  const json after = optuna_dump(journal, "small");
  // The killed trial is FAIL (re-queued), its parameters ran again as a new trial; three trials
  // count, every trial finished before the kill is unchanged.
  int requeued = 0, retried = 0;
  for (const auto& t : after["trials"]) {
    requeued += t["system_attrs"].contains("rlrun:requeued");
    retried += t["system_attrs"].contains("rlrun:retry_of");
  }
  CHECK(requeued == 1);
  CHECK(retried == 1);
  CHECK(after["trials"].size() == 4);
  CHECK(count_state(after, "COMPLETE") + count_state(after, "PRUNED") == 3);
  for (size_t i = 0; i < before["trials"].size(); ++i)
    if (before["trials"][i]["state"] != "RUNNING") CHECK(after["trials"][i] == before["trials"][i]);
  for (const auto& t : after["trials"])
    if (t["system_attrs"].contains("rlrun:retry_of")) {
      const auto& killed = after["trials"][t["system_attrs"]["rlrun:retry_of"].get<int>()];
      CHECK(killed["state"] == "FAIL");
      CHECK(t["params"] == killed["params"]);  // the same configuration, run again
    }
}

TEST_CASE("tune: Ctrl-C re-queues the running trial, the same command goes on", "[cli][tune]") {
  TempDir dir("tune_int");
  const std::string study = write_study(dir, "", 2, 200000, 1, 40);
  const std::string journal = dir / "out/study.journal";
  const std::string status = tune_then_signal(study, journal, 2, "INT", dir / "int.log");
  INFO(status << read_text(dir / "int.log"));
  REQUIRE(status.find("exit=130") != std::string::npos);
  CHECK_THAT(read_text(dir / "int.log"), Catch::Contains("interrupted and re-queued"));
  const json before = optuna_dump(journal, "small");
  CHECK(count_state(before, "RUNNING") == 0);
  CHECK(count_state(before, "WAITING") == 1);
  const auto resumed = run_rlrun("tune " + study);
  INFO(resumed.output);
  REQUIRE(resumed.exit_code == 0);
  const json after = optuna_dump(journal, "small");
  CHECK(count_state(after, "COMPLETE") + count_state(after, "PRUNED") == 2);
  CHECK(count_state(after, "WAITING") == 0);
}

TEST_CASE("tune: a study Optuna started is continued by rlrun", "[cli][tune]") {
  TempDir dir("tune_from_optuna");
  const std::string study = write_study(dir, "", 5);
  const std::string journal = dir / "out/study.journal";
  std::filesystem::create_directories(dir / "out");
  // Optuna's own trials on the same parameters (its objective is a stand-in number).
  std::ofstream(dir / "start.py") << R"(import optuna, sys, warnings
warnings.filterwarnings("ignore")
s = optuna.create_study(study_name="small", direction="maximize",
    storage=optuna.storages.JournalStorage(optuna.storages.JournalFileStorage(sys.argv[1])))
def f(t):
    lr = t.suggest_float("algo.learning_rate", 1e-4, 3e-3, log=True)
    t.suggest_int("algo.n_epochs", 1, 7)
    t.suggest_categorical("algo.policy.net_arch", ["[32]", "[64, 64]"])
    t.report(100.0, 1)
    return 100.0 + lr
s.optimize(f, n_trials=2)
s.enqueue_trial({"algo.learning_rate": 0.001, "algo.n_epochs": 4, "algo.policy.net_arch": "[32]"})
)";
  const auto started = run_command("/usr/bin/python3 " + (dir / "start.py") + " " + journal);
  INFO(started.output);
  REQUIRE(started.exit_code == 0);
  const auto r = run_rlrun("tune " + study);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const json after = optuna_dump(journal, "small");
  REQUIRE(after["trials"].size() == 5);
  CHECK(after["trials"][0]["user_attrs"].empty());  // Optuna's trials as they were
  CHECK(after["trials"][0]["values"][0].get<double>() > 100.0);
  // The trial Optuna enqueued ran with its fixed parameters.
  CHECK(after["trials"][2]["params"]["algo.learning_rate"] == 0.001);
  CHECK(after["trials"][2]["params"]["algo.n_epochs"] == 4);
  CHECK(after["trials"][2]["system_attrs"].contains("rlrun:overrides"));
  for (size_t i = 2; i < 5; ++i) CHECK(after["trials"][i]["state"] != "WAITING");
}

TEST_CASE("tune: a trial whose configuration fails is recorded as failed and the study goes on",
          "[cli][tune]") {
  TempDir dir("tune_fail");
  // n_steps 1 with 8 envs and batch 256: PPO needs batch_size > 1 per minibatch of the rollout;
  // an activation rlrun does not know makes the configuration invalid.
  const std::string study = write_study(dir, "", 4);
  std::string text = read_text(study);
  text += "  algo.policy.activation_fn: {categorical: [tanh, no_such_activation]}\n";
  std::ofstream(study) << text;
  const auto r = run_rlrun("tune " + study);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const json dump = optuna_dump(dir / "out/study.journal", "small");
  REQUIRE(dump["trials"].size() == 4);
  int failed = 0;
  for (const auto& t : dump["trials"]) {
    const bool bad = t["params"]["algo.policy.activation_fn"] == "no_such_activation";
    CHECK((t["state"] == "FAIL") == bad);
    if (bad)
      CHECK_THAT(t["system_attrs"]["fail_reason"].get<std::string>(),
                 Catch::Contains("activation"));
    failed += bad;
  }
  CHECK(failed >= 1);
}

TEST_CASE("tune: errors in a study file name the line and suggest the key", "[cli][tune]") {
  TempDir dir("tune_errors");
  const std::string study = write_study(dir, "n_trails: 3\n");
  auto r = run_rlrun("tune " + study);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output,
             Catch::Contains("study.yaml:") && Catch::Contains("did you mean 'n_trials'"));
  std::ofstream(study) << "base: " << RLRUN_SOURCE_DIR << "/configs/cartpole_ppo.yaml\n"
                       << "space:\n  algo.learning_rate: {float: [1.0e-3, 1.0e-4], logg: true}\n";
  r = run_rlrun("tune " + study);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("did you mean 'log'"));
  std::ofstream(study) << "base: " << RLRUN_SOURCE_DIR << "/configs/cartpole_ppo.yaml\n"
                       << "space:\n  algo.learning_rate: {float: [1.0e-3, 1.0e-4]}\n";
  r = run_rlrun("tune " + study);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("study.yaml:3") && Catch::Contains("low must be <= high"));
  std::ofstream(study) << "base: " << RLRUN_SOURCE_DIR << "/configs/cartpole_ppo.yaml\nspace: zoo\n"
                       << "sampler: {type: cmaes}\n";
  r = run_rlrun("tune " + study);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("cmaes"));
  r = run_rlrun("tune reprot " + study);
  CHECK(r.exit_code == 2);
}

TEST_CASE("tune: a progress.csv objective minimised, successive halving, --trial re-trains",
          "[cli][tune]") {
  TempDir dir("tune_progress");
  std::string text = read_text(write_study(dir, "", 4, 4096, 1, 4));
  // The file's objective and pruner replaced (later keys would be duplicates).
  text.replace(text.find("pruner: {type: median, n_startup_trials: 2}"),
               std::string("pruner: {type: median, n_startup_trials: 2}").size(),
               "pruner: {type: successive_halving, min_resource: 1, reduction_factor: 2}\n"
               "objective: {metric: train/value_loss, direction: minimize, reduce: mean}");
  std::ofstream(dir / "study.yaml") << text;
  const auto r = run_rlrun("tune " + (dir / "study.yaml"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const json dump = optuna_dump(dir / "out/study.journal", "small");
  REQUIRE(dump["trials"].size() == 4);
  CHECK(dump["direction"] == "MINIMIZE");
  int pruned = 0;
  for (const auto& t : dump["trials"]) {
    pruned += t["state"] == "PRUNED";
    if (t["state"] != "COMPLETE") continue;
    // The value is the mean of the seed's progress.csv column train/value_loss.
    const std::string progress =
        read_text(dir / ("out/trials/trial_" + std::to_string(t["number"].get<int>()) +
                         "/seed1/progress.csv"));
    std::istringstream lines(progress);
    std::string header;
    std::getline(lines, header);
    int column = -1, i = 0;
    for (size_t start = 0, comma; start <= header.size(); start = comma + 1, ++i) {
      comma = header.find(',', start);
      if (comma == std::string::npos) comma = header.size();
      if (header.substr(start, comma - start) == "train/value_loss") column = i;
    }
    REQUIRE(column >= 0);
    double sum = 0;
    int n = 0;
    for (std::string line; std::getline(lines, line);) {
      std::istringstream cells(line);
      std::string cell;
      for (int k = 0; k <= column && std::getline(cells, cell, ','); ++k) {
      }
      if (!cell.empty()) {
        sum += std::stod(cell);
        ++n;
      }
    }
    REQUIRE(n > 0);
    CHECK(t["values"][0].get<double>() == Approx(sum / n).epsilon(1e-4));
    // Successive halving records the rungs a trial reached.
    CHECK(t["system_attrs"].contains("completed_rung_0"));
  }
  CHECK(pruned < 4);
  // --trial N re-trains trial 0 into <out_dir>/retrained/.
  const auto retrain = run_rlrun("tune report " + (dir / "study.yaml") + " --trial 0");
  INFO(retrain.output);
  CHECK(retrain.exit_code == 0);
  CHECK(std::filesystem::exists(dir / "out/retrained/trial_0/seed1/model.zip"));
}

// Issue 41: `--set run.total_timesteps=512` ran every trial for the study's n_timesteps,
// silently. The keys a study sets for every trial itself are refused as fixed overrides, naming
// the study's own option; --n-timesteps replaces n_timesteps (workers and report included).
TEST_CASE("tune: --set of a key the study sets per trial is refused, and --n-timesteps",
          "[cli][tune]") {
  TempDir dir("tune_steps");
  const std::string study = write_study(dir, "", 1, 4096, 1, 1);
  auto r = run_rlrun("tune " + study + " --set run.total_timesteps=512");
  INFO(r.output);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("--set run.total_timesteps=512") &&
                           Catch::Contains("n_timesteps") && Catch::Contains("--n-timesteps 512"));
  CHECK_FALSE(std::filesystem::exists(dir / "out/study.journal"));
  r = run_rlrun("tune " + study + " --set eval.n_episodes=3");
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("eval_episodes"));

  r = run_rlrun("tune " + study + " --n-timesteps 512");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.output, Catch::Contains("1 seed x 512 steps"));
  CHECK(read_text(dir / "out/trials/trial_0/seed1/finished") == "timesteps 512\n");
  r = run_rlrun("tune report " + study + " --n-timesteps 512 --best-config " + (dir / "best.yaml"));
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(read_text(dir / "best.yaml"), Catch::Contains("total_timesteps: 512"));

  // The study file's own `set:` is refused at its line.
  std::ofstream(study, std::ios::app) << "set: {run.total_timesteps: 512}\n";
  r = run_rlrun("tune " + study);
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.output, Catch::Contains("study.yaml:") && Catch::Contains("n_timesteps"));
}
