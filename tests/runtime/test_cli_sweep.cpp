// rlrun sweep / sweep run / sweep slurm / report / plot and scripts/sweep.sh, through the real
// binary (issue 9). The Slurm cluster itself is scripts/tests/test_slurm.sh's (run by CI).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "rlrun/runtime/io/run_results.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// The 2 x 3 CartPole sweep of the issue, short runs with frequent checkpoints.
std::string write_sweep(const TempDir& dir, int timesteps) {
  const std::string path = dir / "sweep.yaml";
  std::ofstream(path)
      << "name: test_sweep\nbase: " << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml\nout_dir: " << dir / "out"
      << "\nseeds: [1, 2, 3]\ngrid:\n  algo.learning_rate: [lin_0.001, 3.0e-4]\n"
      << "set: {run.total_timesteps: " << timesteps
      << ", checkpoint: {freq: 4096, keep: 2}, run.console_interval: 1000}\n"
      << "slurm: {time: \"00:05:00\", cpus_per_task: 2, mem: 1G, extra: [\"--qos=short\"]}\n";
  return path;
}

std::vector<double> column(const std::string& csv_path, const std::string& name) {
  std::ifstream in(csv_path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  const size_t k = std::find(header.begin(), header.end(), name) - header.begin();
  std::vector<double> values;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (size_t i = 0; i <= k && std::getline(row, cell, ','); ++i) {
    }
    values.push_back(std::stod(cell));
  }
  return values;
}

}  // namespace

TEST_CASE("sweep: expansion, stable ids, errors at the sweep file's line", "[sweep]") {
  TempDir dir("sweep_expand");
  const std::string sweep = write_sweep(dir, 8192);
  const auto r = run_rlrun("sweep " + sweep);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string manifest = read_text(dir / "out/manifest.yaml");
  CHECK(manifest.find("id: learning_rate=lin_0.001/seed1") != std::string::npos);
  CHECK(manifest.find("id: learning_rate=3.0e-4/seed3") != std::string::npos);
  CHECK(std::count(manifest.begin(), manifest.end(), '\n') >= 6 + 8);
  const std::string config = read_text(dir / "out/configs/learning_rate=3.0e-4_seed2.yaml");
  CHECK(config.find("learning_rate: 0.0003") != std::string::npos);
  CHECK(config.find("seed: 2") != std::string::npos);
  CHECK(config.find("total_timesteps: 8192") != std::string::npos);
  CHECK(run_rlrun("sweep " + sweep).exit_code == 0);  // again: the same manifest
  CHECK(read_text(dir / "out/manifest.yaml") == manifest);

  std::ofstream(dir / "typo.yaml")
      << "base: " << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml\ngrid:\n  algo.lerning_rate: [1, 2]\n";
  const auto typo = run_rlrun("sweep " + dir / "typo.yaml");
  CHECK(typo.exit_code == 2);
  CHECK(typo.output.find("typo.yaml:3:3") != std::string::npos);
  CHECK(typo.output.find("did you mean 'learning_rate'") != std::string::npos);
  std::ofstream(dir / "key.yaml") << "base: x.yaml\nsedes: [1]\n";
  const auto key = run_rlrun("sweep " + dir / "key.yaml");
  CHECK(key.exit_code == 2);
  CHECK(key.output.find("did you mean 'seeds'") != std::string::npos);

  const auto slurm = run_rlrun("sweep slurm " + dir / "out/manifest.yaml");
  INFO(slurm.output);
  REQUIRE(slurm.exit_code == 0);
  const std::string script = read_text(dir / "out/sweep.sbatch");
  CHECK(script.find("#SBATCH --array=0-5") != std::string::npos);
  CHECK(script.find("#SBATCH --cpus-per-task=2") != std::string::npos);
  CHECK(script.find("#SBATCH --time=00:05:00") != std::string::npos);
  CHECK(script.find("#SBATCH --mem=1G") != std::string::npos);
  CHECK(script.find("#SBATCH --qos=short") != std::string::npos);
  CHECK(script.find("--threads 2 sweep run '" + dir / "out/manifest.yaml" +
                    "' --index \"$SLURM_ARRAY_TASK_ID\"") != std::string::npos);
}

// The bar: 2 configurations x 3 seeds with -j 2, interrupted, re-run: exactly 6
// finished runs, the interrupted ones resumed (their step counts continue), none trained twice.
TEST_CASE("sweep run -j 2: interrupted, re-run, 6 finished runs", "[sweep]") {
  TempDir dir("sweep_run");
  const std::string sweep = write_sweep(dir, 60000);
  REQUIRE(run_rlrun("sweep " + sweep).exit_code == 0);
  const std::string manifest = dir / "out/manifest.yaml";
  // Ctrl-C as soon as a run has written its first checkpoint (whatever the machine's speed).
  const auto first = run_command(std::string(RLRUN_BINARY) + " sweep run " + manifest + " -j 2 > " +
                                 dir / "first.txt" + " 2>&1 & pid=$!; for i in $(seq 600); do ls " +
                                 dir / "out/runs" +
                                 "/*/*/checkpoints/*.zip >/dev/null 2>&1 && break; sleep 0.05; "
                                 "done; kill -INT $pid; wait $pid; echo $?");
  const std::string first_out = read_text(dir / "first.txt");
  INFO(first_out);
  CHECK(first.output.find("130") != std::string::npos);
  const auto status = run_rlrun("sweep status " + manifest);
  INFO(status.output);
  int resumable = 0, finished_early = 0;
  for (size_t at = 0; (at = status.output.find("resumable", at)) != std::string::npos; ++at)
    ++resumable;
  for (size_t at = 0; (at = status.output.find(" finished ", at)) != std::string::npos; ++at)
    ++finished_early;
  CHECK(resumable >= 1);      // stopped mid-run with a checkpoint
  CHECK(finished_early < 6);  // the interruption came before the end

  // Each run's console output stays in the sweep's logs/, named by the first line.
  CHECK(first_out.find("console output of each in " + dir / "out/logs" + "/<run id>.txt") !=
        std::string::npos);

  const auto second = run_rlrun("sweep run " + manifest + " -j 2");
  INFO(second.output);
  CHECK(second.exit_code == 0);
  CHECK(second.output.find("6 of 6 runs finished") != std::string::npos);
  int resumed = 0;
  for (const char* label : {"learning_rate=lin_0.001", "learning_rate=3.0e-4"})
    for (int seed = 1; seed <= 3; ++seed) {
      const std::string run = dir / "out/runs" + "/" + label + "/seed" + std::to_string(seed);
      CHECK(fs::exists(run + "/finished"));
      CHECK_FALSE(fs::exists(run + "_2"));  // trained in its own directory, once
      const std::vector<double> steps = column(run + "/progress.csv", "time/total_timesteps");
      REQUIRE(!steps.empty());
      CHECK(steps.back() >= 60000);
      for (size_t i = 1; i < steps.size(); ++i) CHECK(steps[i] > steps[i - 1]);  // no restart
      const std::string log = read_text(run + "/log.txt");
      if (log.find("resuming") != std::string::npos) ++resumed;
      // Its console output, kept: each `sweep run` session appended under a header line.
      const std::string console =
          read_text(dir / "out/logs" + "/" + label + "/seed" + std::to_string(seed) + ".txt");
      CHECK(console.find("=== ") == 0);
      CHECK(console.find("sweep: run ") != std::string::npos);
      if (log.find("resuming") != std::string::npos)
        CHECK(console.find("resuming from ") != std::string::npos);
    }
  CHECK(resumed == resumable);
  // A third run trains nothing.
  const auto model_time =
      fs::last_write_time(dir / "out/runs/learning_rate=3.0e-4/seed3/model.zip");
  const auto third = run_rlrun("sweep run " + manifest + " -j 2");
  CHECK(third.output.find("6 finished before (skipped), 0 to resume, 0 to start") !=
        std::string::npos);
  CHECK(fs::last_write_time(dir / "out/runs/learning_rate=3.0e-4/seed3/model.zip") == model_time);
}

TEST_CASE(
    "sweep --out and --set: the sweep's out_dir and a value for every run, as train takes them",
    "[sweep]") {
  TempDir dir("sweep_options");
  const std::string sweep = write_sweep(dir, 8192);
  auto r = run_rlrun("sweep " + sweep + " --out " + dir / "elsewhere" +
                     " --set run.total_timesteps=2048 --set algo.n_epochs=4");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("sweep test_sweep: 6 runs -> " + dir / "elsewhere/manifest.yaml") !=
        std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out"));
  const std::string config = read_text(dir / "elsewhere/configs/learning_rate=3.0e-4_seed2.yaml");
  CHECK(config.find("total_timesteps: 2048") != std::string::npos);  // over the file's set:
  CHECK(config.find("n_epochs: 4") != std::string::npos);
  CHECK(config.find("learning_rate: 0.0003") != std::string::npos);  // the grid's own
  // A key the grid varies, a key the base lacks, options of other sweep commands: refused.
  r = run_rlrun("sweep " + sweep + " --set algo.learning_rate=0.1");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("the sweep varies algo.learning_rate") != std::string::npos);
  r = run_rlrun("sweep " + sweep + " --set algo.n_epoch=4");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("--set algo.n_epoch=4 does not fit") != std::string::npos);
  const std::string manifest = dir / "elsewhere/manifest.yaml";
  r = run_rlrun("sweep run " + manifest + " --out " + dir / "x");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("sweep run takes no --out") != std::string::npos);
  r = run_rlrun("sweep status " + manifest + " --set a=1");
  CHECK(r.exit_code == 2);
  r = run_rlrun("sweep status " + manifest + " stray");
  CHECK(r.exit_code == 2);
  CHECK(r.output.find("unexpected argument 'stray'") != std::string::npos);
  // `sweep slurm --set` passes the values on to each array task's `sweep run`.
  r = run_rlrun("sweep slurm " + manifest + " --set 'env.kwargs.sumo_binary=/opt/my sumo'");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(
      read_text(dir / "elsewhere/sweep.sbatch")
          .find(
              "--index \"$SLURM_ARRAY_TASK_ID\" '--set' 'env.kwargs.sumo_binary=/opt/my sumo'\n") !=
      std::string::npos);
}

// Issue 41: each run of a sweep has its own run.tb_log_name (<label>_seed<N>), so report and
// plot saw six configurations of one seed each. A configuration is the run's config without
// what differs per seed; the 2 x 3 sweep is 2 rows of 3 seeds and 2 lines with bands.
TEST_CASE("report and plot of a real 2 x 3 sweep: one row and one line per configuration",
          "[sweep][report][plot]") {
  TempDir dir("sweep_report");
  REQUIRE(run_rlrun("sweep " + write_sweep(dir, 512)).exit_code == 0);
  const auto trained = run_rlrun("sweep run " + dir / "out/manifest.yaml" + " -j 2");
  INFO(trained.output);
  REQUIRE(trained.exit_code == 0);
  const auto report = run_rlrun("report " + dir / "out/runs" + " --csv " + dir / "report.csv");
  INFO(report.output);
  REQUIRE(report.exit_code == 0);
  CHECK(report.output.find("| learning_rate=lin_0.001 | 3 (1 2 3) |") != std::string::npos);
  CHECK(report.output.find("| learning_rate=3.0e-4 | 3 (1 2 3) |") != std::string::npos);
  const std::string csv = read_text(dir / "report.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2);  // header, 2 configurations
  const auto plot = run_rlrun("plot " + dir / "out/runs" + " --output " + dir / "curves.svg");
  INFO(plot.output);
  REQUIRE(plot.exit_code == 0);
  CHECK(plot.output.find("plotted 2 configurations (6 runs)") != std::string::npos);
  // In the SVG, each configuration is a mean line (stroke width 2) over a band (opacity 0.2),
  // and its legend entry one of each again.
  const std::string svg = read_text(dir / "curves.svg");
  const auto count = [&svg](const std::string& what) {
    int n = 0;
    for (size_t at = 0; (at = svg.find(what, at)) != std::string::npos; ++at) ++n;
    return n;
  };
  CHECK(count("stroke-width:2;") == 2 * 2);
  CHECK(count("fill-opacity:0.2;") == 2 * 2);
}

TEST_CASE("sweep: the shipped example sweep expands into 6 runs", "[sweep]") {
  TempDir dir("sweep_example");
  std::ifstream in(std::string(RLRUN_SOURCE_DIR) + "/configs/sweeps/cartpole_ppo_lr.yaml");
  std::ofstream out(dir / "lr.yaml");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("base:", 0) == 0)
      line = "base: " + std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml";
    if (line.rfind("out_dir:", 0) == 0) line = "out_dir: " + dir / "out";
    out << line << "\n";
  }
  out.close();
  const auto r = run_rlrun("sweep " + dir / "lr.yaml");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("sweep cartpole_ppo_lr: 6 runs") != std::string::npos);
}

TEST_CASE("sweep run --index: a run another process holds is left to it", "[sweep]") {
  TempDir dir("sweep_lock");
  REQUIRE(run_rlrun("sweep " + write_sweep(dir, 4096)).exit_code == 0);
  const std::string manifest = dir / "out/manifest.yaml";
  fs::create_directories(dir / "out/locks");
  const auto r = run_command("flock -n " + dir / "out/locks/0.lock" + " -c '" + RLRUN_BINARY +
                             " sweep run " + manifest + " --index 0'");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(r.output.find("being trained by another process") != std::string::npos);
  CHECK_FALSE(fs::exists(dir / "out/runs/learning_rate=lin_0.001/seed1"));
  const auto own = run_rlrun("sweep run " + manifest + " --index 0");
  CHECK(own.exit_code == 0);
  CHECK(fs::exists(dir / "out/runs/learning_rate=lin_0.001/seed1/finished"));
  CHECK(run_rlrun("sweep run " + manifest + " --index 6").exit_code == 2);

  // The sweep file edited and expanded again: the finished run is not silently kept.
  REQUIRE(run_rlrun("sweep " + write_sweep(dir, 8192)).exit_code == 0);
  const auto changed = run_rlrun("sweep run " + manifest + " --index 0");
  CHECK(changed.exit_code == 2);
  CHECK(changed.output.find("was trained with other settings") != std::string::npos);
  CHECK(run_rlrun("sweep status " + manifest).output.find("(settings changed since it ran)") !=
        std::string::npos);
  // A run directory's config.yaml is untrusted text: damaged (a stray ']' that made yaml-cpp
  // loop forever) it is a mismatch, refused the same way, at once.
  std::ofstream(dir / "out/runs/learning_rate=lin_0.001/seed1/config.yaml") << "# x\n, 300]\n";
  const auto damaged = run_rlrun("sweep run " + manifest + " --index 0");
  CHECK(damaged.exit_code == 2);
  CHECK(damaged.output.find("was trained with other settings") != std::string::npos);
  fs::remove_all(dir / "out/runs/learning_rate=lin_0.001/seed1");
  CHECK(run_rlrun("sweep run " + manifest + " --index 0").exit_code == 0);
}

namespace {

// A hand-made run directory: config (name, seed), progress.csv, log.txt, and either an
// evaluations.csv or monitor files.
void make_run(const std::string& dir, const std::string& name, int seed, double lr,
              const std::vector<double>& eval_rewards, double success, double wall, int steps) {
  fs::create_directories(dir);
  std::ofstream(dir + "/config.yaml")
      << "run: {name: " << name << ", seed: " << seed
      << ", out_dir: somewhere}\nalgo: {id: PPO, learning_rate: " << lr << "}\n";
  std::ofstream progress(dir + "/progress.csv");
  progress << "rollout/ep_rew_mean,time/time_elapsed,time/total_timesteps\n";
  for (int i = 1; i <= 4; ++i)
    progress << (10.0 * i + seed) << ',' << i << ',' << steps * i / 4 << '\n';
  std::ofstream(dir + "/log.txt") << "trained " << steps << " steps in " << wall
                                  << " s (1 steps/s); model saved\n";
  if (!eval_rewards.empty()) {
    std::ofstream eval(dir + "/evaluations.csv");
    eval << "timesteps,mean_reward,std_reward,mean_ep_length,success_rate\n";
    for (size_t i = 0; i < eval_rewards.size(); ++i)
      eval << (i + 1) * 100 << ',' << eval_rewards[i] << ",0,10," << success << '\n';
  }
}

}  // namespace

TEST_CASE("report: statistics over seeds on hand-made run directories", "[report]") {
  TempDir dir("report");
  // Configuration A, 4 seeds; final evaluation returns 10, 20, 30, 100 (earlier rows differ).
  const double finals[] = {10, 20, 30, 100}, successes[] = {0.5, 1.0, 1.0, 0.5};
  for (int s = 0; s < 4; ++s)
    make_run(dir / "a/seed" + std::to_string(s + 1), "a", s + 1, 0.001, {-5, finals[s]},
             successes[s], 2.0 * (s + 1), 1000);
  // Configuration B, 1 seed, no evaluations: the last 100 of 150 monitor episodes, two files,
  // ordered by their end time t: returns 1..150 ending at t = episode -> mean(51..150) = 100.5.
  make_run(dir / "b/seed1", "b", 1, 0.01, {}, 0, 4.0, 2000);
  std::ofstream m0(dir / "b/seed1/0.monitor.csv"), m1(dir / "b/seed1/1.monitor.csv");
  m0 << "#{\"t_start\": 0}\nr,l,t\n";
  m1 << "#{\"t_start\": 0}\nr,l,t\n";
  for (int e = 1; e <= 150; ++e) (e % 2 ? m0 : m1) << e << ",10," << e << "\n";
  m0.close();
  m1.close();

  const auto r = run_rlrun("report " + dir.str() + " --csv " + dir / "report.csv" + " --markdown " +
                           dir / "report.md");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("| a | 4 (1 2 3 4) | 40.00 | 35.36 | 25.00 | 25.00 [") != std::string::npos);
  CHECK(r.output.find("| 0.750 | 1000 | 5.0 | 200 | eval |") != std::string::npos);
  CHECK(r.output.find("| b | 1 (1) | 100.50 | 0.00 | 100.50 | 100.50 [100.50, 100.50] | — | 2000 | "
                      "4.0 | 500 | monitor |") != std::string::npos);
  CHECK(read_text(dir / "report.md") == r.output);
  const std::string csv = read_text(dir / "report.csv");
  CHECK(csv.find("a,4,1 2 3 4,40.000000,35.355339,25.000000,25.000000,") != std::string::npos);

  // The statistics themselves: scipy.stats.trim_mean(x, 0.25) and the bootstrap interval.
  CHECK(interquartile_mean({1, 2, 3, 4, 5, 6, 7, 8}) == 4.5);           // cuts 2 each side
  CHECK(interquartile_mean({5, 1, 100, 2, 3, 4, -50}) == Approx(3.0));  // cuts 1 each side
  const SeedStatistics s = seed_statistics({10, 20, 30, 100});
  CHECK(s.iqm == 25.0);
  CHECK(s.iqm_low >= 10.0);
  CHECK(s.iqm_high <= 100.0);
  CHECK(s.iqm_low < s.iqm);
  CHECK(s.iqm_high > s.iqm);
  CHECK(seed_statistics({10, 20, 30, 100}).iqm_low == s.iqm_low);  // fixed bootstrap seed

  CHECK(run_rlrun("report " + dir / "nothing_here").exit_code == 2);
}

TEST_CASE("report: the run's true step count and training time, not progress.csv's last row",
          "[report]") {
  TempDir dir("report_steps");
  // DQN logs a progress.csv row every 4 episodes: a 5000-step run's last row may say 2880. The
  // `finished` marker has the count; log.txt has a session of 4000 steps and a resumed one.
  make_run(dir / "dqn/seed1", "dqn", 1, 0.001, {}, 0, 0, 2880);
  std::ofstream(dir / "dqn/seed1/finished") << "timesteps 5000\n";
  std::ofstream(dir / "dqn/seed1/log.txt")
      << "rlrun: training DQN on TrafficSignal-v0 for 5000 steps\n"
      << "trained 4000 steps in 10.00 s (400 steps/s); model saved to m\n"
      << "rlrun: resuming DQN on TrafficSignal-v0 from c (step 4000 of 5000)\n"
      << "trained 1000 steps (4000 -> 5000) in 2.50 s (400 steps/s); model saved to m\n";
  auto r = run_rlrun("report " + dir / "dqn");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  CHECK(r.output.find("| 5000 | 12.5 | 400 | none |") != std::string::npos);

  // A real DQN run: the count from `finished`, then (without it: interrupted, or training) from
  // model.zip's meta.json.
  const auto train = run_rlrun("train " + std::string(RLRUN_SOURCE_DIR) +
                               "/configs/cartpole_dqn.yaml --timesteps 1000 --out " + dir / "real");
  INFO(train.output);
  REQUIRE(train.exit_code == 0);
  const std::string run = dir / "real/cartpole_dqn/seed1";
  const std::string finished = read_text(run + "/finished");  // "timesteps N"
  REQUIRE(finished.rfind("timesteps ", 0) == 0);
  const int steps = std::stoi(finished.substr(10));
  REQUIRE(steps >= 1000);
  REQUIRE(column(run + "/progress.csv", "time/total_timesteps").back() < steps);
  const std::string cell = "| " + std::to_string(steps) + " | ";
  r = run_rlrun("report " + run);
  CHECK(r.output.find(cell) != std::string::npos);
  fs::remove(run + "/finished");
  r = run_rlrun("report " + run);
  INFO(r.output);
  CHECK(r.output.find(cell) != std::string::npos);
}

TEST_CASE("plot: PNG and SVG learning curves, a wrong metric is named", "[plot]") {
  TempDir dir("plot");
  for (int s = 1; s <= 3; ++s)
    make_run(dir / "a/seed" + std::to_string(s), "a", s, 0.001, {}, 0, 1, 1000);
  make_run(dir / "single/seed1", "single", 1, 0.1, {}, 0, 1, 800);
  const auto png = run_rlrun("plot " + dir.str() + " --output " + dir / "curves.png");
  INFO(png.output);
  REQUIRE(png.exit_code == 0);
  CHECK(png.output.find("plotted 2 configurations (4 runs)") != std::string::npos);
  const auto probe = run_command("ffprobe -v error -show_entries stream=width,height -of csv=p=0 " +
                                 dir / "curves.png");
  CHECK(probe.output.find(",560") != std::string::npos);
  const auto svg =
      run_rlrun("plot " + dir / "single" + " --output " + dir / "one.svg --title 'one run'");
  REQUIRE(svg.exit_code == 0);
  CHECK(read_text(dir / "one.svg").rfind("<?xml", 0) == 0);
  const auto wrong =
      run_rlrun("plot " + dir.str() + " --output " + dir / "x.png --metric rollout/ep_rew_meen");
  CHECK(wrong.exit_code == 2);
  CHECK(wrong.output.find("did you mean 'rollout/ep_rew_mean'") != std::string::npos);
  CHECK(run_rlrun("plot " + dir.str() + " --output " + dir / "x.jpg").exit_code == 2);

  // A run that has logged nothing yet: said so, not "has no such column; it has " + nothing.
  make_run(dir / "fresh/seed1", "fresh", 1, 0.3, {}, 0, 1, 100);
  std::ofstream(dir / "fresh/seed1/progress.csv", std::ios::trunc).close();
  const auto fresh = run_rlrun("plot " + dir / "fresh/seed1" + " --output " + dir / "f.png");
  CHECK(fresh.exit_code == 1);
  CHECK(fresh.output.find(dir / "fresh/seed1" + "/progress.csv has no rows yet") !=
        std::string::npos);
  const auto rest = run_rlrun("plot " + dir.str() + " --output " + dir / "rest.png");
  INFO(rest.output);
  CHECK(rest.exit_code == 0);
  CHECK(rest.output.find("note: left out " + dir / "fresh/seed1") != std::string::npos);
  CHECK(rest.output.find("plotted 2 configurations (4 runs)") != std::string::npos);
}

TEST_CASE("scripts/sweep.sh: seeds x learning rates in plain shell", "[sweep]") {
  TempDir dir("shell_sweep");
  const auto r = run_command(
      "cd " + std::string(RLRUN_SOURCE_DIR) + " && OUT=" + dir.str() + " RLRUN=" + RLRUN_BINARY +
      " TIMESTEPS=2048 SEEDS='1 2' RATES='1e-3 3e-4' JOBS=2 scripts/sweep.sh");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  for (const char* rate : {"1e-3", "3e-4"})
    for (int seed : {1, 2})
      CHECK(fs::exists(dir / ("cartpole_ppo_lr=" + std::string(rate) + "/seed" +
                              std::to_string(seed) + "/finished")));
  const auto report = run_rlrun("report " + dir.str());
  CHECK(report.output.find("| cartpole_ppo_lr=1e-3 | 2 (1 2) |") != std::string::npos);
}
