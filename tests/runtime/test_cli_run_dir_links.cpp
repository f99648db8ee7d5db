// Links and special files planted in run directories and studies (issue 41, item 4), through the
// real binary. A run directory or study may come from anyone (docs/security.md): rlrun opens
// every name in it without following links, only regular files, within bounds. Each case here
// once wrote or deleted outside the run (a log.txt, checkpoints/, TensorBoard event file or
// study.journal link) or hung (a FIFO) or grew without bound (a /dev/zero link); each must now
// be refused, naming the file, with nothing outside changed. Commands run under `timeout -s
// KILL` (a process blocked opening a FIFO ignores SIGTERM), so a hang fails the test (exit 124)
// instead of hanging the suite.
#include <sys/stat.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "runtime/cli_runner.hpp"
#include "runtime/peak_memory_bound.hpp"
#include "test_paths.hpp"

using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(RLRUN_SOURCE_DIR) + "/configs";

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// Every file below `dir` with its contents: what "nothing written or deleted there" compares.
std::map<std::string, std::string> snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[fs::relative(e.path(), dir).string()] = read_text(e.path());
  return files;
}

// rlrun under `timeout -s KILL 60`: a command that hangs is killed (exit code 124).
CommandResult run_bounded(const std::string& args) {
  return run_command_measured("timeout -s KILL 60 " + std::string(RLRUN_BINARY) + " " + args);
}

// A CartPole PPO run with checkpoints at steps 256 and 512 and a model.
std::string train_with_checkpoints(const TempDir& dir, const std::string& extra = "") {
  const auto r = run_rlrun("--threads 1 train " + kConfigs + "/cartpole_ppo.yaml --timesteps 512" +
                           " --set checkpoint.freq=256 --out " + dir / "runs" + " " + extra);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return dir / "runs/cartpole_ppo/seed1";
}

// Replaces `path` by a FIFO (nobody writes it: a reader that opens it blocks for ever).
void make_fifo(const std::string& path) {
  fs::remove(path);
  REQUIRE(mkfifo(path.c_str(), 0600) == 0);
}

void make_link(const std::string& target, const std::string& path) {
  fs::remove(path);
  fs::create_symlink(target, path);
}

// A study of one short trial on CartPole PPO, its journal in `out`.
std::string write_study(const TempDir& dir, const std::string& out) {
  const std::string path = dir / "study.yaml";
  write_file(path, "name: small\nbase: " + kConfigs + "/cartpole_ppo.yaml\nout_dir: " + out +
                       "\nn_trials: 1\nseeds_per_trial: 1\nn_timesteps: 256\nn_evaluations: 1\n"
                       "eval_episodes: 1\nsampler: {type: random, seed: 1}\npruner: {type: none}\n"
                       "space:\n  algo.n_epochs: {int: [1, 2]}\n");
  return path;
}

}  // namespace

TEST_CASE("run dir links: a log.txt link is refused on resume, its target untouched",
          "[cli][security]") {
  TempDir dir("links_log");
  const std::string run = train_with_checkpoints(dir);
  write_file(dir / "victim.txt", "precious\n");
  make_link(dir / "victim.txt", run + "/log.txt");
  const auto r = run_bounded("train --resume " + run + " --timesteps 768");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, run + "/log.txt is a symbolic link"));
  CHECK(read_text(dir / "victim.txt") == "precious\n");
}

TEST_CASE("run dir links: a checkpoints/ link is refused, nothing is written or deleted there",
          "[cli][security]") {
  TempDir dir("links_checkpoints");
  // keep=2: the resumed run's keep-N clean-up would delete the oldest step_*.zip it sees.
  const std::string run = train_with_checkpoints(dir, "--set checkpoint.keep=2");
  const std::string elsewhere = dir / "elsewhere";
  fs::rename(run + "/checkpoints", elsewhere);
  fs::copy_file(elsewhere + "/step_256.zip", elsewhere + "/step_1.zip");  // someone's file
  make_link(elsewhere, run + "/checkpoints");
  const auto before = snapshot(elsewhere);
  for (const std::string& from : {run, run + "/checkpoints/step_512.zip"}) {
    const auto r = run_bounded("train --resume " + from + " --timesteps 1024");
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, run + "/checkpoints is a symbolic link"));
    CHECK(snapshot(elsewhere) == before);
  }
}

TEST_CASE("run dir links: a TensorBoard event file link is not cut or appended to on resume",
          "[cli][security][tensorboard]") {
  TempDir dir("links_events");
  const std::string tb = dir / "tb";
  const std::string run = train_with_checkpoints(dir, "--tensorboard-log " + tb);
  std::string events;
  for (const auto& e : fs::directory_iterator(tb + "/cartpole_ppo_1")) events = e.path().string();
  REQUIRE(!events.empty());
  // The victim is longer than the length the checkpoint recorded: it would be cut back to it.
  const std::string victim = dir / "victim.bin";
  write_file(victim, read_text(events) + "the rest of someone's file");
  const std::string victim_text = read_text(victim);
  make_link(victim, events);
  const auto r = run_bounded("train --resume " + run + " --timesteps 768 --tensorboard-log " + tb);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, events + " is a symbolic link"));
  CHECK(read_text(victim) == victim_text);
}

TEST_CASE(
    "run dir links: FIFOs as log.txt and progress.csv are refused by report, plot and "
    "resume, not waited on",
    "[cli][security]") {
  TempDir dir("links_fifo");
  const std::string run = train_with_checkpoints(dir);
  for (const std::string file : {"log.txt", "progress.csv"}) {
    const std::string saved = read_text(run + "/" + file);
    make_fifo(run + "/" + file);
    for (const std::string& args : {"report " + run, "plot " + run + " -o " + dir / "curves.png",
                                    "train --resume " + run + " --timesteps 768"}) {
      const auto r = run_bounded(args);
      INFO(args << "\n" << r.output);
      CHECK(r.exit_code == 1);  // 124: it hung
      CHECK(contains(r.output, run + "/" + file + " is a FIFO (named pipe), not a regular file"));
    }
    fs::remove(run + "/" + file);
    write_file(run + "/" + file, saved);
  }
}

TEST_CASE("run dir links: a progress.csv link to /dev/zero is refused at once, in little memory",
          "[cli][security]") {
  TempDir dir("links_zero");
  const std::string run = train_with_checkpoints(dir);
  make_link("/dev/zero", run + "/progress.csv");
  for (const std::string& args : {"report " + run, "plot " + run + " -o " + dir / "c.png"}) {
    const auto r = run_bounded(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, run + "/progress.csv is a symbolic link"));
    CHECK(r.peak_rss_kb < peak_rss_bound_kb(200 * 1024));
  }
  // The same bytes in a regular file: read within the bound of runtime/io/run_file_bounds.hpp,
  // not to the end (a line of NULs longer than one row may be).
  fs::remove(run + "/progress.csv");
  write_file(run + "/progress.csv", std::string(3 << 20, '\0'));
  const auto r = run_bounded("report " + run);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, run + "/progress.csv:1: a line longer than 1 MiB"));
}

TEST_CASE("run dir links: a link to a run directory is not followed by report or resume",
          "[cli][security]") {
  TempDir dir("links_run_dir");
  const std::string run = train_with_checkpoints(dir);
  fs::create_directories(dir / "root");
  make_link(run, dir / "root/linked");
  auto r = run_bounded("report " + dir / "root/linked");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, dir / "root/linked is a symbolic link"));
  // Searching a directory: a link inside is not entered (the real run elsewhere is found).
  r = run_bounded("report " + dir / "root");
  CHECK(r.exit_code == 2);
  CHECK(contains(r.output, "holds no run directory"));
  r = run_bounded("train --resume " + dir / "root/linked --timesteps 768");
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, "is a symbolic link"));
}

TEST_CASE("study links: a study.journal link is refused by tune and tune report, a FIFO too",
          "[cli][security][tune]") {
  TempDir dir("links_study");
  const std::string out = dir / "out";
  const std::string study = write_study(dir, out);
  fs::create_directories(out);
  write_file(dir / "victim.journal", "");
  make_link(dir / "victim.journal", out + "/study.journal");
  for (const std::string& args : {"--threads 1 tune " + study, "tune report " + study,
                                  "tune report " + out + "/study.journal"}) {
    const auto r = run_bounded(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, out + "/study.journal is a symbolic link"));
    CHECK(read_text(dir / "victim.journal").empty());
  }
  make_fifo(out + "/study.journal");
  for (const std::string& args : {"--threads 1 tune " + study, "tune report " + study}) {
    const auto r = run_bounded(args);
    INFO(args << "\n" << r.output);
    CHECK(r.exit_code == 1);  // 124: it hung
    CHECK(contains(r.output, out + "/study.journal is a FIFO (named pipe), not a regular file"));
  }
  // trials/ inside the study: a link there is refused, not trained into.
  fs::remove(out + "/study.journal");
  fs::create_directories(dir / "elsewhere");
  make_link(dir / "elsewhere", out + "/trials");
  const auto r = run_bounded("--threads 1 tune " + study);
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, out + "/trials is a symbolic link"));
  CHECK(fs::is_empty(dir / "elsewhere"));
}

TEST_CASE(
    "run dir temporaries: a run killed before its first checkpoint leaves none behind "
    "once resumed",
    "[cli][security][resume]") {
  TempDir dir("links_stale_tmp");
  const std::string run = dir / "runs/cartpole_ppo/seed1";
  // Killed (SIGKILL) once training has logged, long before its first checkpoint.
  const auto killed = run_command(
      std::string(RLRUN_BINARY) + " --threads 1 train " + kConfigs + "/cartpole_ppo.yaml" +
      " --timesteps 100000000 --set checkpoint.freq=50000000 --out " + dir / "runs" +
      " > /dev/null 2>&1 & pid=$!; while ! grep -q 'time/total_timesteps' " + run +
      "/progress.csv 2>/dev/null && kill -0 $pid 2>/dev/null; do sleep 0.05; done; kill -9 $pid;" +
      " wait $pid; echo exit=$?");
  REQUIRE(contains(killed.output, "exit=137"));
  // What a kill in the middle of an atomic write leaves (core/temp_beside.hpp, libzip).
  write_file(run + "/.progress.csv.Ab12Cd.tmp", "half a file");
  fs::create_directories(run + "/checkpoints");
  write_file(run + "/checkpoints/step_50000000.zip.tmp.Xy34Zw", "half a zip");
  const auto r = run_bounded("train --resume " + run);
  INFO(r.output);
  CHECK(r.exit_code == 2);  // nothing to resume from, said so
  CHECK(contains(r.output, "it has no checkpoints/step_<N>.zip"));
  CHECK_FALSE(fs::exists(run + "/.progress.csv.Ab12Cd.tmp"));
  CHECK_FALSE(fs::exists(run + "/checkpoints/step_50000000.zip.tmp.Xy34Zw"));
  CHECK(fs::exists(run + "/progress.csv"));  // the run's own files stay
}
