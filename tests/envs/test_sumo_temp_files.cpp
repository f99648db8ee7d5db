// SUMO's temporary files (issue 15, item 9) on the real SUMO: its log and the tripinfo file the
// metrics come from live in private mkdtemp directories, so a symlink planted at the names
// rlrun once used (<tmp>/rlrun<pid>_<n>.log, .tripinfo.xml) is never followed, and nothing is
// left behind, also when SUMO fails at start-up (whose error still quotes SUMO's own lines).
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/envs/sumo/sumo_process.hpp"
#include "rlrun/envs/traffic/traffic_signal.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::testing;
namespace fs = std::filesystem;

namespace {

// Points TMPDIR at `path` while alive (std::filesystem::temp_directory_path reads it each time).
class ScopedTmpdir {
 public:
  explicit ScopedTmpdir(const std::string& path) {
    if (const char* old = std::getenv("TMPDIR")) old_ = old;
    setenv("TMPDIR", path.c_str(), 1);
  }
  ~ScopedTmpdir() {
    if (old_.empty())
      unsetenv("TMPDIR");
    else
      setenv("TMPDIR", old_.c_str(), 1);
  }

 private:
  std::string old_;
};

std::set<std::string> entries(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

bool process_exists(pid_t pid) { return pid > 0 && kill(pid, 0) == 0; }

bool contains_text(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("PrivateTempDir: mode 0700, O_EXCL files, removed with its contents", "[traffic]") {
  TempDir dir("private_temp_dir");
  ScopedTmpdir tmpdir(dir.str());
  std::string path;
  {
    PrivateTempDir temp("rlrun-test-");
    path = temp.path();
    CHECK(fs::path(path).parent_path() == fs::path(dir.str()));
    struct stat st {};
    REQUIRE(lstat(path.c_str(), &st) == 0);
    CHECK(S_ISDIR(st.st_mode));
    CHECK((st.st_mode & 0777) == 0700);
    const int fd = temp.create_file("a.log");
    CHECK(fd >= 0);
    close(fd);
    CHECK_THROWS_AS(temp.create_file("a.log"), RuntimeFailure);  // exists: O_EXCL
    fs::create_symlink(dir / "elsewhere", temp.file("b.log"));
    CHECK_THROWS_AS(temp.create_file("b.log"), RuntimeFailure);  // a link: not followed
    CHECK_FALSE(fs::exists(dir / "elsewhere"));
    CHECK_THROWS_AS(temp.file("../x"), std::invalid_argument);
  }
  CHECK_FALSE(fs::exists(path));
}

TEST_CASE("PrivateTempDir: removes this user's directories of ended processes, nothing else",
          "[traffic]") {
  TempDir dir("private_temp_stale");
  ScopedTmpdir tmpdir(dir.str());
  const pid_t dead = fork();  // a pid that has ended
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const std::string prefix = "rlrun-stale-test-";
  const std::string stale = dir / (prefix + std::to_string(dead) + "-Ab12Cd");
  const std::string alive = dir / (prefix + std::to_string(getppid()) + "-Ab12Cd");
  const std::string link = dir / (prefix + std::to_string(dead) + "-Zz99Zz");
  const std::string other = dir / ("rlrun-other-" + std::to_string(dead) + "-Ab12Cd");
  for (const std::string& d : {stale, alive, other}) {
    fs::create_directories(d);
    std::ofstream(d + "/x.log") << "x\n";
  }
  fs::create_directories(dir / "target");
  std::ofstream(dir / "target/keep.txt") << "keep\n";
  fs::create_symlink(dir / "target", link);
  {
    PrivateTempDir no_sweep(prefix);  // the default: leftovers stay (e.g. logs kept for the user)
    CHECK(fs::exists(stale));
  }
  PrivateTempDir temp(prefix, PrivateTempDir::RemoveStale::kYes);
  CHECK_FALSE(fs::exists(stale));
  CHECK(fs::exists(alive + "/x.log"));
  CHECK(fs::exists(other + "/x.log"));
  CHECK(fs::is_symlink(link));
  CHECK(read_text(dir / "target/keep.txt") == "keep\n");
  CHECK(
      fs::path(temp.path()).filename().string().rfind(prefix + std::to_string(getpid()) + "-", 0) ==
      0);
}

TEST_CASE("rlrun killed with SIGKILL: the next rlrun removes its SUMO directories",
          "[traffic][cli]") {
  TempDir dir("sumo_killed_leftovers");
  const std::string tmp = dir / "tmp";
  fs::create_directories(tmp);
  const std::string env = "TMPDIR='" + tmp + "' ";
  // Training on the traffic task, killed once its SUMO runs: no destructor removes its
  // directories (SUMO itself goes with it, PR_SET_PDEATHSIG).
  const auto killed = run_command(
      env + RLRUN_BINARY + " train " + RLRUN_SOURCE_DIR +
      "/configs/cartpole_ppo.yaml --set "
      "env.id=TrafficSignal-v0 --set 'algo.policy.net_arch=[8]' --set env.n_envs=1 --timesteps "
      "100000000 --out '" +
      dir / "runs" +
      "' > /dev/null 2>&1 & pid=$!; "
      "for i in $(seq 200); do ls '" +
      tmp +
      "' | grep -q rlrun-sumo- && break; sleep 0.05; done; "
      "sleep 0.5; kill -9 $pid; wait $pid; ls '" +
      tmp + "'");
  INFO(killed.output);
  CHECK(contains_text(killed.output, "rlrun-sumo-"));
  CHECK(contains_text(killed.output, "rlrun-traffic-"));  // the env's tripinfo directory
  // The next rlrun that starts SUMO sweeps them away, and leaves nothing of its own.
  const auto next = run_command(env + RLRUN_BINARY +
                                " check-env TrafficSignal-v0 --set num_seconds=60 --episodes 1");
  INFO(next.output);
  CHECK(next.exit_code == 0);
  CHECK(entries(tmp).empty());
}

TEST_CASE("SUMO's log and tripinfo: private directories, planted symlinks untouched, nothing left",
          "[traffic]") {
  TempDir dir("sumo_temp_files");
  const std::string tmp = dir / "tmp";
  fs::create_directories(tmp);
  const std::string target = dir / "precious.txt";
  std::ofstream(target) << "keep me\n";
  // The names rlrun used before: predictable from the pid and a counter.
  const std::string pid = std::to_string(getpid());
  for (int n = 0; n < 64; ++n) {
    fs::create_symlink(target, tmp + "/rlrun" + pid + "_" + std::to_string(n) + ".log");
    fs::create_symlink(target, tmp + "/rlrun" + pid + "_" + std::to_string(n) + ".tripinfo.xml");
  }
  const std::set<std::string> planted = entries(tmp);
  ScopedTmpdir tmpdir(tmp);
  pid_t sumo = -1;
  {
    TrafficSignal::Config config;
    config.num_seconds = 60;
    TrafficSignal env(config);
    std::vector<float> obs(10);
    for (int episode = 0; episode < 2; ++episode) {
      env.reset(episode + 1, obs);
      sumo = env.sumo_pid();
      // While SUMO runs: two new entries (the env's tripinfo directory, the process's log
      // directory), both directories only their owner may enter.
      std::vector<std::string> made;
      for (const std::string& name : entries(tmp))
        if (!planted.count(name)) made.push_back(name);
      CHECK(made.size() == 2);
      for (const std::string& name : made) {
        struct stat st {};
        REQUIRE(lstat((tmp + "/" + name).c_str(), &st) == 0);
        CHECK(S_ISDIR(st.st_mode));
        CHECK((st.st_mode & 0777) == 0700);
      }
      const float action = 0.0f;
      StepResult step;
      for (int i = 0; i < 100 && !step.terminated && !step.truncated; ++i)
        step = env.step({&action, 1}, obs);
      REQUIRE((step.terminated || step.truncated));
      // The episode's metrics came from the tripinfo file in the private directory.
      CHECK(env.info().get(env.info().find("throughput")) > 0);
    }
  }
  CHECK_FALSE(process_exists(sumo));
  CHECK(read_text(target) == "keep me\n");
  CHECK(entries(tmp) == planted);
}

TEST_CASE("SUMO failing at start-up: its own error quoted, no files left, no process",
          "[traffic]") {
  TempDir dir("sumo_startup_failure");
  const std::string tmp = dir / "tmp";
  fs::create_directories(tmp);
  const std::string config = dir / "broken.sumocfg";
  std::ofstream(config) << "<configuration><input><net-file value=\"missing.net.xml\"/></input>"
                           "</configuration>\n";
  ScopedTmpdir tmpdir(tmp);

  SumoLaunch launch;
  launch.config = config;
  try {
    SumoProcess process(launch);
    FAIL("SUMO started on a configuration without its network");
  } catch (const RuntimeFailure& e) {
    const std::string message = e.what();
    INFO(message);
    CHECK(message.find("SUMO exited before accepting the TraCI connection") != std::string::npos);
    CHECK(message.find("missing.net.xml") != std::string::npos);  // SUMO's own words
  }
  CHECK(entries(tmp).empty());

  // The same through the env: it reads the scenario's files before SUMO runs (TrafficSignal-v0
  // is TrafficNetwork-v0's single-intersection case), so the error names the missing network
  // at once, and nothing is left.
  {
    TrafficSignal::Config env_config;
    env_config.scenario.value = config;
    CHECK_THROWS_WITH(TrafficSignal(env_config), Catch::Contains("missing.net.xml"));
  }
  CHECK(entries(tmp).empty());

  // A sumo binary that is not there: nothing made either.
  launch.binary = dir / "no-such-sumo";
  CHECK_THROWS_AS(SumoProcess(launch), RuntimeFailure);
  CHECK(entries(tmp).empty());
}
