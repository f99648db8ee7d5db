#pragma once
// The `rlrun._core` extension module (python/rlrun/ is the package around it): one bind_*
// function per concept, called from module.cpp. The C++ side speaks flat float32 vectors and
// plain dicts; the Python files shape them into Gymnasium's and SB3's conventions
// (docs/python.md).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/runtime/components/registry.hpp"

namespace rlrun::python {

namespace py = pybind11;

// The registry every binding uses: the built-in components (built once per process).
Registry& module_registry();

// A Space as a dict the Python side turns into gymnasium.spaces (python/rlrun/_spaces.py):
// {"kind": "Box", "low": ndarray, "high": ndarray, "shape": tuple}, {"kind": "Discrete", "n",
// "start"}, {"kind": "MultiDiscrete", "nvec"}, {"kind": "MultiBinary", "n"}, {"kind": "Dict",
// "keys": [...], "spaces": [...]}.
py::dict space_dict(const Space& space);

// rlrun.make's env: the registered env `id` built from `kwargs_yaml` (a YAML/JSON mapping,
// parsed strictly by the env's Config; ConfigError naming `origin`), under a TimeLimit of
// `max_episode_steps` (< 0: the registered limit; 0: none), as gymnasium.make stacks it.
EnvPtr make_registered_env(const std::string& id, const std::string& kwargs_yaml,
                           int max_episode_steps);
// The env's current frame as an (H, W, 3) uint8 array (Gymnasium's rgb_array), None when it
// cannot draw; `frame` and `rgb` are the caller's buffers, kept between calls.
py::object render_rgb(Env& env, std::unique_ptr<Frame>& frame, std::vector<uint8_t>& rgb);
// The present values of an Info (absent ones are NaN) as a dict of floats.
py::dict info_dict(const Info& info);

void bind_env(py::module_& m);
void bind_multi_agent_env(py::module_& m);
void bind_board_game(py::module_& m);
void bind_vec_env(py::module_& m);
void bind_model(py::module_& m);
void bind_train(py::module_& m);
void bind_training_session(py::module_& m);

}  // namespace rlrun::python
