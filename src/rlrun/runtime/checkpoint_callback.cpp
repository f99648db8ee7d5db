#include "rlrun/runtime/checkpoint_callback.hpp"

#include "rlrun/runtime/experiment.hpp"

#include <algorithm>
#include <filesystem>
#include <regex>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

CheckpointCallback::CheckpointCallback(TrainingContext& context)
    : context_(context),
      config_(context.experiment.checkpoint),
      dir_(context.run_dir + "/checkpoints"),
      next_(context.experiment.checkpoint.freq) {
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw RuntimeFailure("cannot create " + dir_ + ": " + ec.message());
  kept_ = list_checkpoints(dir_);
}

std::vector<std::string> CheckpointCallback::list_checkpoints(const std::string& dir) {
  static const std::regex name("step_([0-9]+)\\.zip");
  std::vector<std::pair<int64_t, std::string>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::smatch m;
    const std::string file = entry.path().filename().string();
    if (std::regex_match(file, m, name)) found.emplace_back(std::stoll(m[1]), entry.path().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> paths;
  for (auto& f : found) paths.push_back(std::move(f.second));
  return paths;
}

bool CheckpointCallback::on_step(int64_t num_timesteps) {
  if (crossed(num_timesteps, config_.freq, next_)) due_ = true;
  return true;
}

void CheckpointCallback::write_state(StateWriter& out) const {
  out.put_int("next", next_);
  out.put_bool("due", due_);
}

void CheckpointCallback::read_state(const StateReader& in) {
  next_ = in.get_count("next");  // crossed() counts up from it
  due_ = in.get_bool("due");
}

void CheckpointCallback::at_safe_point(int64_t num_timesteps) {
  // The step count of the checkpoint is the one it was taken at, also when n_envs steps at
  // once crossed the multiple of freq (SB3 names its files by num_timesteps the same way).
  if (!due_) return;
  due_ = false;  // before saving: the checkpoint holds the state after this point
  const std::string path = dir_ + "/step_" + std::to_string(num_timesteps) + ".zip";
  context_.save_checkpoint(path);
  kept_.erase(std::remove(kept_.begin(), kept_.end(), path), kept_.end());
  kept_.push_back(path);
  std::string removed;
  while (config_.keep > 0 && static_cast<int>(kept_.size()) > config_.keep) {
    std::error_code ec;
    fs::remove(kept_.front(), ec);
    removed.append(" ").append(fs::path(kept_.front()).filename().string());
    kept_.erase(kept_.begin());
  }
  std::string message = "checkpoint saved to " + path;
  if (!removed.empty()) message.append(" (removed").append(removed).append(")");
  context_.message(message);
}

}  // namespace rlrun
