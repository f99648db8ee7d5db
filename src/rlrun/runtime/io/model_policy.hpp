#pragma once
// A trained model as a function from the env's own observations to the env's own actions:
// what `rlrun eval` does between reading an observation and stepping the env, for the Python
// package's `model.predict` (python/, docs/python.md).
//
// rlrun's policies act on the observations their wrapper stack produces (NormalizeObservation
// with the model's frozen statistics, OneHotObservation, ...) and their actions pass back
// down that stack (RescaleAction, ClipAction, DiscreteAsBox, ...) before the env sees them.
// Rather than re-implement those steps, ModelPolicy builds the model's wrapper stack as eval
// does (load_model: the two-phase reader and its budget, docs/security.md), over an env that
// stands for the spaces the file records (ModelEnv::kSpacesOnly: no Python worker, no
// simulator), and slips a feed under it (runtime/experiment/base_layer.hpp): predict() hands each observation to the stack as the
// env's reset observation, runs the algorithm's predict() on what comes out on top, and steps
// the stack with the result so that the action wrappers turn it into the env's action, which
// the feed keeps instead of stepping the env.
//
// Each observation is treated as the first of an episode: stateless observation wrappers
// (the normalisation, one-hot) are exact; a FrameStack model sees a stack of copies (SB3's
// model.predict also leaves frame stacking to the caller's VecFrameStack).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "rlrun/runtime/io/model_loader.hpp"

namespace rlrun {

class FeedLayer;

class ModelPolicy {
 public:
  // Reads an untrusted model file; throws RuntimeFailure naming the file (as `rlrun eval`),
  // ConfigError for a bad `overrides` entry. `trust` as load_model's (`trust=True`).
  ModelPolicy(const std::string& path, const Registry& registry,
              const std::vector<std::string>& overrides = {}, const ModelTrust& trust = {});
  ~ModelPolicy();

  const ModelMeta& meta() const { return loaded_.file.meta; }
  const Experiment& experiment() const { return loaded_.experiment; }
  // The algorithm's tensors as the file holds them (rlrun's names; docs/model_format.md).
  const TensorMap& tensors() const { return loaded_.file.tensors; }
  // The env's own spaces: what predict() takes and returns.
  const Space& observation_space() const;
  const Space& action_space() const;
  // The spaces the algorithm sees on top of the wrapper stack.
  const Space& policy_observation_space() const { return loaded_.env->observation_space(); }
  const Space& policy_action_space() const { return loaded_.env->action_space(); }
  int num_agents() const { return loaded_.env->num_agents(); }

  // Entries of one action mask the model takes (MaskablePPO, env/action_mask.hpp), 0 for none.
  // Masks are over policy_action_space(): the env's own unless an action wrapper changes it.
  int action_mask_size() const { return loaded_.algorithm->action_mask_size(); }

  // obs: observation_space().flat_dim() x batch (a column per observation); actions: resized
  // to action_space().flat_dim() x batch. `masks` (action_mask_size() x batch of 0/1, or null
  // for none: sb3-contrib's predict(action_masks=None)) keep the policy to legal actions;
  // masks for a model without masking throw std::invalid_argument.
  // A recurrent model (RecurrentPPO): `recurrent` carries each observation's state
  // (recurrent_state_size() x batch, in and out) and its episode-start flags, as sb3-contrib's
  // predict(obs, state, episode_start); null starts every observation from zeros.
  struct RecurrentInput {
    Eigen::MatrixXf& states;
    const Eigen::RowVectorXf& episode_starts;
  };
  int recurrent_state_size() const { return loaded_.algorithm->recurrent_state_size(); }
  int recurrent_layers() const { return loaded_.algorithm->recurrent_layers(); }
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions, const Eigen::MatrixXf* masks = nullptr,
               const RecurrentInput* recurrent = nullptr);

 private:
  LoadedModel loaded_;
  FeedLayer* feed_ = nullptr;  // owned by loaded_.env's stack
  Eigen::MatrixXf policy_obs_, policy_actions_;
  std::vector<float> scratch_obs_;
};

}  // namespace rlrun
