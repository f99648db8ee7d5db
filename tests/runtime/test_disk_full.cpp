// A full disk (issue 15, item 14): every write of config.yaml, the CSV files and eval --csv is
// checked, an error names the file and errno, write_text_atomic never leaves its target
// truncated nor its temporary behind, and a training run on a disk that fills up stops with
// exit 1, its last checkpoint intact.
//
// Three ways to make writes fail, from cheapest: /dev/full (every write: ENOSPC), a file-size
// limit (setrlimit RLIMIT_FSIZE: writes past it fail with EFBIG once SIGXFSZ is ignored; no
// privileges needed), and a real tmpfs of a few MB that fills up, mounted in a user and mount
// namespace of its own (`unshare -rm`, unprivileged where the kernel allows user namespaces, as
// Debian 12's does; skipped with a message where it is not available).
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/envs/classic/cartpole.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/experiment/env_factory.hpp"
#include "rlrun/runtime/experiment/experiment.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/run_directory.hpp"
#include "rlrun/runtime/run/eval_callback.hpp"
#include "rlrun/wrappers/monitor.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Files in `dir` whose name starts with '.' (write_text_atomic's temporaries).
// Temporary files left behind (hidden names); a run directory's own `.lock` does not count.
int hidden_files(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    n += name.rfind('.', 0) == 0 && name != ".lock";
  }
  return n;
}

// Limits the size of files this process writes while alive (SIGXFSZ ignored, so a write past
// the limit fails with EFBIG).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old_);
    old_handler_ = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = old_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_{};
  sighandler_t old_handler_ = SIG_DFL;
};

}  // namespace

TEST_CASE("CheckedFile: a failed write names the file and errno", "[disk]") {
  CheckedFile full("/dev/full", CheckedFile::Mode::kTruncate);
  full << "r,l,t\n";
  CHECK_THROWS_WITH(full.flush(),
                    Catch::Contains("cannot write /dev/full: No space left on device (ENOSPC)"));
  // A run directory's file must be regular (core/regular_file.hpp).
  CHECK_THROWS_WITH(CheckedFile::run_file("/dev/full", CheckedFile::Mode::kTruncate),
                    Catch::Contains("/dev/full is a character device, not a regular file"));
  CHECK_THROWS_WITH(CheckedFile("/nonexistent/dir/x.csv", CheckedFile::Mode::kAppend),
                    Catch::Contains("(ENOENT)"));
}

TEST_CASE("write_text_atomic: a failed write keeps the old file and leaves no temporary",
          "[disk]") {
  TempDir dir("write_atomic_full");
  const std::string path = dir / "config.yaml";
  write_text_atomic(path, "old: 1\n");
  CHECK(read_text(path) == "old: 1\n");
  {
    FileSizeLimit limit(4096);
    try {
      write_text_atomic(path, std::string(10000, 'x'));
      FAIL("a write past the file-size limit succeeded");
    } catch (const RuntimeFailure& e) {
      CHECK(contains(e.what(), "cannot write " + path));
      CHECK(contains(e.what(), "(EFBIG)"));
    }
  }
  CHECK(read_text(path) == "old: 1\n");
  CHECK(hidden_files(dir.str()) == 0);

  // The temporary is a fresh name: a symlink planted at the old fixed name is not followed.
  const std::string victim = dir / "victim.txt";
  std::ofstream(victim) << "keep\n";
  fs::create_symlink(victim, path + ".tmp");
  write_text_atomic(path, "new: 2\n");
  CHECK(read_text(path) == "new: 2\n");
  CHECK(read_text(victim) == "keep\n");
  // Mode of an ordinary new file, not mkstemp's 0600.
  CHECK((fs::status(path).permissions() & fs::perms::others_read) != fs::perms::none);

  // A FIFO (or a device) is not replaced by a regular file.
  const std::string fifo = dir / "fifo";
  REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(write_text_atomic(fifo, "x"), Catch::Contains("not a regular file"));
  CHECK(fs::is_fifo(fifo));
}

TEST_CASE("CsvSink and Monitor: a failed write stops with the file and errno", "[disk]") {
  TempDir dir("csv_full");
  const std::string progress = dir / "progress.csv";
  {
    CsvSink sink(progress);
    FileSizeLimit limit(2000);
    LogRow row{{"time/total_timesteps", 0.0}, {"rollout/ep_rew_mean", 21.5}};
    bool failed = false;
    for (int step = 0; step < 1000 && !failed; ++step) {
      row["time/total_timesteps"] = step;
      try {
        sink.write(row, step);
      } catch (const RuntimeFailure& e) {
        failed = true;
        CHECK(contains(e.what(), "cannot write " + progress + ": File too large (EFBIG)"));
      }
    }
    CHECK(failed);
  }
  CHECK(hidden_files(dir.str()) == 0);

  // Monitor: its header is flushed when it opens, each episode's row when the episode ends. Its
  // file is a run directory's, so /dev/full is refused (core/checked_file.hpp: run_file); the
  // file-size limit makes the writes fail.
  EnvPtr cartpole = std::make_unique<CartPole>(CartPole::Config{});
  CHECK_THROWS_WITH(Monitor(std::move(cartpole), "/dev/full", 0.0),
                    Catch::Contains("/dev/full is a character device, not a regular file"));
  const std::string monitor_path = dir / "0.monitor.csv";
  Monitor monitor(std::make_unique<CartPole>(CartPole::Config{}), monitor_path, 0.0);
  std::vector<float> obs(4);
  const float push = 1.0f;
  FileSizeLimit limit(fs::file_size(monitor_path) + 30);
  bool failed = false;
  for (int episode = 0; episode < 50 && !failed; ++episode) {
    monitor.reset(episode, obs);
    try {
      for (StepResult r; !r.terminated && !r.truncated;) r = monitor.step({&push, 1}, obs);
    } catch (const RuntimeFailure& e) {
      failed = true;
      CHECK(contains(e.what(), "cannot write " + monitor_path + ": File too large (EFBIG)"));
    }
  }
  CHECK(failed);
}

TEST_CASE("EvalCallback: a failed evaluations.csv row stops with the file and errno", "[disk]") {
  TempDir dir("eval_callback_full");
  Registry registry = make_builtin_registry();
  const Experiment experiment =
      load_experiment(std::string(RLRUN_SOURCE_DIR) + "/configs/cartpole_ppo.yaml",
                      {"eval.freq=64", "eval.n_episodes=1", "env.n_envs=1"}, registry);
  VecEnv env = make_vec_env(experiment.env, registry, 1, "");
  const AlgorithmSetup setup{env.observation_space(), env.action_space(), env.num_envs(), 1};
  std::unique_ptr<Algorithm> algorithm =
      registry.find_algorithm(experiment.algo.id)->make(experiment.algo.params, setup);
  const auto ignore = [](const std::string&) {};
  TrainingContext context{experiment.env,
                          experiment.run.seed,
                          registry,
                          dir.str(),
                          *algorithm,
                          env,
                          nullptr,
                          ignore,
                          ignore,
                          ignore,
                          false,
                          {},
                          {}};
  EvalCallback callback(context, experiment.eval);
  const std::string path = dir / "evaluations.csv";
  FileSizeLimit limit(fs::file_size(path) + 10);  // the header fits, a row does not
  try {
    callback.on_step(64);
    FAIL("an evaluation row past the file-size limit was written");
  } catch (const RuntimeFailure& e) {
    CHECK(contains(e.what(), "cannot write " + path + ": File too large (EFBIG)"));
  }
}

TEST_CASE("eval --csv on a full disk: exit 1 naming the file and ENOSPC", "[disk][cli]") {
  const auto r = run_rlrun("eval --env CartPole-v1 --policy random --episodes 2 --csv /dev/full");
  INFO(r.output);
  CHECK(r.exit_code == 1);
  CHECK(contains(r.output, "cannot write /dev/full: No space left on device (ENOSPC)"));
  CHECK(fs::is_character_file("/dev/full"));  // written to, never replaced
}

TEST_CASE("eval --csv / --trajectory that cannot be written fail before the first episode",
          "[disk][cli]") {
  // It used to fail only after all episodes, which a long evaluation wastes.
  for (const char* option : {"--csv", "--trajectory"}) {
    const auto r = run_rlrun(std::string("eval --env CartPole-v1 --policy random --episodes 3 ") +
                             option + " /proc/x/y.csv");
    INFO(r.output);
    CHECK(r.exit_code == 1);
    CHECK(contains(r.output, "cannot write /proc/x/y.csv: No such file or directory (ENOENT)"));
    CHECK_FALSE(contains(r.output, "mean_reward"));  // no episode ran
  }
  TempDir dir("eval_csv_check");
  const std::string existing = dir / "old.csv";
  std::ofstream(existing) << "kept\n";
  check_writable_file(existing);  // checked without truncating it
  CHECK(contains(read_text(existing), "kept"));
  check_writable_file(dir / "new/new.csv");  // its directory made, the file not left behind
  CHECK(fs::is_directory(dir / "new"));
  CHECK_FALSE(fs::exists(dir / "new/new.csv"));
}

TEST_CASE("train on a disk that fills up: exit 1, ENOSPC and the file named, checkpoint intact",
          "[disk][cli]") {
  TempDir dir("train_disk_full");
  const std::string mnt = dir / "mnt", out = dir / "out";
  fs::create_directories(mnt);
  fs::create_directories(out);
  const std::string run = mnt + "/runs/cartpole_ppo/seed1";
  // In a mount namespace of its own: a 4 MB tmpfs; train; once the first checkpoint exists,
  // keep a copy of it and fill the disk; then copy the run out (the tmpfs goes with the
  // namespace). A second run starts on the full disk: config.yaml cannot be written.
  // tmpfs takes space a page at a time, so appends go on until a CSV needs a new page: with
  // eval off and the next checkpoint 20000 steps away, progress.csv (a row per 256 steps) or a
  // monitor file (a row per episode) is the first write that fails.
  std::ofstream(dir / "run.sh")
      << "mount -t tmpfs -o size=4m tmpfs \"$1\" 2>\"$2/mount_error\" || exit 77\n"
         "cd \"$1\"\n"
         "\"$3\" train "
      << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml --set "
         "run.total_timesteps=100000000 --set checkpoint.freq=20000 --set eval.freq=0 "
         "--out \"$1/runs\" > \"$2/train.log\" 2>&1 &\n"
         "pid=$!\n"
         "run=\"$1/runs/cartpole_ppo/seed1\"\n"
         "while ! ls \"$run\"/checkpoints/*.zip >/dev/null 2>&1; do\n"
         "  kill -0 $pid 2>/dev/null || break; sleep 0.02\n"
         "done\n"
         "cp \"$run\"/checkpoints/*.zip \"$2/\"\n"
         "dd if=/dev/zero of=\"$1/fill\" bs=64k 2>/dev/null\n"
         "wait $pid; echo $? > \"$2/rc\"\n"
         "\"$3\" train "
      << RLRUN_SOURCE_DIR
      << "/configs/cartpole_ppo.yaml --out \"$1/full\" > "
         "\"$2/second.log\" 2>&1; echo $? > \"$2/second_rc\"\n"
         "rm -f \"$1/fill\"\n"
         "cp -a \"$1/runs\" \"$1/full\" \"$2/\"\n";
  const auto r = run_command("unshare -rm sh " + dir / "run.sh" + " '" + mnt + "' '" + out + "' '" +
                             RLRUN_BINARY + "'");
  if (r.exit_code == 77 || contains(r.output, "unshare:")) {
    WARN("skipped: cannot mount a small tmpfs in a user namespace here (" + r.output +
         read_text(out + "/mount_error") + ")");
    return;
  }
  const std::string log = read_text(out + "/train.log");
  INFO(r.output << log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
  REQUIRE(r.exit_code == 0);
  CHECK(read_text(out + "/rc") == "1\n");
  CHECK(contains(log, "No space left on device (ENOSPC)"));
  // A file of the run, named (whichever the run wrote first after the disk filled).
  CHECK((contains(log, "error: cannot write " + run + "/progress.csv: ") ||
         contains(log, "error: cannot write " + run + "/log.txt: ") ||
         contains(log, ".monitor.csv: No space left on device (ENOSPC)")));

  // The checkpoint written before the disk filled is still there, unchanged, and loads.
  std::vector<fs::path> saved;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().extension() == ".zip") saved.push_back(e.path());
  REQUIRE(saved.size() == 1);
  const std::string copied =
      out + "/runs/cartpole_ppo/seed1/checkpoints/" + saved[0].filename().string();
  REQUIRE(fs::exists(copied));
  CHECK(read_text(copied) == read_text(saved[0].string()));
  const auto eval = run_rlrun("eval --model " + copied + " --episodes 1");
  INFO(eval.output);
  CHECK(eval.exit_code == 0);
  CHECK(fs::file_size(out + "/runs/cartpole_ppo/seed1/config.yaml") > 100);
  CHECK(hidden_files(out + "/runs") == 0);

  // The run started on the full disk: exit 1 naming config.yaml; no empty config.yaml.
  const std::string second = read_text(out + "/second.log");
  INFO(second);
  CHECK(read_text(out + "/second_rc") == "1\n");
  CHECK(contains(second, "No space left on device (ENOSPC)"));
  CHECK(contains(second, "config.yaml"));
  const std::string config = out + "/full/cartpole_ppo/seed1/config.yaml";
  CHECK((!fs::exists(config) || fs::file_size(config) > 0));
  if (fs::exists(out + "/full")) CHECK(hidden_files(out + "/full") == 0);
}
