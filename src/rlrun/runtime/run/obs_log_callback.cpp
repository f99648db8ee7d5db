#include "rlrun/runtime/run/obs_log_callback.hpp"

#include <cstdio>
#include <cstring>
#include <regex>
#include <stdexcept>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/npy.hpp"
#include "rlrun/runtime/experiment/env_statistics.hpp"

namespace rlrun {

ObsLogCallback::ObsLogCallback(TrainingContext& context, const ObsLogConfig& config)
    : context_(context),
      config_(config),
      tap_(find_wrapper<ObservationTap>(context.env.env(config.env))),
      dir_(DirHandle::open(context.run_dir).make_subdir("obs_log")),
      next_(config.freq) {
  if (!tap_) throw std::logic_error("obs_log: training env has no ObservationTap");
  obs_dim_ = static_cast<int>(tap_->last_step_obs().size());
  // One chunk's rows, allocated once: the step loop does not allocate.
  const int64_t rows = config_.freq / context.env.num_envs() + 2;
  rows_.reserve(static_cast<size_t>(rows * obs_dim_));
}

bool ObsLogCallback::on_step(int64_t num_timesteps) {
  const std::span<const float> obs = tap_->last_step_obs();
  rows_.insert(rows_.end(), obs.begin(), obs.end());
  if (crossed(num_timesteps, config_.freq, next_)) {
    save_chunk(num_timesteps);
    last_chunk_step_ = num_timesteps;
  }
  return true;
}

void ObsLogCallback::on_training_end(int64_t num_timesteps, bool /*resumable*/) {
  // Also when resumable: the partial chunk is what a user who does not resume gets; a resume
  // removes it (read_state) and writes the full chunk.
  if (!rows_.empty()) save_chunk(num_timesteps);
}

void ObsLogCallback::write_state(StateWriter& out) const {
  out.put_int("next", next_);
  out.put_int("last_chunk_step", last_chunk_step_);
  out.put_vector("rows", rows_);
}

void ObsLogCallback::read_state(const StateReader& in) {
  next_ = in.get_count("next");  // crossed() counts up from it
  last_chunk_step_ = in.get_count("last_chunk_step");
  const std::vector<float> rows = in.get_span<float>("rows");
  if (rows.size() % static_cast<size_t>(obs_dim_) != 0)
    throw StateMismatch("checkpoint obs_log rows do not match the observation size " +
                        std::to_string(obs_dim_));
  rows_.assign(rows.begin(), rows.end());
  static const std::regex name("obs_([0-9]{1,18})\\.npy");
  for (const DirHandle::Entry& entry : dir_.list()) {
    std::smatch m;
    if (std::regex_match(entry.name, m, name) && std::stoll(m[1]) > last_chunk_step_)
      dir_.remove(entry.name);  // in obs_log/ itself: never elsewhere
  }
}

void ObsLogCallback::save_chunk(int64_t num_timesteps) {
  Tensor t;
  t.dtype = DType::kFloat32;
  t.shape = {static_cast<int64_t>(rows_.size() / obs_dim_), obs_dim_};
  t.bytes.resize(rows_.size() * sizeof(float));
  std::memcpy(t.bytes.data(), rows_.data(), t.bytes.size());
  const std::vector<uint8_t> bytes = encode_npy(t);
  char name[64];
  std::snprintf(name, sizeof name, "obs_%010lld.npy", static_cast<long long>(num_timesteps));
  // Atomic and checked (a full disk is an error naming the file, not a short chunk).
  dir_.write_atomic(name,
                    std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  rows_.clear();  // keeps its capacity
}

}  // namespace rlrun
