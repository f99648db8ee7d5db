// Study journals from anyone (issue 41, items 5 and 10), through the real binary: JSON nested
// 200 000 deep and over-long lines are refused with the file and line (they crashed `tune
// report` with a stack overflow), and a journal whose last line a killed writer left half
// written is read by `tune report` and continued by a `tune` worker alike (the worker used to
// append after the fragment and then refuse its own damaged line).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::string kCreate =
    R"({"op_code": 0, "worker_id": "w", "study_name": "s", "directions": [1]})"
    "\n";

CommandResult report(const std::string& journal) {
  return run_command_measured("timeout -s KILL 120 " + std::string(RLRUN_BINARY) + " tune report " +
                              journal);
}

}  // namespace

TEST_CASE("journal bounds: 200 000 nested brackets and an over-long line are refused, no crash",
          "[cli][tune][security]") {
  TempDir dir("journal_bounds");
  const std::string journal = dir / "study.journal";
  // Balanced: parsed whole, then walked (and destroyed) recursively: a SIGSEGV before the bound.
  std::ofstream(journal) << kCreate << R"({"op_code": 5, "a": )" << std::string(200000, '[')
                         << std::string(200000, ']') << "}\n";
  auto r = report(journal);
  INFO(r.output);
  CHECK(r.exit_code == 1);  // was a SIGSEGV
  CHECK(contains(r.output, journal + ":2: JSON nested deeper than 128 levels"));

  std::ofstream(journal, std::ios::trunc)
      << kCreate << "{\"x\": \"" << std::string(2 << 20, 'a') << "\"}\n";
  r = report(journal);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, journal + ":2: a line longer than 1048576 bytes"));
}

TEST_CASE("journal bounds: a half-written last line is read by tune report and continued by tune",
          "[cli][tune]") {
  TempDir dir("journal_half_line");
  const std::string study = dir / "study.yaml";
  std::ofstream(study)
      << "name: small\nbase: " << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml\nout_dir: " << dir / "out"
      << "\nn_trials: 1\nseeds_per_trial: 1\nn_timesteps: 256\nn_evaluations: 1\n"
         "eval_episodes: 1\nsampler: {type: random, seed: 1}\npruner: {type: none}\n"
         "space:\n  algo.n_epochs: {int: [1, 2]}\n";
  auto r = run_rlrun("--threads 1 tune " + study);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  const std::string journal = dir / "out/study.journal";
  const std::string whole = read_text(journal);
  // A writer killed in the middle of its append.
  std::ofstream(journal, std::ios::app) << R"({"op_code": 4, "worker_id": "dead", "stu)";
  r = report(study);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.output, "1 trial"));
  // The worker agrees: it cuts the fragment (under the lock) and runs its trial.
  r = run_rlrun("--threads 1 tune " + study + " --n-trials 2");
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.output, "trial 1 complete"));
  const std::string after = read_text(journal);
  CHECK(after.compare(0, whole.size(), whole) == 0);
  CHECK_FALSE(contains(after, "\"dead\""));
  r = report(study);
  INFO(r.output);
  CHECK(r.exit_code == 0);
  CHECK(contains(r.output, "2 trials"));
}
