#include "rlrun/runtime/run/trajectory_tap.hpp"

#include <algorithm>

#include "rlrun/core/checked_file.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/float_format.hpp"
#include "rlrun/env/physics_state.hpp"
#include "rlrun/runtime/experiment/base_layer.hpp"

namespace rlrun {

TrajectoryTap::TrajectoryTap(EnvPtr env)
    : Wrapper(std::move(env)), obs_(static_cast<size_t>(inner_->observation_space().flat_dim())) {
  csv_ = "episode,step";
  for (size_t i = 0; i < obs_.size(); ++i) csv_ += ",obs_" + std::to_string(i);
  if (const PhysicsState* physics = physics_state_of(*inner_)) {
    for (size_t i = 0; i < physics->qpos().size(); ++i) csv_ += ",qpos_" + std::to_string(i);
    for (size_t i = 0; i < physics->qvel().size(); ++i) csv_ += ",qvel_" + std::to_string(i);
    for (size_t i = 0; i < physics->qacc_warmstart().size(); ++i)
      csv_ += ",qacc_warmstart_" + std::to_string(i);
  }
  for (int i = 0; i < inner_->action_space().flat_dim(); ++i)
    csv_ += ",action_" + std::to_string(i);
  csv_ += ",reward,terminated,truncated\n";
}

void TrajectoryTap::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  std::copy(obs.begin(), obs.end(), obs_.begin());
  ++episode_;
  step_ = 0;
}

StepResult TrajectoryTap::step(std::span<const float> action, std::span<float> obs) {
  // The row is built before the step: an env that throws leaves the action that broke it.
  csv_ += std::to_string(episode_) + ',' + std::to_string(step_);
  for (float v : obs_) csv_ += ',' + float32_text(v);
  if (const PhysicsState* physics = physics_state_of(*inner_)) {
    for (double v : physics->qpos()) csv_ += ',' + python_float_repr(v);
    for (double v : physics->qvel()) csv_ += ',' + python_float_repr(v);
    for (double v : physics->qacc_warmstart()) csv_ += ',' + python_float_repr(v);
  }
  for (float v : action) csv_ += ',' + float32_text(v);
  const StepResult result = inner_->step(action, obs);
  csv_ += ',' + python_float_repr(result.reward) + (result.terminated ? ",1" : ",0") +
          (result.truncated ? ",1\n" : ",0\n");
  std::copy(obs.begin(), obs.end(), obs_.begin());
  ++step_;
  return result;
}

TrajectoryTap& tap_trajectory(Env& stack) {
  if (stack.num_agents() > 1)
    throw UsageError("--trajectory: " + stack.id() + " has " + std::to_string(stack.num_agents()) +
                     " agents; trajectories are recorded for single-agent envs");
  return insert_base_layer<TrajectoryTap>(
      stack, [](EnvPtr env) { return std::make_unique<TrajectoryTap>(std::move(env)); });
}

void write_trajectory(const TrajectoryTap& tap, const std::string& path) {
  CheckedFile file(path, CheckedFile::Mode::kTruncate);
  file << tap.csv();
  file.close();
}

}  // namespace rlrun
