// rlrun._core.TrainingSession: a training that goes on over several learn() calls
// (runtime/run/trainer.hpp), for SB3's model.learn() (python/rlrun/_algorithms.py), with the
// caller's Python callback told of every env step (SB3's BaseCallback, python/rlrun/callbacks.py),
// and the connector that lets such a training step a live env object of this interpreter
// (envs/python/python_live_env.hpp; the thread serving it: python/rlrun/_live_env.py).
//
// The GIL is released while envs are built and while training runs: a live env's serving
// thread needs it, and the callback takes it for each call.
#include <pybind11/stl.h>

#include <exception>

#include "bindings.hpp"
#include "rlrun/core/available_cpus.hpp"
#include "rlrun/core/errors.hpp"
#include "rlrun/core/execution_context.hpp"
#include "rlrun/core/interrupt.hpp"
#include "rlrun/core/thread_pool.hpp"
#include "rlrun/envs/python/python_live_env.hpp"
#include "rlrun/runtime/run/trainer.hpp"
#include "rlrun/runtime/workflows/zoo/zoo_import.hpp"
#include "scoped_training_signals.hpp"

namespace rlrun {
const char* python_worker_script();  // worker.py's text (envs/python/python_env.cpp)
}

namespace rlrun::python {

namespace session_detail {

// Calls `dispatch(event, num_timesteps, new_obs, rewards, dones, infos, actions)` (python/rlrun/
// callbacks.py's _Dispatcher) after every env step ("step"; its result false stops training, as
// SB3's callback.on_step()) and where SB3 calls on_rollout_end ("rollout_end": after a rollout,
// before the update that learns from it), preceded by "rollout_start" before a rollout's first
// step. An exception in the callback stops training; learn() raises it.
class PythonCallback : public Callback {
 public:
  PythonCallback(py::object dispatch, TrainingContext& context)
      : dispatch_(std::move(dispatch)), context_(context) {}
  ~PythonCallback() override {
    py::gil_scoped_acquire gil;
    dispatch_ = py::object();
  }

  bool on_step(int64_t num_timesteps) override {
    py::gil_scoped_acquire gil;
    if (error_) return false;
    try {
      if (!in_rollout_) {
        in_rollout_ = true;
        dispatch_("rollout_start", num_timesteps, py::none(), py::none(), py::none(), py::none(),
                  py::none());
      }
      if (py::bool_(
              dispatch_("step", num_timesteps, new_obs(), rewards(), dones(), infos(), actions())))
        return true;
      stop_reason_ = "the Python callback's on_step returned False";
    } catch (...) {
      error_ = std::current_exception();
      stop_reason_ = "the Python callback raised an exception";
    }
    return false;
  }

  void on_rollout_end(int64_t num_timesteps) override {
    py::gil_scoped_acquire gil;
    in_rollout_ = false;
    if (error_) return;
    try {
      dispatch_("rollout_end", num_timesteps, py::none(), py::none(), py::none(), py::none(),
                py::none());
    } catch (...) {
      error_ = std::current_exception();
      stop_reason_ = "the Python callback raised an exception";
    }
  }

  // Raises what the callback raised, if it did (with the GIL held).
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  py::array_t<float> new_obs() const {
    const Eigen::MatrixXf& obs = context_.env.obs();  // obs_dim x n_envs
    py::array_t<float> out({obs.cols(), obs.rows()});
    auto view = out.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < obs.cols(); ++i)
      for (Eigen::Index j = 0; j < obs.rows(); ++j) view(i, j) = obs(j, i);
    return out;
  }
  // The actions the envs were stepped with, one row per env (the Python side shapes them by
  // the action space).
  py::array_t<float> actions() const {
    const Eigen::MatrixXf& actions = context_.env.last_actions();  // act_dim x n_envs
    py::array_t<float> out({actions.cols(), actions.rows()});
    auto view = out.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < actions.cols(); ++i)
      for (Eigen::Index j = 0; j < actions.rows(); ++j) view(i, j) = actions(j, i);
    return out;
  }
  py::array_t<float> rewards() const {  // SB3's VecEnv rewards are float32
    const Eigen::VectorXd& r = context_.env.rewards();
    py::array_t<float> out(r.size());
    auto view = out.mutable_unchecked<1>();
    for (Eigen::Index i = 0; i < r.size(); ++i) view(i) = static_cast<float>(r(i));
    return out;
  }
  py::array_t<bool> dones() const {
    const int n = context_.env.num_envs();
    py::array_t<bool> out(n);
    auto view = out.mutable_unchecked<1>();
    for (int i = 0; i < n; ++i) view(i) = context_.env.done(i);
    return out;
  }
  // Each env's info (numeric keys), with SB3 DummyVecEnv's TimeLimit.truncated (every step) and
  // terminal_observation where an episode ended (flat; the Python side shapes it).
  py::list infos() const {
    const VecEnv& env = context_.env;
    py::list out;
    for (int i = 0; i < env.num_envs(); ++i) {
      py::dict info = info_dict(env.info(i));
      if (env.done(i)) {
        const Eigen::VectorXf last = env.final_obs().col(i);
        py::array_t<float> terminal(last.size());
        std::copy(last.data(), last.data() + last.size(), terminal.mutable_data());
        info["terminal_observation"] = terminal;
      }
      info["TimeLimit.truncated"] = env.truncated(i) && !env.terminated(i);
      out.append(info);
    }
    return out;
  }

  py::object dispatch_;
  TrainingContext& context_;
  bool in_rollout_ = false;
  std::exception_ptr error_;
};

// The session and the threads it was built with (as `rlrun --threads auto`), which must
// outlive it.
class PySession {
 public:
  // The experiment is an rl-zoo entry (SB3's constructor keywords, as the Python side writes
  // them into `zoo_path`) translated as `rlrun train --zoo` does, then `overrides`.
  PySession(const std::string& zoo_path, const std::string& env_id, const std::string& algorithm,
            const std::vector<std::string>& overrides)
      : pool_(std::make_unique<ThreadPool>(available_cpus())) {
    py::gil_scoped_release release;
    Experiment experiment =
        zoo::load_zoo_experiment(zoo_path, env_id, algorithm, overrides, module_registry());
    session_ = std::make_unique<TrainingSession>(std::move(experiment), module_registry(),
                                                 ExecutionContext{pool_.get()});
  }
  // The experiment as YAML text (a model file's config: SB3's load() then learn()).
  struct FromText {};
  PySession(FromText, const std::string& text, const std::string& origin,
            const std::vector<std::string>& overrides)
      : pool_(std::make_unique<ThreadPool>(available_cpus())) {
    py::gil_scoped_release release;
    Experiment experiment =
        load_experiment_text(text, origin, "model", overrides, module_registry());
    session_ = std::make_unique<TrainingSession>(std::move(experiment), module_registry(),
                                                 ExecutionContext{pool_.get()});
  }
  ~PySession() {
    py::gil_scoped_release release;  // closing a live env's socket lets its thread return
    session_.reset();
  }

  py::dict learn(int64_t total_timesteps, py::object dispatch, std::optional<int> log_interval) {
    std::vector<std::unique_ptr<Callback>> extra;
    PythonCallback* callback = nullptr;
    if (!dispatch.is_none()) {
      auto made = std::make_unique<PythonCallback>(std::move(dispatch), session_->context());
      callback = made.get();
      extra.push_back(std::move(made));
    }
    TrainOutcome outcome;
    {
      ScopedTrainingSignals signals;
      py::gil_scoped_release release;
      outcome = session_->learn(total_timesteps, extra, log_interval);
    }
    if (callback) callback->rethrow();
    py::dict d;
    d["run_dir"] = outcome.run_dir;
    d["model_path"] = outcome.model_path;
    d["timesteps"] = outcome.timesteps;
    d["interrupted"] = outcome.interrupted;
    d["checkpoint_path"] = outcome.checkpoint_path;
    d["stop_reason"] = outcome.stop_reason;
    {
      py::gil_scoped_release release;
      extra.clear();
    }
    return d;
  }

  int64_t num_timesteps() const { return session_->num_timesteps(); }
  std::string config_yaml() const { return dump_yaml(session_->experiment().resolved); }

 private:
  std::unique_ptr<ThreadPool> pool_;
  std::unique_ptr<TrainingSession> session_;
};

// The live-env connector: python/rlrun/_live_env.py's connect(number) -> fd, its errors as
// RuntimeFailure (with the message Python gave).
int connect_live_env(int64_t number) {
  py::gil_scoped_acquire gil;
  try {
    return py::module_::import("rlrun._live_env").attr("connect")(number).cast<int>();
  } catch (const py::error_already_set& e) {
    throw RuntimeFailure(std::string("python-object:") + std::to_string(number) + ": " + e.what());
  }
}

}  // namespace session_detail

void bind_training_session(py::module_& m) {
  using session_detail::PySession;
  py::class_<PySession>(m, "TrainingSession")
      .def(py::init<const std::string&, const std::string&, const std::string&,
                    const std::vector<std::string>&>(),
           py::arg("zoo_path"), py::arg("env_id"), py::arg("algorithm"), py::arg("overrides"))
      .def_static(
          "from_experiment",
          [](const std::string& text, const std::string& origin,
             const std::vector<std::string>& overrides) {
            return std::make_unique<PySession>(PySession::FromText{}, text, origin, overrides);
          },
          py::arg("text"), py::arg("origin"), py::arg("overrides"))
      .def("learn", &PySession::learn, py::arg("total_timesteps"), py::arg("dispatch"),
           py::arg("log_interval") = py::none())
      .def_property_readonly("num_timesteps", &PySession::num_timesteps)
      .def_property_readonly("config_yaml", &PySession::config_yaml);
  m.def(
      "worker_script", [] { return std::string(python_worker_script()); },
      "worker.py's text: the loop that serves a Python env (python/rlrun/_live_env.py)");
  set_live_env_connector(session_detail::connect_live_env);
}

}  // namespace rlrun::python
