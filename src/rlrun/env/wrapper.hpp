#pragma once
// Base wrapper (gymnasium.Wrapper): owns the inner env and forwards everything; subclasses
// override only what they change.
#include <stdexcept>
#include <string>
#include <utility>

#include "rlrun/env.hpp"

namespace rlrun {

class PolicyGraph;

class Wrapper : public Env {
 public:
  explicit Wrapper(EnvPtr inner) : inner_(std::move(inner)) {}

  const Space& observation_space() const override { return inner_->observation_space(); }
  const Space& action_space() const override { return inner_->action_space(); }
  void reset(std::optional<uint64_t> seed, std::span<float> obs) override {
    inner_->reset(seed, obs);
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    return inner_->step(action, obs);
  }
  const Info& info() const override { return inner_->info(); }
  int num_agents() const override { return inner_->num_agents(); }
  // A wrapper that transforms steps handles several agents only if it says how (TimeLimit,
  // Monitor do); any other refuses a multi-agent env rather than step it wrongly.
  void step_agents(std::span<const float> actions, std::span<float> obs,
                   std::span<StepResult> results) override {
    if (inner_->num_agents() == 1) {
      results[0] = step(actions, obs);
      return;
    }
    throw std::invalid_argument(id() + ": this wrapper does not support multi-agent envs yet");
  }
  std::string id() const override { return inner_->id(); }
  Env& unwrapped() override { return inner_->unwrapped(); }
  RenderSpec render_spec() const override { return inner_->render_spec(); }
  bool render(Frame& frame) const override { return inner_->render(frame); }
  bool render_observation(std::span<const float> obs, Frame& frame) const override {
    return inner_->render_observation(obs, frame);
  }

  // A wrapper's state is its own (write_own_state) plus its inner env's under "inner/".
  bool can_save_state() const override { return inner_->can_save_state(); }
  void write_state(StateWriter& out) const override {
    write_own_state(out);
    StateWriter inner = out.sub("inner");
    inner_->write_state(inner);
  }
  void read_state(const StateReader& in) override {
    read_own_state(in);
    inner_->read_state(in.sub("inner"));
  }

  Env& inner() { return *inner_; }
  const Env& inner() const { return *inner_; }

  // Deploying a policy (rlrun export; nn/policy_graph.hpp): what this wrapper does to an
  // observation on its way up (inner -> agent) and to an action on its way down (agent ->
  // inner), as graph nodes; each returns the name of its result. Wrappers that touch neither
  // (rewards, episode ends, bookkeeping) say so with exports_unchanged(); the others override
  // the two, and a wrapper that does neither refuses with ExportError (it keeps state between
  // steps, as FrameStack, or has not said how).
  virtual bool exports_unchanged() const { return false; }
  // A wrapper whose observation no graph can compute (it renders the env, or keeps frames
  // between steps: AddRenderObservation, FrameStack, MaxAndSkip) but that passes actions on as
  // they are says so here: the exported policy then reads this wrapper's observations, as an
  // SB3 policy exported on its own reads preprocessed ones (runtime/io/model_graph.hpp).
  virtual bool exports_action_unchanged() const { return exports_unchanged(); }
  virtual std::string export_observation(PolicyGraph& graph, const std::string& obs) const;
  virtual std::string export_action(PolicyGraph& graph, const std::string& action) const;
  // True for a wrapper that the env's registration applies as part of the env id
  // (MaskVelocity for the zoo's *NoVel ids): its observations are the env's own, so layers slipped
  // in "right above the env" (runtime/experiment/base_layer.hpp) go above it.
  virtual bool belongs_to_env() const { return false; }
  // Puts `inner` in place of the inner env and returns the old one. For runtime code that
  // slips a layer under a built stack (runtime/run/trajectory_tap.hpp records what the env itself
  // sees; runtime/io/model_policy.hpp feeds the stack observations from elsewhere): the new
  // inner env must have the old one's spaces, since wrappers size their buffers from them.
  EnvPtr exchange_inner(EnvPtr inner) {
    std::swap(inner_, inner);
    return inner;
  }

 protected:
  // Wrappers that keep state between steps (counters, running statistics) save it here.
  virtual void write_own_state(StateWriter& /*out*/) const {}
  virtual void read_own_state(const StateReader& /*in*/) {}

  EnvPtr inner_;
};

// The wrapper's class name for messages ("rlrun::FrameStack" -> "FrameStack").
std::string wrapper_class_name(const Wrapper& w);

}  // namespace rlrun
