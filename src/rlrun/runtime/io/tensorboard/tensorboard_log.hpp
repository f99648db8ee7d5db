#pragma once
// A run's TensorBoard log (`run.tensorboard_log: DIR`, `train --tensorboard-log DIR`): SB3's
// `tensorboard_log=` + `tb_log_name`. Each training run gets its own TensorBoard run
// directory DIR/<tb_log_name>_<N> (N one more than the highest already there, as SB3's
// get_latest_run_id numbers them), holding one event file
// (runtime/io/tensorboard/event_file.hpp) with
//   * every progress.csv row as scalars at step = num_timesteps, with SB3's tags; the keys SB3
//     logs with exclude="tensorboard" (time/iterations, time/time_elapsed,
//     time/total_timesteps, time/episodes, train/n_updates) are left out as SB3 leaves them out;
//   * at the end, the learning curve as an image (images/learning_curve);
//   * the HParams plugin's session start (the resolved config) and, when the run ends, its end
//     with the final returns as scalars final/ep_rew_mean and final/eval_mean_reward, so
//     TensorBoard's HParams tab lists runs with their settings and results.
// A resumed run continues the same TensorBoard run: checkpoints record the event file and
// its length, and the resume cuts the file back to that length before appending (no
// duplicated or missing steps; SB3's resumed runs start a new curve at step 0 unless told
// otherwise).
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "rlrun/core/logger.hpp"
#include "rlrun/core/state_dict.hpp"
#include "rlrun/runtime/io/tensorboard/event_file.hpp"

namespace rlrun {

class TensorBoardLog : public LogSink {
 public:
  // A new TensorBoard run DIR/<name>_<N> for a new training run; `config` is the resolved
  // experiment (its values become the hyperparameters).
  static TensorBoardLog start(const std::string& dir, const std::string& name,
                              const YAML::Node& config);
  // The TensorBoard run a checkpoint's state names, inside `dir` and named <name>_<N>
  // (checkpoints are untrusted: anything else is refused), its event file cut back to the
  // checkpoint. `note` receives a line when the file is gone and a new one is started.
  static TensorBoardLog resume(const std::string& dir, const std::string& name,
                               const StateReader& state,
                               const std::function<void(const std::string&)>& note);

  void write(const LogRow& row, int64_t step) override;
  // The run ended: final returns and the HParams session end (`finished`: it trained to its
  // end; an interrupted run that will be resumed writes nothing here).
  // `learning_curve_png` (may be empty): the run's learning curve, shown under
  // images/learning_curve.
  void finish(int64_t step, bool finished, const std::string& learning_curve_png = "");

  void write_state(StateWriter out) const;

  // DIR/<name>_<N>, for messages.
  const std::string& run_dir() const { return run_dir_; }

 private:
  TensorBoardLog(std::string run_dir, std::string run_name, EventFile file)
      : run_dir_(std::move(run_dir)), run_name_(std::move(run_name)), file_(std::move(file)) {}
  std::string run_dir_;
  std::string run_name_;  // <name>_<N>, relative to DIR
  EventFile file_;
  // The last values of the returns, for the final scalars.
  double last_ep_rew_mean_ = std::nan("");
  double last_eval_mean_reward_ = std::nan("");
};

// The keys SB3 logs with exclude="tensorboard" (stable_baselines3/common/on_policy_algorithm.py,
// off_policy_algorithm.py, callbacks.py, the algorithms' train()).
bool excluded_from_tensorboard(const std::string& key);

}  // namespace rlrun
