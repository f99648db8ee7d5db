#pragma once
// `obs_log: {freq, env}` — the course's ObsSaveCallback: records the observations of training
// env `env` (default 0) and saves them every `freq` TOTAL env steps as
//     <run_dir>/obs_log/obs_<N>.npy      float32, shape (rows, obs_dim), C order
// where N (zero-padded to 10 digits, so names sort in time order) is the total step count at
// the end of the chunk, and the rest at the end of training (also after Ctrl-C or an early
// stop). One row per VecEnv step: the observation that step returned, i.e. the final
// observation when the step ended an episode (never the auto-reset one), so consecutive rows
// are the states the env went through. They are the env's OWN observations, recorded below
// the YAML wrappers (an ObservationTap above the Monitor): NormalizeObservation or FrameStack
// do not change them, and `rlrun record --from-obs` can draw them. With freq F and n_envs E a
// chunk holds F / E rows. A resumed run continues the chunk in progress at its checkpoint
// (whose rows the checkpoint holds) and removes the chunks written after it, so the files
// are those of an uninterrupted run.
#include <cstdint>
#include <string>
#include <vector>

#include "rlrun/core/dir_handle.hpp"
#include "rlrun/runtime/experiment/obs_log_config.hpp"
#include "rlrun/runtime/run/callback.hpp"
#include "rlrun/wrappers/observation_tap.hpp"

namespace rlrun {

class ObsLogCallback : public Callback {
 public:
  // Throws std::logic_error if training env `config.env` has no ObservationTap (the trainer
  // adds it when obs_log.freq > 0).
  ObsLogCallback(TrainingContext& context, const ObsLogConfig& config);
  bool on_step(int64_t num_timesteps) override;
  void on_training_end(int64_t num_timesteps, bool resumable) override;
  void write_state(StateWriter& out) const override;
  void read_state(const StateReader& in) override;

 private:
  void save_chunk(int64_t num_timesteps);

  TrainingContext& context_;
  const ObsLogConfig& config_;
  const ObservationTap* tap_;
  DirHandle dir_;  // <run_dir>/obs_log, held open: never a link (core/dir_handle.hpp)
  int obs_dim_;
  int64_t next_;
  int64_t last_chunk_step_ = 0;  // N of the last full chunk written
  std::vector<float> rows_;      // obs_dim floats per row
};

}  // namespace rlrun
