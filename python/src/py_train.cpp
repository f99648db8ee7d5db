// rlrun._core.train_file / train_text: `rlrun train` in-process (runtime/run/trainer.hpp), for
// rlrun.train (python/rlrun/_train.py). Training runs without the GIL; while it runs,
// rlrun's own SIGINT/SIGTERM handlers (core/interrupt.hpp) replace Python's, so Ctrl-C stops
// it as on the command line: at the next safe point, with a checkpoint; Python's handlers come
// back afterwards and rlrun.train raises KeyboardInterrupt.
#include <pybind11/stl.h>

#include <csignal>

#include "bindings.hpp"
#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/execution_context.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "scoped_training_signals.hpp"

namespace rlrun::python {

namespace {

py::dict run(const Experiment& experiment) {
  TrainOutcome outcome;
  {
    ScopedTrainingSignals signals;
    py::gil_scoped_release release;
    // As `rlrun --threads auto`: the CPUs this process may use (the result is the same with any
    // number). The pool lives for this training only.
    ThreadPool pool(available_cpus());
    outcome = train_experiment(experiment, module_registry(), ExecutionContext{&pool});
  }
  py::dict d;
  d["run_dir"] = outcome.run_dir;
  d["model_path"] = outcome.model_path;
  d["timesteps"] = outcome.timesteps;
  d["wall_seconds"] = outcome.wall_seconds;
  d["interrupted"] = outcome.interrupted;
  d["checkpoint_path"] = outcome.checkpoint_path;
  d["stop_reason"] = outcome.stop_reason;
  return d;
}

}  // namespace

void bind_train(py::module_& m) {
  m.def(
      "train_file",
      [](const std::string& path, const std::vector<std::string>& overrides) {
        return run(load_experiment(path, overrides, module_registry()));
      },
      py::arg("path"), py::arg("overrides"),
      "Trains the experiment file with `--set` overrides; returns the outcome as a dict.");
  m.def(
      "train_text",
      [](const std::string& text, const std::string& origin, const std::string& default_name,
         const std::vector<std::string>& overrides) {
        return run(load_experiment_text(text, origin, default_name, overrides, module_registry()));
      },
      py::arg("text"), py::arg("origin"), py::arg("default_name"), py::arg("overrides"),
      "Trains an experiment given as YAML text; returns the outcome as a dict.");
}

}  // namespace rlrun::python
