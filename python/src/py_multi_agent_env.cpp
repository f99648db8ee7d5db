// rlrun._core.MultiAgentEnv: one of rlrun's registered envs with all its agents, stepped from
// Python (rlrun.parallel_env and rlrun.env, python/rlrun/_pettingzoo.py, shape it into
// PettingZoo's APIs). Arrays are agent-major, as include/rlrun/env.hpp lays agents out:
// observations (num_agents, *shape), actions (num_agents, act_dim), one reward and two flags
// per agent. An env of one agent works too (PettingZoo with a single agent).
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "rlrun/env/action_mask.hpp"
#include "rlrun/env/agent_names.hpp"
#include "rlrun/frame.hpp"

namespace rlrun::python {

namespace {

class PyMultiAgentEnv {
 public:
  PyMultiAgentEnv(const std::string& id, const std::string& kwargs_yaml, int max_episode_steps)
      : env_(make_registered_env(id, kwargs_yaml, max_episode_steps)),
        id_(id),
        agents_(static_cast<size_t>(env_->num_agents())),
        obs_dim_(static_cast<size_t>(env_->observation_space().flat_dim())),
        act_dim_(static_cast<size_t>(env_->action_space().flat_dim())),
        mask_size_(static_cast<size_t>(action_mask_size(env_->action_space()))),
        results_(agents_) {}

  Env& env() {
    if (!env_) throw py::value_error(id_ + ": the env is closed");
    return *env_;
  }

  std::vector<std::string> agent_names() {
    std::vector<std::string> names;
    for (size_t a = 0; a < agents_; ++a) names.push_back(agent_name_of(env(), static_cast<int>(a)));
    return names;
  }

  // (obs, info, masks)
  py::tuple reset(std::optional<uint64_t> seed) {
    Env& e = env();
    py::array_t<float> obs = new_obs();
    {
      py::gil_scoped_release release;
      e.reset(seed, {obs.mutable_data(), agents_ * obs_dim_});
    }
    return with_info(obs);
  }

  // (obs, rewards, terminated, truncated, info, masks) for `actions` of shape
  // (num_agents, act_dim) (or num_agents values when act_dim is 1).
  py::tuple step(const py::object& actions) {
    Env& e = env();
    using Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
    const Array a = Array::ensure(actions);
    if (!a) throw py::type_error("step: " + id_ + ": actions must be numeric");
    if (static_cast<size_t>(a.size()) != agents_ * act_dim_)
      throw py::value_error("step: " + id_ + " takes " + std::to_string(agents_) + " x " +
                            std::to_string(act_dim_) + " action values, got " +
                            std::to_string(a.size()));
    actions_.assign(a.data(), a.data() + a.size());
    const Space& space = e.action_space();
    if (!space.is_box())
      for (size_t i = 0; i < agents_; ++i)
        if (!space.contains({actions_.data() + i * act_dim_, act_dim_}))
          throw py::value_error("step: " + id_ + ": agent " + std::to_string(i) +
                                "'s action is not in " + space.describe());
    py::array_t<float> obs = new_obs();
    {
      py::gil_scoped_release release;
      e.step_agents(actions_, {obs.mutable_data(), agents_ * obs_dim_}, results_);
    }
    py::array_t<double> rewards(static_cast<py::ssize_t>(agents_));
    py::array_t<bool> terminated(static_cast<py::ssize_t>(agents_));
    py::array_t<bool> truncated(static_cast<py::ssize_t>(agents_));
    for (size_t i = 0; i < agents_; ++i) {
      rewards.mutable_data()[i] = results_[i].reward;
      terminated.mutable_data()[i] = results_[i].terminated;
      truncated.mutable_data()[i] = results_[i].truncated;
    }
    const py::tuple rest = with_info(obs);
    return py::make_tuple(rest[0], rewards, terminated, truncated, rest[1], rest[2]);
  }

  // An (H, W, 3) uint8 frame of the whole env, None if it cannot draw.
  py::object render() { return render_rgb(env(), frame_, rgb_); }

  void close() {
    frame_.reset();
    env_.reset();
  }

  EnvPtr env_;
  std::string id_;
  size_t agents_, obs_dim_, act_dim_, mask_size_;
  std::vector<StepResult> results_;
  std::vector<float> actions_;
  std::unique_ptr<Frame> frame_;
  std::vector<uint8_t> rgb_;

 private:
  // (num_agents, *shape) for a Box, (num_agents, flat_dim) otherwise (Python shapes those).
  py::array_t<float> new_obs() {
    const Space& space = env().observation_space();
    std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(agents_)};
    if (space.is_box())
      shape.insert(shape.end(), space.shape().begin(), space.shape().end());
    else
      shape.push_back(static_cast<py::ssize_t>(obs_dim_));
    return py::array_t<float>(shape);
  }

  // (obs, info without the mask keys, masks (num_agents, mask entries) int8 or None): the
  // env's info is the whole env's (every agent sees it); its action_mask.<k> keys hold the
  // agents' masks agent-major (env/action_mask.hpp).
  py::tuple with_info(const py::array_t<float>& obs) {
    const Info& info = env().info();
    py::dict d;
    std::vector<int8_t> masks(agents_ * mask_size_, -1);
    bool has_mask = false;
    for (size_t i = 0; i < info.keys().size(); ++i) {
      const int key = static_cast<int>(i);
      if (!info.has(key)) continue;
      const std::string& name = info.keys()[i];
      if (mask_size_ > 0 && name.starts_with("action_mask.")) {
        const size_t entry = std::stoul(name.substr(12));
        if (entry < masks.size()) {
          masks[entry] = info.get(key) != 0.0 ? 1 : 0;
          has_mask = true;
        }
        continue;
      }
      d[py::str(name)] = info.get(key);
    }
    if (!has_mask) return py::make_tuple(obs, d, py::none());
    py::array_t<int8_t> out(
        {static_cast<py::ssize_t>(agents_), static_cast<py::ssize_t>(mask_size_)});
    // An entry the env did not report is legal (as an env without a mask).
    for (size_t k = 0; k < masks.size(); ++k) out.mutable_data()[k] = masks[k] == 0 ? 0 : 1;
    return py::make_tuple(obs, d, out);
  }
};

}  // namespace

void bind_multi_agent_env(py::module_& m) {
  py::class_<PyMultiAgentEnv>(m, "MultiAgentEnv")
      .def(py::init<const std::string&, const std::string&, int>(), py::arg("id"),
           py::arg("kwargs_yaml") = "{}", py::arg("max_episode_steps") = -1)
      .def("reset", &PyMultiAgentEnv::reset, py::arg("seed"))
      .def("step", &PyMultiAgentEnv::step, py::arg("actions"))
      .def("render", &PyMultiAgentEnv::render)
      .def("close", &PyMultiAgentEnv::close)
      .def_property_readonly("closed", [](const PyMultiAgentEnv& self) { return !self.env_; })
      .def_property_readonly("agent_names", &PyMultiAgentEnv::agent_names)
      .def_property_readonly("num_agents", [](const PyMultiAgentEnv& self) { return self.agents_; })
      .def_property_readonly(
          "observation_space",
          [](PyMultiAgentEnv& self) { return space_dict(self.env().observation_space()); })
      .def_property_readonly(
          "action_space",
          [](PyMultiAgentEnv& self) { return space_dict(self.env().action_space()); })
      .def_property_readonly("render_fps",
                             [](PyMultiAgentEnv& self) { return self.env().render_spec().fps; })
      .def_property_readonly(
          "can_render", [](PyMultiAgentEnv& self) { return self.env().render_spec().width > 0; })
      .def_property_readonly("id", [](const PyMultiAgentEnv& self) { return self.id_; });
}

}  // namespace rlrun::python
