#include "rlrun/runtime/run/checkpoint_callback.hpp"

#include <algorithm>
#include <regex>

#include "rlrun/core/errors.hpp"

namespace rlrun {

CheckpointCallback::CheckpointCallback(TrainingContext& context, const CheckpointConfig& config)
    : context_(context),
      config_(config),
      dir_(DirHandle::open(context.run_dir).make_subdir("checkpoints")),
      next_(config.freq) {
  kept_ = list_checkpoints(dir_);
}

std::vector<std::string> CheckpointCallback::list_checkpoints(const DirHandle& dir) {
  static const std::regex name("step_([0-9]{1,18})\\.zip");
  std::vector<std::pair<int64_t, std::string>> found;
  for (const DirHandle::Entry& entry : dir.list()) {
    std::smatch m;
    if (entry.kind == EntryKind::kRegular && std::regex_match(entry.name, m, name))
      found.emplace_back(std::stoll(m[1]), entry.name);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  for (auto& f : found) names.push_back(std::move(f.second));
  return names;
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
  const std::string name = "step_" + std::to_string(num_timesteps) + ".zip";
  const std::string path = dir_.child(name);
  context_.save_checkpoint(name);
  kept_.erase(std::remove(kept_.begin(), kept_.end(), name), kept_.end());
  kept_.push_back(name);
  std::string removed;
  while (config_.keep > 0 && static_cast<int>(kept_.size()) > config_.keep) {
    dir_.remove(kept_.front());  // unlinkat in checkpoints/ itself: never elsewhere
    removed.append(" ").append(kept_.front());
    kept_.erase(kept_.begin());
  }
  std::string message = "checkpoint saved to " + path;
  if (!removed.empty()) message.append(" (removed").append(removed).append(")");
  context_.message(message);
}

}  // namespace rlrun
