// rlrun._core.VecEnv: n of rlrun's envs stepped together in C++ in one call (EnvPool's idea,
// github.com/sail-sg/envpool), on rlrun's VecEnv (env/vec_env.hpp: same-step auto-reset,
// final_obs kept, env i seeded seed + i). Every step hands Python a few arrays — one copy of
// the observations, rewards, flags, the info values as an (n, keys) matrix — and no per-env
// Python objects; python/rlrun/_vector.py turns them into Gymnasium 1.x's VectorEnv API.
#include <pybind11/stl.h>

#include <cstring>
#include <limits>
#include <optional>

#include "bindings.hpp"
#include "rlrun/env/vec_env.hpp"

namespace rlrun::python {

namespace {

std::vector<EnvPtr> make_envs(const std::string& id, int n, const std::string& kwargs_yaml,
                              int max_episode_steps) {
  if (n < 1)
    throw py::value_error("make_vec: num_envs must be at least 1, got " + std::to_string(n));
  std::vector<EnvPtr> envs;
  for (int i = 0; i < n; ++i)
    envs.push_back(make_registered_env(id, kwargs_yaml, max_episode_steps));
  return envs;
}

class PyVecEnv {
 public:
  PyVecEnv(const std::string& id, int n, const std::string& kwargs_yaml, int max_episode_steps)
      : vec_(make_envs(id, n, kwargs_yaml, max_episode_steps)), id_(id) {
    keys_ = vec_.env(0).info().keys();
  }

  // (num_envs, obs_dim) float32: VecEnv's obs matrix is obs_dim x num_envs column-major, the
  // same bytes as a row-major (num_envs, obs_dim) array: one memcpy.
  py::array_t<float> obs_copy(const Eigen::MatrixXf& m) const {
    py::array_t<float> out(
        {static_cast<py::ssize_t>(m.cols()), static_cast<py::ssize_t>(m.rows())});
    std::memcpy(out.mutable_data(), m.data(), sizeof(float) * static_cast<size_t>(m.size()));
    return out;
  }

  // The info values of the last step (`current` false: VecEnv's info(i), copied before the
  // auto-reset) or of each env's current state (`current`: after an auto-reset the new
  // episode's first one, what Gymnasium's same-step mode returns as infos, with the step's
  // under final_info). A multi-agent env's slots share a copy: they keep the step's.
  py::array_t<double> info_values(bool current = false) const {
    const int n = vec_.num_envs();
    const bool per_copy = current && vec_.num_copies() == n;
    const py::ssize_t k = static_cast<py::ssize_t>(keys_.size());
    py::array_t<double> out({static_cast<py::ssize_t>(n), k});
    double* data = out.mutable_data();
    for (int i = 0; i < n; ++i) {
      const Info& info = per_copy ? vec_.env(i).info() : vec_.info(i);
      for (py::ssize_t j = 0; j < k; ++j)
        data[i * k + j] = j < static_cast<py::ssize_t>(info.values().size())
                              ? info.values()[static_cast<size_t>(j)]
                              : Info::kAbsent;
    }
    return out;
  }

  py::tuple reset(std::optional<uint64_t> seed) {
    {
      py::gil_scoped_release release;
      if (seed) vec_.seed(*seed);
      vec_.reset();
    }
    return py::make_tuple(obs_copy(vec_.obs()), info_values());
  }

  // actions: (num_envs, act_dim) float32, C order (the bytes of an act_dim x num_envs matrix).
  py::tuple step(py::array_t<float, py::array::c_style | py::array::forcecast> actions) {
    const int n = vec_.num_envs();
    const int act_dim = vec_.action_space().flat_dim();
    if (actions.size() != static_cast<py::ssize_t>(n) * act_dim)
      throw py::value_error("step: " + std::to_string(n) + " envs of " + std::to_string(act_dim) +
                            " action values need " + std::to_string(n * act_dim) + " values, got " +
                            std::to_string(actions.size()));
    const Eigen::Map<const Eigen::MatrixXf> a(actions.data(), act_dim, n);
    const Space& space = vec_.action_space();
    if (!space.is_box())
      for (int i = 0; i < n; ++i)
        if (!space.contains({a.col(i).data(), static_cast<size_t>(act_dim)}))
          throw py::value_error("step: " + id_ + ": action of env " + std::to_string(i) +
                                " not in " + space.describe());
    {
      py::gil_scoped_release release;
      vec_.step(a);
    }
    py::array_t<double> rewards(n);
    py::array_t<bool> terminated(n), truncated(n);
    std::memcpy(rewards.mutable_data(), vec_.rewards().data(),
                sizeof(double) * static_cast<size_t>(n));
    bool* term = terminated.mutable_data();
    bool* trunc = truncated.mutable_data();
    bool any_done = false;
    for (int i = 0; i < n; ++i) {
      term[i] = vec_.terminated(i);
      trunc[i] = vec_.truncated(i);
      any_done = any_done || term[i] || trunc[i];
    }
    // final_obs only when an episode ended (rows of envs that did not end are NaN).
    py::object final_obs = any_done ? py::object(obs_copy(vec_.final_obs())) : py::none();
    return py::make_tuple(obs_copy(vec_.obs()), rewards, terminated, truncated, final_obs,
                          info_values(/*current=*/true), info_values());
  }

  VecEnv vec_;
  std::string id_;
  std::vector<std::string> keys_;
};

}  // namespace

void bind_vec_env(py::module_& m) {
  py::class_<PyVecEnv>(m, "VecEnv")
      .def(py::init<const std::string&, int, const std::string&, int>(), py::arg("id"),
           py::arg("num_envs"), py::arg("kwargs_yaml") = "{}", py::arg("max_episode_steps") = -1)
      .def("reset", &PyVecEnv::reset, py::arg("seed"),
           "(obs (n, obs_dim) float32, info values (n, keys) float64, NaN = absent)")
      .def("step", &PyVecEnv::step, py::arg("actions"),
           "(obs, rewards, terminated, truncated, final_obs or None, info values of each env's "
           "current state (after an auto-reset: the new episode's), info values of the step)")
      .def_property_readonly("num_envs", [](const PyVecEnv& self) { return self.vec_.num_envs(); })
      .def_property_readonly("info_keys", [](const PyVecEnv& self) { return self.keys_; })
      .def_property_readonly(
          "observation_space",
          [](const PyVecEnv& self) { return space_dict(self.vec_.observation_space()); })
      .def_property_readonly(
          "action_space", [](const PyVecEnv& self) { return space_dict(self.vec_.action_space()); })
      .def_property_readonly("id", [](const PyVecEnv& self) { return self.id_; });
}

}  // namespace rlrun::python
