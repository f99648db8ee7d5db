// rlrun._core: rlrun's envs, models and trainer for Python (pybind11). Exceptions carry the
// CLI's messages (docs/commands.md): ConfigError and UsageError (bad input, exit 2 on the command
// line) are ValueErrors, RuntimeFailure (exit 1) a RuntimeError, Interrupted (Ctrl-C) a
// KeyboardInterrupt.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "process_environment.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/components/builtins.hpp"
#include "rlrun/runtime/components/plugin_loader.hpp"

namespace rlrun::python {

Registry& module_registry() {
  static Registry registry = make_builtin_registry();
  return registry;
}

py::dict space_dict(const Space& space) {
  py::dict d;
  d["kind"] = space_kind_name(space.kind());
  switch (space.kind()) {
    case SpaceKind::kBox: {
      std::vector<py::ssize_t> shape(space.shape().begin(), space.shape().end());
      py::array_t<float> low(shape), high(shape);
      std::copy(space.low().begin(), space.low().end(), low.mutable_data());
      std::copy(space.high().begin(), space.high().end(), high.mutable_data());
      d["low"] = low;
      d["high"] = high;
      d["shape"] = py::tuple(py::cast(shape));
      d["dtype"] = box_dtype_name(space.dtype());
      break;
    }
    case SpaceKind::kDiscrete:
      d["n"] = space.n();
      d["start"] = space.start();
      break;
    case SpaceKind::kMultiDiscrete: d["nvec"] = space.nvec(); break;
    case SpaceKind::kMultiBinary: d["n"] = space.n(); break;
    case SpaceKind::kDict: {
      py::list spaces;
      for (const Space& s : space.subspaces()) spaces.append(space_dict(s));
      d["keys"] = space.keys();
      d["spaces"] = spaces;
      break;
    }
  }
  return d;
}

}  // namespace rlrun::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace rlrun::python;
  m.doc() = "rlrun's native core: envs, vector envs, models and training (see the rlrun package)";
  // The RLRUN_* variables, once (the package has set RLRUN_PYTHON to its interpreter by now).
  try {
    rlrun::apply_process_environment();
  } catch (const std::runtime_error& e) {
    throw rlrun::UsageError(std::string("RLRUN_KERNELS=") + e.what());
  }
  m.attr("__version__") = RLRUN_VERSION;
  // Subclasses of the standard exceptions, so `except ValueError` catches a bad config.
  py::register_exception<rlrun::ConfigError>(m, "ConfigError", PyExc_ValueError);
  py::register_exception<rlrun::UsageError>(m, "UsageError", PyExc_ValueError);
  py::register_exception<rlrun::RuntimeFailure>(m, "RuntimeFailure", PyExc_RuntimeError);
  // Stopped by Ctrl-C where no safe point could be waited for (a Python env's worker that hangs).
  py::register_exception<rlrun::Interrupted>(m, "Interrupted", PyExc_KeyboardInterrupt);
  m.def(
      "list_envs",
      [] {
        py::list out;
        for (const rlrun::EnvEntry& e : module_registry().envs())
          out.append(py::make_tuple(e.id, e.description, e.max_episode_steps));
        return out;
      },
      "The registered envs as (id, description, max_episode_steps) tuples, as `rlrun list`.");
  m.def(
      "load_plugin",
      [](const std::string& path) { return rlrun::load_plugin(path, module_registry()); },
      py::arg("path"), "Loads an env plugin library (as --plugin); returns its resolved path.");
  bind_env(m);
  bind_multi_agent_env(m);
  bind_board_game(m);
  bind_vec_env(m);
  bind_model(m);
  bind_train(m);
  bind_training_session(m);
}
