// The study journal against Optuna itself (Debian's python3-optuna 3.1, tests/tune/optuna_study.py):
// a study rlrun writes loads in Optuna with the same trials, one Optuna writes replays in rlrun
// to the same trials; and the file's rules — locking between processes, a stale lock, trial
// ownership, damaged files.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "rlrun/core/errors.hpp"
#include "rlrun/tune/journal_storage.hpp"
#include "runtime/cli_runner.hpp"
#include "test_paths.hpp"

using namespace rlrun;
using namespace rlrun::tune;
using rlrun::testing::read_text;
using rlrun::testing::run_command;
using rlrun::testing::TempDir;
using json = nlohmann::json;

namespace {

std::string optuna_script() {
  return std::string("/usr/bin/python3 ") + RLRUN_SOURCE_DIR + "/tests/tune/optuna_study.py";
}

json plain(double v) {
  if (std::isfinite(v)) return v;
  return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
}

// The study as optuna_study.py's `dump` prints it, from rlrun's replay.
json rlrun_dump(const JournalReplay& state, const std::string& name) {
  const int64_t id = *state.find_study(name);
  json trials = json::array();
  std::optional<std::pair<int, double>> best;
  const bool maximize = state.study(id).directions[0] == StudyDirection::kMaximize;
  for (const FrozenTrial& t : state.trials(id)) {
    json params = json::object(), distributions = json::object(), intermediate = json::object();
    for (const auto& [k, v] : t.params) {
      const json external = to_external(t.distributions.at(k), v);
      params[k] = external.is_number_float() ? plain(external.get<double>()) : external;
      distributions[k] = distribution_to_json(t.distributions.at(k));
    }
    for (const auto& [step, v] : t.intermediate_values)
      intermediate[std::to_string(step)] = plain(v);
    json values = nullptr;
    if (t.values) {
      values = json::array();
      for (double v : *t.values) values.push_back(plain(v));
    }
    trials.push_back({{"number", t.number},
                      {"state", state_name(t.state)},
                      {"params", params},
                      {"distributions", distributions},
                      {"intermediate_values", intermediate},
                      {"values", values},
                      {"user_attrs", t.user_attrs},
                      {"system_attrs", t.system_attrs},
                      {"has_start", !t.datetime_start.empty()},
                      {"has_complete", !t.datetime_complete.empty()}});
    if (t.state == TrialState::kComplete && t.value() &&
        (!best || (maximize ? *t.value() > best->second : *t.value() < best->second)))
      best = {t.number, *t.value()};
  }
  json out = {{"direction", maximize ? "MAXIMIZE" : "MINIMIZE"},
              {"user_attrs", state.study(id).user_attrs},
              {"trials", trials}};
  if (best) {
    out["best_number"] = best->first;
    out["best_value"] = best->second;
  }
  return out;
}

json optuna_dump(const std::string& journal, const std::string& name) {
  const auto r = run_command(optuna_script() + " dump " + journal + " " + name);
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  return json::parse(r.output);
}

// The distributions' JSON text is compared as JSON (key order is Python's business).
void normalise_distributions(json& dump) {
  for (auto& t : dump["trials"])
    for (auto& [k, v] : t["distributions"].items()) v = json::parse(v.get<std::string>());
}

}  // namespace

TEST_CASE("journal: a study rlrun writes loads in Optuna with identical trials", "[tune]") {
  TempDir dir("journal_write");
  const std::string path = dir.str() + "/study.journal";
  JournalStorage storage(path);
  const int64_t study = storage.create_or_load_study("demo", StudyDirection::kMaximize);
  storage.set_study_user_attr(study, "rlrun:space", "three parameters");
  const auto lr = make_float_distribution("lr", 1e-5, 1.0, true, std::nullopt);
  const auto clip = make_float_distribution("clip", 0.1, 0.4, false, 0.1);
  const auto layers = make_int_distribution("layers", 1, 9, false, 2);
  const auto act = make_categorical_distribution("act", {"tanh", nullptr, 1.5, true, 3});
  // 0: complete with reports and attributes.
  int64_t t0 = storage.create_running_trial(study);
  storage.set_trial_param(t0, "lr", 3.0e-4, lr);
  storage.set_trial_param(t0, "clip", 0.30000000000000004, clip);
  storage.set_trial_param(t0, "layers", 5, layers);
  storage.set_trial_param(t0, "act", 2, act);
  storage.report(t0, 1, 10.5);
  storage.report(t0, 2, 250.25);
  storage.set_trial_user_attr(t0, "gamma", 0.98);
  storage.set_trial_system_attr(t0, "rlrun:overrides", json::array({"algo.learning_rate=0.0003"}));
  storage.set_trial_state(t0, TrialState::kComplete, 480.5);
  // 1: pruned at its last report.
  int64_t t1 = storage.create_running_trial(study);
  storage.set_trial_param(t1, "lr", 0.5, lr);
  storage.set_trial_param(t1, "act", 1, act);
  storage.report(t1, 1, 9.0);
  storage.set_trial_state(t1, TrialState::kPruned, 9.0);
  // 2: failed; 3: enqueued; 4: running.
  int64_t t2 = storage.create_running_trial(study);
  storage.set_trial_system_attr(t2, "fail_reason", "training failed: NaN");
  storage.set_trial_state(t2, TrialState::kFail);
  storage.enqueue_trial(study, {{"lr", 0.001}, {"act", "tanh"}}, {{"rlrun:retry_of", 1}});
  storage.create_running_trial(study);

  json ours = rlrun_dump(storage.state(), "demo");
  json theirs = optuna_dump(path, "demo");
  normalise_distributions(ours);
  normalise_distributions(theirs);
  CHECK(theirs["trials"].size() == 5);
  CHECK(theirs["trials"][3]["state"] == "WAITING");
  CHECK(theirs["trials"][0]["params"]["act"] == 1.5);
  CHECK(theirs["best_number"] == 0);
  CHECK(theirs == ours);
}

TEST_CASE("journal: a study Optuna writes replays in rlrun to identical trials", "[tune]") {
  TempDir dir("journal_read");
  const std::string path = dir.str() + "/study.journal";
  const auto r = run_command(optuna_script() + " optimize " + path + " opt 12");
  INFO(r.output);
  REQUIRE(r.exit_code == 0);
  JournalStorage storage(path);
  json ours = rlrun_dump(storage.state(), "opt");
  json theirs = optuna_dump(path, "opt");
  normalise_distributions(ours);
  normalise_distributions(theirs);
  CHECK(theirs["trials"].size() == 12);
  CHECK(theirs["trials"][3]["state"] == "FAIL");
  CHECK(theirs == ours);
  // And rlrun continues it: a new trial takes number 12 and Optuna sees it.
  const int64_t study = storage.create_or_load_study("opt", StudyDirection::kMinimize);
  const int64_t t = storage.create_running_trial(study);
  storage.set_trial_param(t, "x", 1.0, make_float_distribution("x", -5, 5, false, std::nullopt));
  storage.set_trial_state(t, TrialState::kComplete, 0.5);
  CHECK(storage.state().trial(t).number == 12);
  CHECK(optuna_dump(path, "opt")["best_value"] == 0.5);
  // A direction that does not match is refused.
  CHECK_THROWS_AS(storage.create_or_load_study("opt", StudyDirection::kMaximize), RuntimeFailure);
}

TEST_CASE("journal: writers in several processes lose no line", "[tune]") {
  TempDir dir("journal_processes");
  const std::string path = dir.str() + "/study.journal";
  {
    JournalStorage storage(path);
    storage.create_or_load_study("race", StudyDirection::kMinimize);
  }
  constexpr int kWriters = 4, kTrials = 25;
  std::vector<pid_t> children;
  for (int w = 0; w < kWriters; ++w) {
    const pid_t pid = fork();
    if (pid == 0) {
      try {
        JournalStorage storage(path);
        const int64_t study = *storage.state().find_study("race");
        for (int i = 0; i < kTrials; ++i) {
          const int64_t t = storage.create_running_trial(study);
          storage.report(t, 1, w * 100 + i);
          storage.set_trial_state(t, TrialState::kComplete, w * 100 + i);
        }
      } catch (...) {
        _exit(1);
      }
      _exit(0);
    }
    children.push_back(pid);
  }
  for (pid_t pid : children) {
    int status = 0;
    waitpid(pid, &status, 0);
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 0);
  }
  JournalStorage storage(path);
  const auto trials = storage.state().trials(*storage.state().find_study("race"));
  REQUIRE(trials.size() == kWriters * kTrials);
  std::set<double> values;
  for (const auto& t : trials) {
    CHECK(t.state == TrialState::kComplete);
    values.insert(*t.value());
  }
  CHECK(values.size() == kWriters * kTrials);
  CHECK(optuna_dump(path, "race")["trials"].size() == kWriters * kTrials);
  CHECK_FALSE(std::filesystem::exists(path + ".lock"));
}

TEST_CASE("journal: workers started together on a fresh journal share one study", "[tune]") {
  // The array tasks of `rlrun tune --slurm` start at the same moment on a journal that does not
  // exist yet; each must find or create the one study, none be refused as a duplicate (CI saw
  // a worker fail so). The children wait on a pipe and are released together, many rounds.
  TempDir dir("journal_fresh_race");
  constexpr int kRounds = 20, kWorkers = 4;
  for (int round = 0; round < kRounds; ++round) {
    const std::string path = dir.str() + "/study" + std::to_string(round) + ".journal";
    int gate[2];
    REQUIRE(pipe(gate) == 0);
    std::vector<pid_t> children;
    for (int w = 0; w < kWorkers; ++w) {
      const pid_t pid = fork();
      if (pid == 0) {
        ::close(gate[1]);
        char byte;
        while (::read(gate[0], &byte, 1) < 0 && errno == EINTR) {
        }
        try {
          JournalStorage storage(path);
          storage.create_or_load_study("together", StudyDirection::kMaximize);
        } catch (...) {
          _exit(1);
        }
        _exit(0);
      }
      children.push_back(pid);
    }
    ::close(gate[0]);
    ::close(gate[1]);  // end of file on the pipe releases every child at once
    int failed = 0;
    for (pid_t pid : children) {
      int status = 0;
      waitpid(pid, &status, 0);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failed;
    }
    INFO("round " << round);
    CHECK(failed == 0);
    std::ifstream journal(path);
    int creates = 0;
    for (std::string line; std::getline(journal, line);)
      if (json::parse(line)["op_code"] == static_cast<int>(JournalOperation::kCreateStudy))
        ++creates;
    CHECK(creates == 1);
  }
}

TEST_CASE("journal: a waiting trial is owned by the first worker that claims it", "[tune]") {
  TempDir dir("journal_claim");
  const std::string path = dir.str() + "/study.journal";
  JournalStorage a(path), b(path);
  const int64_t study = a.create_or_load_study("claim", StudyDirection::kMinimize);
  const int64_t waiting = a.enqueue_trial(study, {{"x", 1.0}});
  b.sync();
  CHECK(b.claim_waiting_trial(waiting));
  CHECK_FALSE(a.claim_waiting_trial(waiting));
  CHECK(a.state().trial(waiting).state == TrialState::kRunning);
  // A finished trial cannot be changed by its own worker (Optuna's rule).
  b.set_trial_state(waiting, TrialState::kComplete, 1.0);
  CHECK_THROWS_AS(b.report(waiting, 3, 2.0), RuntimeFailure);
}

TEST_CASE("journal: a lock left by a killed process is broken after the grace period", "[tune]") {
  TempDir dir("journal_stale_lock");
  const std::string path = dir.str() + "/study.journal";
  JournalStorage storage(path);
  const std::string lock = path + ".lock";
  REQUIRE(symlink(path.c_str(), lock.c_str()) == 0);
  // The link's own time, 60 s in the past (older than kLockGracePeriod).
  struct timespec times[2];
  clock_gettime(CLOCK_REALTIME, &times[0]);
  times[0].tv_sec -= 60;
  times[1] = times[0];
  REQUIRE(utimensat(AT_FDCWD, lock.c_str(), times, AT_SYMLINK_NOFOLLOW) == 0);
  storage.create_or_load_study("after_kill", StudyDirection::kMinimize);
  CHECK(storage.state().find_study("after_kill"));
  CHECK_FALSE(std::filesystem::exists(lock));
}

TEST_CASE("journal: a damaged file is refused with its name, never a crash", "[tune]") {
  TempDir dir("journal_damaged");
  const std::string path = dir.str() + "/study.journal";
  const auto write = [&](const std::string& text) { std::ofstream(path, std::ios::trunc) << text; };
  const auto message = [&]() -> std::string {
    try {
      JournalStorage storage(path);
    } catch (const RuntimeFailure& e) {
      return e.what();
    }
    return "";
  };
  const std::string create =
      R"({"op_code": 0, "worker_id": "w", "study_name": "s", "directions": [1]})";
  write(create + "\n{not json\n" + create + "\n");
  CHECK_THAT(message(), Catch::Contains(path) && Catch::Contains("damaged"));
  write(create + "\n{\"op_code\": 4, \"worker_id\": \"w\", \"study_id\": 0, \"state\": 9}\n");
  CHECK_THAT(message(), Catch::Contains("trial state"));
  write(
      create +
      "\n{\"op_code\": 4, \"worker_id\": \"w\", \"study_id\": 0, \"distributions\": "
      "{\"x\": \"{\\\"name\\\": \\\"FloatDistribution\\\", \\\"attributes\\\": {\\\"low\\\": 1, "
      "\\\"high\\\": 0, \\\"log\\\": false, \\\"step\\\": null}}\"}, \"params\": {\"x\": 0.5}}\n");
  CHECK_THAT(message(), Catch::Contains("low must be <= high"));
  write(create + "\n{\"op_code\": 77, \"worker_id\": \"w\"}\n");
  CHECK_THAT(message(), Catch::Contains("op_code"));
  // A refused file leaves no descriptor open (open() returns the lowest free one), also when
  // the bad line is in the middle (fuzz/fuzz_journal.cpp found the reader leaking them).
  write(create + "\n{not json\n" + create + "\n");
  const int before = ::open("/dev/null", O_RDONLY);
  ::close(before);
  for (int i = 0; i < 50; ++i) CHECK_THAT(message(), Catch::Contains("damaged"));
  write(create + "\n[1, 2]\n");
  for (int i = 0; i < 50; ++i) CHECK_THAT(message(), Catch::Contains("JSON object"));
  const int after = ::open("/dev/null", O_RDONLY);
  ::close(after);
  CHECK(after == before);
  write(create + "\n" + std::string(kMaxJournalLineBytes + 10, ' '));
  CHECK_THAT(message(), Catch::Contains("longer than"));
  // A last line without its newline is an append in progress: not an error, not read yet.
  write(create + "\n{\"op_code\": 4, \"worker_id\": \"w\", \"stu");
  CHECK(message().empty());
  // Python's NaN and Infinity tokens are numbers (Optuna writes them for NaN reports).
  write(create +
        "\n{\"op_code\": 4, \"worker_id\": \"w\", \"study_id\": 0, \"datetime_start\": null}\n"
        "{\"op_code\": 7, \"worker_id\": \"w\", \"trial_id\": 0, \"step\": 1, "
        "\"intermediate_value\": NaN}\n"
        "{\"op_code\": 7, \"worker_id\": \"w\", \"trial_id\": 0, \"step\": 2, "
        "\"intermediate_value\": -Infinity}\n");
  JournalStorage storage(path);
  const FrozenTrial& t = storage.state().trial(0);
  CHECK(std::isnan(t.intermediate_values.at(1)));
  CHECK(t.intermediate_values.at(2) == -HUGE_VAL);
}

TEST_CASE("journal: a half-written last line is left by readers and repaired by the next append",
          "[tune]") {
  TempDir dir("journal_half_line");
  const std::string path = dir.str() + "/study.journal";
  const std::string create =
      R"({"op_code": 0, "worker_id": "w", "study_name": "s", "directions": [1]})";
  const auto text = [&] { return read_text(path); };
  // A fragment (a writer killed mid-append): readers leave it, the next append cuts it first.
  std::ofstream(path) << create << "\n{\"op_code\": 4, \"worker_id\": \"dead\", \"stu";
  {
    JournalStorage storage(path);
    CHECK(storage.state().study_names() == std::vector<std::string>{"s"});
    storage.create_or_load_study("t", StudyDirection::kMinimize);
  }
  CHECK(text().find("dead") == std::string::npos);
  JournalStorage again(path);
  CHECK(again.state().study_names() == std::vector<std::string>{"s", "t"});
  // A whole operation without its newline (as Optuna 3.1 would still read it) gets the newline.
  std::ofstream(path, std::ios::trunc) << create;
  {
    JournalStorage storage(path);
    CHECK(storage.state().study_names().empty());  // not read yet: it may be an append going on
    storage.create_or_load_study("t", StudyDirection::kMinimize);
    CHECK(storage.state().study_names() == std::vector<std::string>{"s", "t"});
  }
  CHECK(text().rfind(create + "\n", 0) == 0);
}

TEST_CASE("journal: nesting deeper than the bound, a link or a FIFO is refused",
          "[tune][security]") {
  TempDir dir("journal_refused");
  const std::string path = dir.str() + "/study.journal";
  const auto message = [&]() -> std::string {
    try {
      JournalStorage storage(path);
    } catch (const RuntimeFailure& e) {
      return e.what();
    }
    return "";
  };
  std::ofstream(path) << std::string(200000, '[') << std::string(200000, ']') << "\n";
  CHECK_THAT(message(), Catch::Contains(path + ":1: JSON nested deeper than 128 levels"));
  // 128 levels are fine (then refused as no operation, as any array).
  std::ofstream(path, std::ios::trunc) << std::string(128, '[') << std::string(128, ']') << "\n";
  CHECK_THAT(message(), Catch::Contains("an operation is a JSON object"));
  std::ofstream(path, std::ios::trunc) << "{\"a\": \"" << std::string(300, '[') << "\"}\n";
  CHECK_THAT(message(), Catch::Contains("op_code"));  // brackets in a string do not count

  std::filesystem::remove(path);
  std::ofstream(dir.str() + "/victim") << "";
  std::filesystem::create_symlink(dir.str() + "/victim", path);
  CHECK_THAT(message(), Catch::Contains(path + " is a symbolic link"));
  CHECK(read_text(dir.str() + "/victim").empty());
  std::filesystem::remove(path);
  REQUIRE(mkfifo(path.c_str(), 0600) == 0);
  CHECK_THAT(message(), Catch::Contains(path + " is a FIFO (named pipe), not a regular file"));
}
