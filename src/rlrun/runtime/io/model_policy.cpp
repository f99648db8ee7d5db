#include "rlrun/runtime/io/model_policy.hpp"

#include <algorithm>

#include "rlrun/core/errors.hpp"
#include "rlrun/runtime/experiment/base_layer.hpp"

namespace rlrun {

// The layer under the model's stack: reset() and step() write the observation predict() was
// given and step() keeps the action that came down the stack; the env it wraps stands for the
// env's spaces only (env/spaces_only_env.hpp) and is never stepped.
class FeedLayer : public Wrapper {
 public:
  explicit FeedLayer(EnvPtr env)
      : Wrapper(std::move(env)),
        obs_(static_cast<size_t>(inner_->observation_space().flat_dim()), 0.0f),
        action_(static_cast<size_t>(inner_->action_space().flat_dim()), 0.0f) {}

  void reset(std::optional<uint64_t> /*seed*/, std::span<float> obs) override {
    std::copy(obs_.begin(), obs_.end(), obs.begin());
  }
  StepResult step(std::span<const float> action, std::span<float> obs) override {
    std::copy(action.begin(), action.end(), action_.begin());
    std::copy(obs_.begin(), obs_.end(), obs.begin());
    return {};
  }

  std::span<float> next_obs() { return obs_; }
  std::span<const float> last_action() const { return action_; }

 private:
  std::vector<float> obs_;
  std::vector<float> action_;
};

ModelPolicy::ModelPolicy(const std::string& path, const Registry& registry,
                         const std::vector<std::string>& overrides, const ModelTrust& trust)
    : loaded_(load_model(path, registry, overrides, trust, ModelEnv::kSpacesOnly)) {
  Env& stack = *loaded_.env;
  if (stack.num_agents() > 1) {
    // Multi-agent stacks hold only TimeLimit and Monitor (make_env): the policy acts on the
    // env's own observations, one column per agent.
    if (!(policy_observation_space() == observation_space()) ||
        !(policy_action_space() == action_space()))
      throw RuntimeFailure(path +
                           ": a multi-agent model whose wrappers change its spaces "
                           "cannot predict from the env's observations");
    return;
  }
  feed_ = &insert_base_layer<FeedLayer>(
      stack, [](EnvPtr env) { return std::make_unique<FeedLayer>(std::move(env)); });
  scratch_obs_.resize(static_cast<size_t>(policy_observation_space().flat_dim()));
}

ModelPolicy::~ModelPolicy() = default;

const Space& ModelPolicy::observation_space() const {
  return loaded_.env->unwrapped().observation_space();
}
const Space& ModelPolicy::action_space() const { return loaded_.env->unwrapped().action_space(); }

void ModelPolicy::predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
                          Eigen::MatrixXf& actions, const Eigen::MatrixXf* masks,
                          const RecurrentInput* recurrent) {
  const int obs_dim = observation_space().flat_dim();
  const int act_dim = action_space().flat_dim();
  if (obs.rows() != obs_dim)
    throw std::invalid_argument("predict: an observation has " + std::to_string(obs.rows()) +
                                " values, the model's env " + std::to_string(obs_dim));
  Algorithm& algorithm = *loaded_.algorithm;
  if (masks && algorithm.action_mask_size() == 0)
    throw std::invalid_argument("predict: action_masks given, but " + meta().algorithm +
                                " takes no action masks (MaskablePPO does)");
  if (recurrent && algorithm.recurrent_state_size() == 0)
    throw std::invalid_argument("predict: a state given, but " + meta().algorithm +
                                " has no recurrent state (RecurrentPPO does)");
  const auto act = [&](const Eigen::Ref<const Eigen::MatrixXf>& in, Eigen::MatrixXf& out) {
    if (recurrent)
      algorithm.predict_recurrent(in, recurrent->episode_starts, recurrent->states, deterministic,
                                  out);
    else if (masks)
      algorithm.predict_masked(in, *masks, deterministic, out);
    else
      algorithm.predict(in, deterministic, out);
  };
  const Eigen::Index batch = obs.cols();
  if (!feed_) {
    act(obs, actions);
    return;
  }
  Env& stack = *loaded_.env;
  const int policy_obs_dim = policy_observation_space().flat_dim();
  policy_obs_.resize(policy_obs_dim, batch);
  // Starts an episode of the stack at observation j; `out` receives what the policy sees.
  const auto reset_at = [&](Eigen::Index j, std::span<float> out) {
    std::span<float> next = feed_->next_obs();
    std::copy(obs.col(j).data(), obs.col(j).data() + obs_dim, next.begin());
    stack.reset(std::nullopt, out);
  };
  for (Eigen::Index j = 0; j < batch; ++j)
    reset_at(j, {policy_obs_.col(j).data(), static_cast<size_t>(policy_obs_dim)});
  act(policy_obs_, policy_actions_);
  actions.resize(act_dim, batch);
  for (Eigen::Index j = 0; j < batch; ++j) {
    // Each action follows a reset with its own observation, as in a one-by-one predict, so the
    // stack's TimeLimit counts one step whatever the batch size.
    reset_at(j, scratch_obs_);
    stack.step({policy_actions_.col(j).data(), static_cast<size_t>(policy_actions_.rows())},
               scratch_obs_);
    const std::span<const float> action = feed_->last_action();
    std::copy(action.begin(), action.end(), actions.col(j).data());
  }
}

}  // namespace rlrun
