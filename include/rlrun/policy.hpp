#pragma once
// rlrun::Policy — a trained rlrun model in your own C++ program (the library rlrun::policy:
// `find_package(rlrun)`, `target_link_libraries(app PRIVATE rlrun::policy)`; docs/deploy.md).
//
//     rlrun::Policy policy = rlrun::Policy::load("model.zip");
//     std::vector<float> action(policy.action_size());
//     policy.act(observation, action);               // one observation
//     policy.act_batch(observations, actions, n);    // n observations, row after row
//
// A recurrent policy (RecurrentPPO) has a state of state_size() floats that each step reads and
// replaces: zeros at the start of every episode, then act(observation, state, action).
//
// It acts as `rlrun eval` does, deterministically: the env's own observation in (a Dict's keys
// concatenated in key order), the env's own action out (discrete actions as their integer
// values), with the model's observation normalisation, its network, the distribution's mode and
// the scaling to the action bounds — the same graph `rlrun export` writes as ONNX or C.
// Loading reads the file as untrusted data (docs/security.md); act() is const and thread-safe
// (several threads may act with one Policy at once) and does not allocate after its first call
// on a thread.
//
// Not part of the plugin interface (include/rlrun/version.hpp): plugins never see it.
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

namespace rlrun {

class Policy {
 public:
  // Reads a model file (model.zip, best_model.zip, a checkpoint). Throws std::runtime_error
  // naming the file and the reason: missing, not a model, another format version, a policy
  // that cannot be deployed (a FrameStack wrapper, a multi-agent env).
  static Policy load(const std::string& model_path);

  Policy(Policy&&) noexcept;
  Policy& operator=(Policy&&) noexcept;
  ~Policy();

  // Floats per observation and per action.
  std::size_t observation_size() const;
  std::size_t action_size() const;
  const std::string& env_id() const;
  const std::string& algorithm() const;

  // Floats of a recurrent policy's state (its LSTM's h of every layer, then its c, as
  // sb3-contrib's (h, c) pair); 0 for a feed-forward policy.
  std::size_t state_size() const;

  // One observation -> one action. Throws std::invalid_argument when a span has the wrong
  // size (nothing is read or written then), or for a recurrent policy (it needs its state).
  void act(std::span<const float> observation, std::span<float> action) const;
  // `count` observations (count * observation_size() floats, one after another) -> count
  // actions. Throws std::invalid_argument for spans of other sizes.
  void act_batch(std::span<const float> observations, std::span<float> actions,
                 std::size_t count) const;
  // A recurrent policy's step: `state` (state_size() floats per observation) is read and
  // replaced by the next one. Zero a state where its episode starts (sb3-contrib's
  // episode_start). Throws std::invalid_argument for spans of other sizes.
  void act(std::span<const float> observation, std::span<float> state,
           std::span<float> action) const;
  void act_batch(std::span<const float> observations, std::span<float> states,
                 std::span<float> actions, std::size_t count) const;

 private:
  struct Impl;
  explicit Policy(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace rlrun
