#include "rlrun/runtime/run/resume_point.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <regex>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/io/agent_team_file.hpp"
#include "rlrun/runtime/io/model_budget.hpp"
#include "rlrun/runtime/run/checkpoint_callback.hpp"

namespace rlrun {

namespace fs = std::filesystem;

std::string run_dir_of_checkpoint(const std::string& checkpoint) {
  return fs::path(checkpoint).parent_path().parent_path().string();
}

std::vector<std::string> resume_candidates(const std::string& run_dir_or_checkpoint) {
  // The run directory and checkpoints/ are opened without following links, and only regular
  // step_<N>.zip files are candidates (core/dir_handle.hpp): a run directory may come from
  // anyone.
  std::error_code ec;
  if (fs::is_directory(run_dir_or_checkpoint, ec)) {
    const DirHandle run = DirHandle::open(run_dir_or_checkpoint);
    if (run.kind(kAgentTeamFile) != EntryKind::kMissing)
      throw UsageError("cannot resume " + run_dir_or_checkpoint +
                       ": a per-agent run (env.agent_policies: per_agent, its " + kAgentTeamFile +
                       ") cannot be resumed: its learners' checkpoints hold their models only");
    const std::optional<DirHandle> checkpoints = run.subdir("checkpoints");
    std::vector<std::string> found;
    if (checkpoints)
      for (const std::string& name : CheckpointCallback::list_checkpoints(*checkpoints))
        found.push_back(checkpoints->child(name));
    if (found.empty())
      throw UsageError("cannot resume " + run_dir_or_checkpoint +
                       ": it has no checkpoints/step_<N>.zip (checkpoints are written every "
                       "checkpoint.freq steps and when training is interrupted)");
    std::reverse(found.begin(), found.end());
    return found;
  }
  if (!fs::exists(fs::symlink_status(run_dir_or_checkpoint, ec)))
    throw UsageError("cannot resume " + run_dir_or_checkpoint +
                     ": no such run directory or checkpoint file");
  const fs::path file(run_dir_or_checkpoint);
  if (file.parent_path().filename() != "checkpoints")
    throw UsageError("cannot resume from " + run_dir_or_checkpoint +
                     ": only checkpoints (<run_dir>/checkpoints/step_<N>.zip) hold a training "
                     "state; to start a new run from a model's weights use --init-from");
  const std::optional<DirHandle> checkpoints =
      DirHandle::open(run_dir_of_checkpoint(run_dir_or_checkpoint)).subdir("checkpoints");
  const std::string name = file.filename().string();
  if (!checkpoints || checkpoints->kind(name) != EntryKind::kRegular) {
    if (checkpoints) checkpoints->open_for_reading(name);  // says what it is instead
    throw UsageError("cannot resume " + run_dir_or_checkpoint + ": no such checkpoint file");
  }
  return {run_dir_or_checkpoint};
}

namespace {

// Why `checkpoint` cannot continue `experiment`, or "".
std::string unfit(const std::string& path, const ModelFile& checkpoint,
                  const Experiment& experiment) {
  if (checkpoint.meta.algorithm != experiment.algo.id)
    return "it was written by " + checkpoint.meta.algorithm + ", the run's config trains " +
           experiment.algo.id;
  const int64_t step = checkpoint.meta.num_timesteps;
  if (step < 0 || step > experiment.run.total_timesteps)
    return "it is at step " + std::to_string(step) + ", outside the run's 0.." +
           std::to_string(experiment.run.total_timesteps) +
           " (to train a finished run further, pass --timesteps with a larger total)";
  static const std::regex name("step_([0-9]+)\\.zip");
  std::smatch m;
  const std::string file = fs::path(path).filename().string();
  if (std::regex_match(file, m, name) && m[1].str() != std::to_string(step))
    return "its name says step " + m[1].str() + " but it holds step " + std::to_string(step);
  return "";
}

}  // namespace

ResumePoint open_resume_point(const std::vector<std::string>& candidates,
                              const Experiment& experiment, const Registry& registry) {
  ResumePoint point;
  std::optional<uint64_t> budget;  // checkpoint_tensor_budget builds envs: once
  for (const std::string& path : candidates) {
    std::string problem;
    try {
      point.checkpoint = read_model_header(path);
      if (!point.checkpoint.holds_training_state)
        throw UsageError("cannot resume from " + path +
                         ": it holds no training state (a model file, or a checkpoint of an env "
                         "that cannot save its state)");
      problem = unfit(path, point.checkpoint, experiment);
      if (problem.empty()) {
        // Tensors only within what the run's own algorithm and envs hold (model_budget.hpp).
        if (!budget) budget = checkpoint_tensor_budget(experiment, registry);
        read_model_tensors(point.checkpoint, ModelParts::kCheckpoint, *budget);
      }
    } catch (const RuntimeFailure& e) {
      problem = e.what();
    }
    if (problem.empty()) {
      point.path = path;
      return point;
    }
    if (candidates.size() == 1) throw RuntimeFailure("cannot resume from " + path + ": " + problem);
    point.skipped.push_back(path + ": " + problem);
  }
  std::string tried;
  for (const std::string& s : point.skipped) tried += "\n  " + s;
  throw RuntimeFailure("cannot resume: no checkpoint can continue the run; tried:" + tried);
}

void remove_stale_temporaries(const DirHandle& run_dir) {
  static const std::regex temporary(".+\\.tmp(\\.[A-Za-z0-9]{6})?");
  const auto clean = [](const DirHandle& dir) {
    for (const DirHandle::Entry& entry : dir.list())
      if (entry.kind == EntryKind::kRegular && std::regex_match(entry.name, temporary))
        dir.remove(entry.name);
  };
  clean(run_dir);
  if (const std::optional<DirHandle> checkpoints = run_dir.subdir("checkpoints"))
    clean(*checkpoints);
}

}  // namespace rlrun
