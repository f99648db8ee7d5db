#include "rlrun/runtime/io/tensorboard/tensorboard_log.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <filesystem>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/tensorboard/png_size.hpp"
#include "rlrun/runtime/io/tensorboard/summaries.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

double wall_time_now() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// N when `entry` is "<stem>_<N>" (N a positive decimal number), else 0.
int64_t run_number(const std::string& entry, const std::string& stem) {
  if (entry.size() <= stem.size() + 1 || entry.compare(0, stem.size(), stem) != 0 ||
      entry[stem.size()] != '_')
    return 0;
  const std::string digits = entry.substr(stem.size() + 1);
  if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stoll(digits);
}

// Creates DIR/<name>_<N> with N above every existing one (mkdir is atomic: two runs starting
// at once in one log directory, as a sweep's do, get different numbers).
std::string create_tensorboard_run_directory(const std::string& dir, const std::string& name,
                                             std::string& run_name) {
  const fs::path full = fs::path(dir) / name;
  const fs::path parent = full.parent_path();
  const std::string stem = full.filename().string();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec)
    throw RuntimeFailure("cannot create the TensorBoard log directory " + parent.string() + ": " +
                         ec.message());
  int64_t latest = 0;
  for (const auto& entry : fs::directory_iterator(parent, ec))
    latest = std::max(latest, run_number(entry.path().filename().string(), stem));
  for (int64_t n = latest + 1;; ++n) {
    const fs::path candidate = parent / (stem + "_" + std::to_string(n));
    if (mkdir(candidate.c_str(), 0777) == 0) {
      run_name = (fs::path(name).parent_path() / candidate.filename()).string();
      return candidate.string();
    }
    if (errno != EEXIST)
      throw RuntimeFailure("cannot create " + candidate.string() + ": " + describe_errno(errno));
  }
}

}  // namespace

bool excluded_from_tensorboard(const std::string& key) {
  return key == "time/iterations" || key == "time/time_elapsed" || key == "time/total_timesteps" ||
         key == "time/episodes" || key == "train/n_updates";
}

TensorBoardLog TensorBoardLog::start(const std::string& dir, const std::string& name,
                                     const YAML::Node& config) {
  std::string run_name;
  const std::string run_dir = create_tensorboard_run_directory(dir, name, run_name);
  const double now = wall_time_now();
  TensorBoardLog log(run_dir, run_name, EventFile::create(DirHandle::open(run_dir), now));
  log.file_.write(session_start_event(now, hparams_of_config(config)));
  return log;
}

namespace {

// DIR/<run_name> for a resumed run: DIR is the user's (--tensorboard-log), the directories
// below it come from the checkpoint and are opened without following links, created when gone.
DirHandle open_tensorboard_run(const std::string& dir, const fs::path& run_name) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  DirHandle at = DirHandle::open(dir, DirHandle::LastLink::kFollow);
  for (const fs::path& part : run_name) at = at.make_subdir(part.string());
  return at;
}

}  // namespace

TensorBoardLog TensorBoardLog::resume(const std::string& dir, const std::string& name,
                                      const StateReader& state,
                                      const std::function<void(const std::string&)>& note) {
  const std::string run_name = state.get_string("run");
  const std::string file_name = state.get_string("file");
  const int64_t bytes = state.get_int_in("bytes", 0, int64_t{1} << 50);
  // Only DIR/<name>_<N>/events.out.tfevents.*: a crafted checkpoint cannot name another file.
  const fs::path expected_parent = fs::path(name).parent_path();
  const fs::path run_path(run_name);
  if (run_path.parent_path() != expected_parent ||
      run_number(run_path.filename().string(), fs::path(name).filename().string()) == 0)
    throw StateMismatch("checkpoint names the TensorBoard run '" + run_name + "', not " + name +
                        "_<N>");
  if (file_name.rfind("events.out.tfevents.", 0) != 0 || file_name.find('/') != std::string::npos ||
      file_name.find('\0') != std::string::npos)
    throw StateMismatch("checkpoint names the TensorBoard event file '" + file_name +
                        "', not events.out.tfevents.*");
  const DirHandle run_dir = open_tensorboard_run(dir, run_path);
  if (run_dir.kind(file_name) == EntryKind::kMissing) {
    note("note: the TensorBoard event file " + run_dir.child(file_name) +
         " is gone; this run's curves continue in a new file there from the checkpoint's step");
    TensorBoardLog log(run_dir.path(), run_name, EventFile::create(run_dir, wall_time_now()));
    return log;
  }
  // A link or a file that is not regular is refused here (EventFile::reopen).
  TensorBoardLog log(run_dir.path(), run_name,
                     EventFile::reopen(run_dir, file_name, static_cast<uint64_t>(bytes)));
  log.last_ep_rew_mean_ = state.get_double("last_ep_rew_mean");
  log.last_eval_mean_reward_ = state.get_double("last_eval_mean_reward");
  return log;
}

void TensorBoardLog::write(const LogRow& row, int64_t step) {
  LogRow shown;
  for (const auto& [key, value] : row)
    if (!excluded_from_tensorboard(key)) shown.emplace(key, value);
  if (const auto it = row.find("rollout/ep_rew_mean"); it != row.end())
    last_ep_rew_mean_ = it->second;
  if (const auto it = row.find("eval/mean_reward"); it != row.end())
    last_eval_mean_reward_ = it->second;
  if (!shown.empty()) file_.write(scalars_event(wall_time_now(), step, shown));
}

void TensorBoardLog::finish(int64_t step, bool finished, const std::string& learning_curve_png) {
  if (!finished) return;
  const auto [width, height] = png_size(learning_curve_png);
  if (width > 0)
    file_.write(image_event(wall_time_now(), step, "images/learning_curve", learning_curve_png,
                            width, height));
  LogRow final_returns;
  if (!std::isnan(last_ep_rew_mean_)) final_returns["final/ep_rew_mean"] = last_ep_rew_mean_;
  if (!std::isnan(last_eval_mean_reward_))
    final_returns["final/eval_mean_reward"] = last_eval_mean_reward_;
  const double now = wall_time_now();
  if (!final_returns.empty()) file_.write(scalars_event(now, step, final_returns));
  file_.write(session_end_event(now, step, true));
}

void TensorBoardLog::write_state(StateWriter out) const {
  out.put_string("run", run_name_);
  out.put_string("file", fs::path(file_.path()).filename().string());
  out.put_int("bytes", static_cast<int64_t>(file_.size()));
  out.put_double("last_ep_rew_mean", last_ep_rew_mean_);
  out.put_double("last_eval_mean_reward", last_eval_mean_reward_);
}

}  // namespace rlrun
