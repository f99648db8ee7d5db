#include "rlrun/runtime/run/training_callbacks.hpp"

#include "rlrun/runtime/run/checkpoint_callback.hpp"
#include "rlrun/runtime/run/eval_callback.hpp"
#include "rlrun/runtime/run/obs_log_callback.hpp"
#include "rlrun/runtime/run/self_play_callback.hpp"
#include "rlrun/runtime/run/video_callback.hpp"

namespace rlrun {

std::vector<std::unique_ptr<Callback>> make_callbacks(const Experiment& e,
                                                      TrainingContext& context) {
  std::vector<std::unique_ptr<Callback>> callbacks;
  if (e.eval.freq > 0) callbacks.push_back(std::make_unique<EvalCallback>(context, e.eval));
  if (e.checkpoint.freq > 0)
    callbacks.push_back(std::make_unique<CheckpointCallback>(context, e.checkpoint));
  if (e.obs_log.freq > 0) callbacks.push_back(std::make_unique<ObsLogCallback>(context, e.obs_log));
  if (e.video.freq > 0) callbacks.push_back(std::make_unique<VideoCallback>(context, e.video));
  // Last, so the other callbacks keep their places in checkpoints (training_state_io.cpp).
  if (e.self_play.freq > 0)
    callbacks.push_back(std::make_unique<SelfPlayCallback>(context, e.self_play));
  return callbacks;
}

}  // namespace rlrun
