// rlrun._core.Env: one of rlrun's registered envs, stepped from Python (rlrun.make,
// python/rlrun/_env.py wraps it in a gymnasium.Env).
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "bindings.hpp"
#include "rlrun/core/config_node.hpp"
#include "rlrun/env/goal_env.hpp"
#include "rlrun/env/physics_state.hpp"
#include "rlrun/env/race_track_state.hpp"
#include "rlrun/frame.hpp"
#include "rlrun/wrappers/time_limit.hpp"

namespace rlrun::python {

EnvPtr make_registered_env(const std::string& id, const std::string& kwargs_yaml,
                           int max_episode_steps) {
  const Registry& registry = module_registry();
  const std::string origin = "rlrun.make('" + id + "')";
  // An unknown id: ConfigError with the closest registered id, as in an experiment file.
  const EnvEntry& entry = registry.env(id, ConfigNode::from_yaml(YAML::Node(id), origin, "id"));
  const ConfigNode kwargs = ConfigNode::load_string(kwargs_yaml, origin + " kwargs");
  EnvPtr env = entry.build(entry.parse(kwargs), EnvContext{});  // python: envs: $RLRUN_PYTHON
  const int limit = max_episode_steps < 0 ? entry.max_episode_steps : max_episode_steps;
  if (limit > 0) env = std::make_unique<TimeLimit>(std::move(env), limit);
  return env;
}

py::object render_rgb(Env& env, std::unique_ptr<Frame>& frame, std::vector<uint8_t>& rgb) {
  const RenderSpec spec = env.render_spec();
  if (spec.width <= 0) return py::none();
  if (!frame) frame = std::make_unique<Frame>(spec.width, spec.height);
  if (!env.render(*frame)) return py::none();
  frame->to_rgb(rgb);
  py::array_t<uint8_t> out({spec.height, spec.width, 3});
  std::copy(rgb.begin(), rgb.end(), out.mutable_data());
  return out;
}

py::dict info_dict(const Info& info) {
  py::dict d;
  for (size_t i = 0; i < info.keys().size(); ++i)
    if (info.has(static_cast<int>(i))) d[py::str(info.keys()[i])] = info.get(static_cast<int>(i));
  return d;
}

namespace {

class PyEnv;
py::array_t<float> compute_goal_reward(PyEnv& self, const py::object& achieved,
                                       const py::object& desired);

class PyEnv {
 public:
  PyEnv(const std::string& id, const std::string& kwargs_yaml, int max_episode_steps)
      : env_(make_registered_env(id, kwargs_yaml, max_episode_steps)),
        id_(id),
        obs_dim_(static_cast<size_t>(env_->observation_space().flat_dim())),
        act_dim_(static_cast<size_t>(env_->action_space().flat_dim())) {
    if (env_->num_agents() > 1)
      throw py::value_error(id + " has " + std::to_string(env_->num_agents()) +
                            " agents: rlrun.make builds single-agent envs (set the env's kwargs "
                            "for one agent, or use make_vec)");
  }

  Env& env() {
    if (!env_) throw py::value_error("rlrun.make('" + id_ + "'): the env is closed");
    return *env_;
  }

  // A new array for one observation: shaped like a Box space, flat otherwise (the Python side
  // shapes those).
  py::array_t<float> new_obs() {
    const Space& space = env().observation_space();
    if (space.is_box())
      return py::array_t<float>(
          std::vector<py::ssize_t>(space.shape().begin(), space.shape().end()));
    return py::array_t<float>(static_cast<py::ssize_t>(obs_dim_));
  }

  // (obs, info)
  py::tuple reset(std::optional<uint64_t> seed) {
    Env& e = env();
    py::array_t<float> obs = new_obs();
    float* out = obs.mutable_data();
    {
      py::gil_scoped_release release;
      e.reset(seed, {out, obs_dim_});
    }
    return py::make_tuple(obs, info_dict(e.info()));
  }

  // (obs, reward, terminated, truncated, info). `action`: a Python int or float for a one-value
  // action (read without numpy: the common Discrete case), else anything numpy converts to
  // act_dim float32 values.
  py::tuple step(py::handle action) {
    Env& e = env();
    action_.resize(act_dim_);
    if (act_dim_ == 1 && (PyLong_CheckExact(action.ptr()) || PyFloat_CheckExact(action.ptr()))) {
      const double value = PyFloat_AsDouble(action.ptr());
      if (PyErr_Occurred()) throw py::error_already_set();
      action_[0] = static_cast<float>(value);
    } else {
      auto array = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(action);
      if (!array) {
        PyErr_Clear();
        throw py::type_error("step: " + id_ + ": an action is a number or an array, got " +
                             std::string(py::str(py::type::handle_of(action))));
      }
      if (static_cast<size_t>(array.size()) != act_dim_)
        throw py::value_error("step: " + id_ + " takes actions of " + std::to_string(act_dim_) +
                              " values, got " + std::to_string(array.size()));
      std::copy(array.data(), array.data() + act_dim_, action_.begin());
    }
    // Gymnasium's envs assert that a discrete action is in their space (cartpole.py:
    // `assert self.action_space.contains(action)`); a Box action is the env's to clip.
    const Space& space = e.action_space();
    if (!space.is_box() && !space.contains(action_))
      throw py::value_error("step: " + id_ + ": action not in " + space.describe());
    py::array_t<float> obs = new_obs();
    float* out = obs.mutable_data();
    StepResult r;
    {
      py::gil_scoped_release release;
      r = e.step(action_, {out, obs_dim_});
    }
    return py::make_tuple(obs, r.reward, r.terminated, r.truncated, info_dict(e.info()));
  }

  // Gymnasium's render_mode="rgb_array": an (H, W, 3) uint8 array, None if the env cannot draw.
  py::object render() { return render_rgb(env(), frame_, rgb_); }

  void close() {
    frame_.reset();
    env_.reset();
  }

  EnvPtr env_;
  std::string id_;
  size_t obs_dim_, act_dim_;
  std::unique_ptr<Frame> frame_;
  std::vector<uint8_t> rgb_;
  std::vector<float> action_;
};

// GoalEnv.compute_reward(achieved_goal, desired_goal) as Gymnasium-Robotics' envs take it (what
// SB3's HerReplayBuffer calls): goals of shape (goal_dim,) or (n, goal_dim); rewards of shape
// () or (n,).
py::array_t<float> compute_goal_reward(PyEnv& self, const py::object& achieved,
                                       const py::object& desired) {
  const GoalEnv* goals = goal_env_of(self.env());
  if (!goals) throw py::type_error(self.env().id() + " is not a goal-conditioned env");
  using Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
  const Array a = Array::ensure(achieved), d = Array::ensure(desired);
  if (!a || !d) throw py::type_error("compute_reward: goals must be numeric arrays");
  if (a.ndim() != d.ndim() || a.ndim() < 1 || a.ndim() > 2)
    throw py::value_error(
        "compute_reward: goals must both have shape (goal_dim,) or (n, goal_dim)");
  for (py::ssize_t i = 0; i < a.ndim(); ++i)
    if (a.shape(i) != d.shape(i)) throw py::value_error("compute_reward: goal shapes differ");
  const Eigen::Index n = a.ndim() == 2 ? a.shape(0) : 1;
  const Eigen::Index dim = a.shape(a.ndim() - 1);
  // Row-major (n, goal_dim) is column-major (goal_dim, n): one goal per column.
  const Eigen::Map<const Eigen::MatrixXf> am(a.data(), dim, n), dm(d.data(), dim, n);
  Eigen::RowVectorXf rewards(n);
  goals->compute_reward(am, dm, rewards);
  if (a.ndim() == 1) {
    py::array_t<float> out(std::vector<py::ssize_t>{});
    *out.mutable_data() = rewards(0);
    return out;
  }
  py::array_t<float> out(n);
  std::copy(rewards.data(), rewards.data() + n, out.mutable_data());
  return out;
}

// The MuJoCo tasks' simulator state (env/physics_state.hpp), for env.unwrapped.set_state and
// env.unwrapped.data.qpos / qvel (python/rlrun/_env.py).
PhysicsState& physics_of(PyEnv& self) {
  PhysicsState* physics = physics_state_of(self.env());
  if (!physics) throw py::attribute_error(self.env().id() + " has no simulator state (qpos, qvel)");
  return *physics;
}

py::array_t<double> copy_array(std::span<const double> values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::span<const double> vector_of(const py::object& values, const char* name, DoubleArray& keep) {
  keep = DoubleArray::ensure(values);
  if (!keep) throw py::type_error(std::string("set_state: ") + name + " must be a numeric array");
  if (keep.ndim() != 1) throw py::value_error(std::string("set_state: ") + name + " must be 1-D");
  return {keep.data(), static_cast<size_t>(keep.size())};
}

// set_state(qpos, qvel[, qacc_warmstart]): Gymnasium's, plus the solver's warm start for exact
// replays (env/physics_state.hpp).
void set_physics_state(PyEnv& self, const py::object& qpos, const py::object& qvel,
                       const py::object& qacc_warmstart) {
  DoubleArray p, v, w;
  const std::span<const double> positions = vector_of(qpos, "qpos", p);
  const std::span<const double> velocities = vector_of(qvel, "qvel", v);
  PhysicsState& physics = physics_of(self);
  try {
    physics.set_state(positions, velocities);
    if (!qacc_warmstart.is_none())
      physics.set_qacc_warmstart(vector_of(qacc_warmstart, "qacc_warmstart", w));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

py::array_t<float> physics_observation(PyEnv& self) {
  PhysicsState& physics = physics_of(self);
  py::array_t<float> out(self.env().observation_space().flat_dim());
  physics.observe({out.mutable_data(), static_cast<size_t>(out.size())});
  return out;
}

void bind_physics_state(py::class_<PyEnv>& env) {
  env.def_property_readonly("has_physics_state",
                            [](PyEnv& self) { return physics_state_of(self.env()) != nullptr; })
      .def_property_readonly("qpos",
                             [](PyEnv& self) { return copy_array(physics_of(self).qpos()); })
      .def_property_readonly("qvel",
                             [](PyEnv& self) { return copy_array(physics_of(self).qvel()); })
      .def_property_readonly("init_qpos",
                             [](PyEnv& self) { return copy_array(physics_of(self).init_qpos()); })
      .def_property_readonly("init_qvel",
                             [](PyEnv& self) { return copy_array(physics_of(self).init_qvel()); })
      .def_property_readonly("dt", [](PyEnv& self) { return physics_of(self).dt(); })
      .def_property_readonly("frame_skip",
                             [](PyEnv& self) { return physics_of(self).frame_skip(); })
      .def_property_readonly(
          "qacc_warmstart",
          [](PyEnv& self) { return copy_array(physics_of(self).qacc_warmstart()); })
      .def("set_state", &set_physics_state, py::arg("qpos"), py::arg("qvel"),
           py::arg("qacc_warmstart") = py::none())
      .def("observation", &physics_observation);
}

// CarRacing's track and car (env/race_track_state.hpp), for env.unwrapped.track, .set_track,
// .car, .reward, .tile_visited_count and .t (python/rlrun/_env.py).
RaceTrackState& race_track_of(PyEnv& self) {
  RaceTrackState* racing = race_track_state_of(self.env());
  if (!racing) throw py::attribute_error(self.env().id() + " has no race track");
  return *racing;
}

py::list track_list(PyEnv& self) {
  py::list out;
  for (const TrackPoint& p : race_track_of(self).track())
    out.append(py::make_tuple(p.alpha, p.beta, p.x, p.y));
  return out;
}

// Gymnasium's track: a sequence of (alpha, beta, x, y).
void set_next_track(PyEnv& self, const py::object& track) {
  std::vector<TrackPoint> points;
  for (const py::handle item : track) {
    const auto values = py::cast<std::vector<double>>(item);
    if (values.size() != 4)
      throw py::value_error("set_track: each track point is (alpha, beta, x, y)");
    points.push_back({values[0], values[1], values[2], values[3]});
  }
  try {
    race_track_of(self).set_next_track(std::move(points));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("set_track: ") + e.what());
  }
}

py::dict body_dict(const RigidBodyState& body) {
  py::dict d;
  d["position"] = py::make_tuple(body.position[0], body.position[1]);
  d["linearVelocity"] = py::make_tuple(body.linear_velocity[0], body.linear_velocity[1]);
  d["angle"] = body.angle;
  d["angularVelocity"] = body.angular_velocity;
  return d;
}

// The car as Box2D and car_dynamics.py name its parts (the Python side makes attributes of it).
py::dict car_dict(PyEnv& self) {
  CarState car;
  try {
    car = race_track_of(self).car();
  } catch (const std::logic_error& e) {
    throw py::value_error(e.what());
  }
  py::list wheels;
  for (const WheelState& w : car.wheels) {
    py::dict d = body_dict(w.body);
    d["gas"] = w.gas;
    d["brake"] = w.brake;
    d["steer"] = w.steer;
    d["omega"] = w.omega;
    d["phase"] = w.phase;
    d["joint_angle"] = w.joint_angle;
    d["tiles"] = w.tiles;
    wheels.append(d);
  }
  py::dict out;
  out["hull"] = body_dict(car.hull);
  out["wheels"] = wheels;
  return out;
}

void bind_race_track(py::class_<PyEnv>& env) {
  env.def_property_readonly("has_race_track",
                            [](PyEnv& self) { return race_track_state_of(self.env()) != nullptr; })
      .def("race_track", &track_list)
      .def("set_next_track", &set_next_track, py::arg("track"))
      .def("set_next_randomize",
           [](PyEnv& self, bool randomize) { race_track_of(self).set_next_randomize(randomize); })
      .def("race_car", &car_dict)
      .def("race_reward", [](PyEnv& self) { return race_track_of(self).episode_reward(); })
      .def("race_tiles_visited", [](PyEnv& self) { return race_track_of(self).tiles_visited(); })
      .def("race_time", [](PyEnv& self) { return race_track_of(self).time(); });
}

}  // namespace

void bind_env(py::module_& m) {
  py::class_<PyEnv> env(m, "Env");
  bind_physics_state(env);
  bind_race_track(env);
  env.def(py::init<const std::string&, const std::string&, int>(), py::arg("id"),
          py::arg("kwargs_yaml") = "{}", py::arg("max_episode_steps") = -1)
      .def("reset", &PyEnv::reset, py::arg("seed"))
      .def("step", &PyEnv::step, py::arg("action"))
      .def("info", [](PyEnv& self) { return info_dict(self.env().info()); })
      .def_property_readonly("is_goal_env",
                             [](PyEnv& self) { return goal_env_of(self.env()) != nullptr; })
      .def("compute_reward", &compute_goal_reward, py::arg("achieved_goal"),
           py::arg("desired_goal"))
      .def("render", &PyEnv::render)
      .def("close", &PyEnv::close)
      .def_property_readonly("closed", [](const PyEnv& self) { return !self.env_; })
      .def_property_readonly("observation_space",
                             [](PyEnv& self) { return space_dict(self.env().observation_space()); })
      .def_property_readonly("action_space",
                             [](PyEnv& self) { return space_dict(self.env().action_space()); })
      .def_property_readonly("render_fps", [](PyEnv& self) { return self.env().render_spec().fps; })
      .def_property_readonly("can_render",
                             [](PyEnv& self) { return self.env().render_spec().width > 0; })
      .def_property_readonly("id", [](const PyEnv& self) { return self.id_; });
}

}  // namespace rlrun::python
