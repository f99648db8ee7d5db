#pragma once
// A Gymnasium env written in Python, as an rlrun Env: `env: {id: "python:my_pkg.my_mod:MyEnv",
// kwargs: {...}}` builds MyEnv(**kwargs), `gymnasium:CartPole-v1` gymnasium.make(...), in a
// worker process of its own (python_worker.hpp, worker.py). rlrun's TimeLimit, Monitor and
// wrappers stack on it like on any env; each copy of a VecEnv has its own worker, and the VecEnv
// sends every copy its action before it waits for any reply (env/split_step.hpp), so the
// workers run in parallel.
//
// The worker is started in the constructor and answers the handshake while the caller goes on
// (make_vec_env starts all copies before it needs their spaces); one that has not answered
// within env.startup_timeout seconds (an __init__ that hangs) is stopped with an error naming
// the env and that setting. Everything the env does wrong
// (an exception, a crash, an observation that does not fit its space, NaN) ends the run with a
// RuntimeFailure that names the env, the worker's pid, the step and episode, and carries the
// Python traceback. A Python env cannot snapshot itself, so checkpoints hold the model only.
//
// `pettingzoo:module:function` builds a PettingZoo env (pettingzoo_agents.py): its agents are
// this env's agents (num_agents(), step_agents(), named as PettingZoo names them), sharing one
// policy.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rlrun/env.hpp"
#include "rlrun/env/agent_names.hpp"
#include "rlrun/env/split_step.hpp"
#include "rlrun/envs/python/python_worker.hpp"

namespace rlrun {

// How a pettingzoo: env's agents are seen (pettingzoo_agents.py): a turn-based game's opponent
// and the learner's seat (env.opponent, env.learner_side), and the observing agent's indicator
// in every observation (env.agent_indicator: none, agent, type).
struct PettingZooSettings {
  std::string opponent = "self";
  std::string learner_side = "alternate";
  std::string agent_indicator = "none";
};

class PythonEnv : public Env, public SplitStep, public AgentNames {
 public:
  // `target` is the env id ("python:module:Attr" or "gymnasium:ID"), `kwargs_json` a JSON
  // object, `python` the interpreter (a name on PATH or a path), `startup_timeout` the seconds
  // its worker may take to import the module and build the env (env.startup_timeout).
  PythonEnv(std::string target, std::string kwargs_json, const std::string& python,
            double startup_timeout = kDefaultStartupTimeout,
            const PettingZooSettings& pettingzoo = PettingZooSettings{});
  static constexpr double kDefaultStartupTimeout = 60.0;
  // The same over a worker already started (an in-process one: python_live_env.hpp).
  PythonEnv(std::string target, std::string kwargs_json, std::unique_ptr<PythonWorker> worker,
            double startup_timeout = kDefaultStartupTimeout,
            const PettingZooSettings& pettingzoo = PettingZooSettings{});
  ~PythonEnv() override;

  const Space& observation_space() const override;
  const Space& action_space() const override;
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override;
  StepResult step(std::span<const float> action, std::span<float> obs) override;
  // step() in two halves (env/split_step.hpp): send the action; read the reply.
  bool steps_asynchronously() const override { return true; }
  void start_step(std::span<const float> action) override;
  StepResult finish_step(std::span<float> obs) override;
  const Info& info() const override { return info_; }
  std::string id() const override { return target_; }

  // A PettingZoo env's agents (1 for a Gymnasium env), all stepped by one request.
  int num_agents() const override;
  std::string agent_name(int agent) const override;
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override;
  bool splits_agents() const override { return true; }
  void start_step_agents(std::span<const float> actions) override;
  void finish_step_agents(std::span<float> obs, std::span<StepResult> results) override;

  RenderSpec render_spec() const override;
  bool render(Frame& frame) const override;

  // The time limit the env's own registration holds (gymnasium.make's spec), if any.
  std::optional<int> registered_time_limit() const;

 private:
  // What the worker said of its env (python_env.cpp).
  struct Handshake;

  // Waits for the worker's handshake once (every public method calls it first).
  void ready() const;
  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void worker_gone(const char* during) const;
  // How to wait for the worker (core/worker_wait.hpp) `what` ("in step()").
  WorkerWait waiting(const char* what) const;
  void send_request() const;
  // Reads a reply; on 'E' throws with the worker's text. Returns the body.
  const std::vector<std::byte>& receive(const char* during) const;
  // Reads every agent's reward, flags and observation (agent-major) and the info.
  void read_step_reply(std::span<float> obs, std::span<StepResult> results, const char* during);
  // Fetches a frame into frame_rgb_ (height x width x 3); false when the env gives none.
  bool fetch_frame() const;

  std::string target_;
  double startup_timeout_;
  mutable std::unique_ptr<PythonWorker> worker_;
  mutable std::unique_ptr<Handshake> handshake_;
  mutable std::vector<std::byte> request_;
  mutable std::vector<std::byte> reply_;
  mutable std::vector<uint8_t> frame_rgb_;
  mutable int frame_width_ = 0, frame_height_ = 0;
  mutable bool render_probe_failed_ = false;  // render_spec()'s render() failed
  Info info_;
  std::vector<int> info_index_;  // the worker's key index -> info_'s
  int is_success_ = -1;
  int64_t episode_ = 0;  // for messages: episode and step where something went wrong
  int64_t step_ = 0;
  bool was_reset_ = false;
  std::vector<StepResult> reset_results_;  // the flags a reset reply carries (all false)
};

}  // namespace rlrun
