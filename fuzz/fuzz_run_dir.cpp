// Fuzz target: a run directory from arbitrary bytes, as `rlrun report`, `rlrun plot` and
// `rlrun train --resume` read one (issue 41, item 4; docs/security.md: run directories may come
// from anyone). The input describes the directory's entries:
//     @@ file progress.csv\n<contents up to the next "\n@@ ">
//     @@ dir checkpoints\n
//     @@ link log.txt\nvictim          (a symbolic link: victim, outside, fifo, zero, self, run)
//     @@ fifo progress.csv\n
// (an input without "@@ " is progress.csv beside a minimal config.yaml). Entry names are one to
// three components of [A-Za-z0-9._-]; links point to fixed targets: a file, a directory and a
// FIFO outside the run, /dev/zero, the run itself, the link itself. The directory is built in a
// private temporary directory, then read as those commands read it: the reports' run results
// (the run named, and found by searching its parent), the resume candidates and each one's
// header, progress.csv's header as a resumed CsvSink reads it, the stale-temporary clean-up,
// and a per-agent team's agents.json with its agents' run directories (eval/record --model RUN).
// Refusing is fine (RuntimeFailure, UsageError, ConfigError); a crash, a sanitizer report, a
// hang (a FIFO waited on), unbounded memory (/dev/zero read to its end), a descriptor left open,
// or any change outside the run directory (written, truncated, deleted) is a bug.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "private_file.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/agent_team_file.hpp"
#include "rlrun/runtime/io/log_sinks.hpp"
#include "rlrun/runtime/io/model_file.hpp"
#include "rlrun/runtime/io/run_lock.hpp"
#include "rlrun/runtime/io/run_results.hpp"
#include "rlrun/runtime/run/resume_point.hpp"

using namespace rlrun;
namespace fs = std::filesystem;

namespace {

constexpr const char* kMinimalConfig =
    "run: {name: fuzz, seed: 1}\nenv: {id: CartPole-v1}\nalgo: {id: PPO}\n";

struct Entry {
  std::string kind, path, contents;
};

// The entries an input describes (see the top of this file).
std::vector<Entry> parse_entries(const std::string& input) {
  if (input.rfind("@@ ", 0) != 0)
    return {{"file", "config.yaml", kMinimalConfig}, {"file", "progress.csv", input}};
  std::vector<Entry> entries;
  size_t at = 0;
  while (at < input.size()) {
    const size_t header_end = input.find('\n', at);
    const std::string header = input.substr(
        at + 3, header_end == std::string::npos ? std::string::npos : header_end - at - 3);
    const size_t body = header_end == std::string::npos ? input.size() : header_end + 1;
    size_t next = input.find("\n@@ ", body);
    Entry entry;
    entry.contents = input.substr(body, (next == std::string::npos ? input.size() : next) - body);
    const size_t space = header.find(' ');
    entry.kind = header.substr(0, space);
    entry.path = space == std::string::npos ? "" : header.substr(space + 1);
    entries.push_back(std::move(entry));
    at = next == std::string::npos ? input.size() : next + 1;
  }
  return entries;
}

// One to three components of [A-Za-z0-9._-] (not "." or ".."): inside the run, always.
bool plain_path(const std::string& path) {
  static const std::regex component("[A-Za-z0-9._-]{1,40}");
  if (path.empty() || path.size() > 128) return false;
  int depth = 0;
  for (const auto& part : fs::path(path)) {
    const std::string p = part.string();
    if (++depth > 3 || p == "." || p == ".." || !std::regex_match(p, component)) return false;
  }
  return path.front() != '/' && path.back() != '/';
}

// Where a link points, by the word its contents start with.
std::string link_target(const std::string& contents, const fs::path& base, const fs::path& link) {
  const std::string word = contents.substr(0, contents.find_first_of(" \n"));
  if (word == "victim") return (base / "outside/victim.txt").string();
  if (word == "outside") return (base / "outside").string();
  if (word == "fifo") return (base / "outside/fifo").string();
  if (word == "zero") return "/dev/zero";
  if (word == "self") return link.filename().string();
  if (word == "run") return (base / "root/run").string();
  return "missing";
}

// Makes the directories above `path` inside the run; false when one of them exists as
// something else (a file, a FIFO, a link: the harness must not write through it either).
bool make_parents(const fs::path& run, const fs::path& relative) {
  std::error_code ec;
  fs::path at = run;
  for (const auto& part : relative.parent_path()) {
    at /= part;
    const fs::file_status st = fs::symlink_status(at, ec);
    if (!fs::exists(st) && !fs::create_directory(at, ec)) return false;
    if (fs::exists(st) && !fs::is_directory(st)) return false;
  }
  return true;
}

void build(const std::vector<Entry>& entries, const fs::path& base, const fs::path& run) {
  std::error_code ec;
  for (const Entry& e : entries) {
    if (!plain_path(e.path) || !make_parents(run, e.path)) continue;
    const fs::path path = run / e.path;
    if (fs::exists(fs::symlink_status(path, ec))) continue;  // the first entry of a name wins
    if (e.kind == "file") {
      std::ofstream(path, std::ios::binary) << e.contents;
    } else if (e.kind == "dir") {
      fs::create_directory(path, ec);
    } else if (e.kind == "link") {
      fs::create_symlink(link_target(e.contents, base, path), path, ec);
    } else if (e.kind == "fifo") {
      ::mkfifo(path.c_str(), 0600);
    }
  }
}

// What lies outside the run: it must be exactly this after every input.
std::map<std::string, std::string> outside_state(const fs::path& outside) {
  std::map<std::string, std::string> state;
  for (const auto& e : fs::directory_iterator(outside)) {
    std::string& what = state[e.path().filename().string()];
    if (e.is_fifo()) {
      what = "fifo";
    } else {
      std::ifstream in(e.path(), std::ios::binary);
      what.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  return state;
}

const fs::path& base_dir() {
  static const fs::path base = [] {
    const fs::path dir = fs::path(fuzz::private_file("run_dir", "x")).parent_path();
    fs::create_directories(dir / "outside");
    std::ofstream(dir / "outside/victim.txt") << "precious\n";
    std::ofstream(dir / "outside/stale.tmp") << "not the run's\n";
    ::mkfifo((dir / "outside/fifo").c_str(), 0600);
    return dir;
  }();
  return base;
}

int lowest_free_descriptor() {
  const int fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  if (fd < 0) std::abort();
  ::close(fd);
  return fd;
}

// Runs `read`, accepting a refusal.
template <class F>
void refusable(F&& read) {
  try {
    read();
  } catch (const RuntimeFailure&) {
  } catch (const UsageError&) {
  } catch (const ConfigError&) {
  }
}

void read_like_the_commands(const fs::path& root, const fs::path& run) {
  refusable([&] { group_runs(read_runs({run.string()})); });   // report/plot RUN
  refusable([&] { group_runs(read_runs({root.string()})); });  // report/plot DIR
  refusable([&] { read_agent_team(run.string()); });           // eval --model TEAM_RUN
  refusable([&] {                                              // train --resume RUN
    for (const std::string& candidate : resume_candidates(run.string()))
      refusable([&] { read_model_header(candidate); });
  });
  refusable([&] {  // what a resume does before training: lock, clean up, read the header
    const DirHandle dir = DirHandle::open(run.string());
    const RunLock lock(dir);
    remove_stale_temporaries(dir);
    CsvSink resumed((run / "progress.csv").string(), /*append=*/true);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const fs::path& base = base_dir();
  const fs::path root = base / "root", run = root / "run";
  static const std::map<std::string, std::string> outside = outside_state(base / "outside");
  std::error_code ec;
  fs::remove_all(root, ec);
  fs::create_directories(run, ec);
  build(parse_entries(std::string(reinterpret_cast<const char*>(data), size)), base, run);
  const int free_before = lowest_free_descriptor();
  read_like_the_commands(root, run);
  if (lowest_free_descriptor() != free_before) std::abort();     // a descriptor leaked
  if (outside_state(base / "outside") != outside) std::abort();  // written outside the run
  return 0;
}
