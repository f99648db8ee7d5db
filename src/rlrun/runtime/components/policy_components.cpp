// The built-in wrappers and algorithms: everything that turns a model file into a policy,
// and nothing that simulates (runtime/components/builtins.cpp adds the envs). rlrun::Policy::load
// (runtime/io/policy_library.cpp) reads models with these alone, so the deploy library links no
// env and no simulator.
#include "rlrun/runtime/components/policy_components.hpp"

#include "rlrun/algos/a2c/a2c.hpp"
#include "rlrun/algos/ars/ars.hpp"
#include "rlrun/algos/crossq/crossq.hpp"
#include "rlrun/algos/ddpg/ddpg.hpp"
#include "rlrun/algos/dqn/dqn.hpp"
#include "rlrun/algos/ppo/ppo.hpp"
#include "rlrun/algos/ppo_mask/ppo_mask.hpp"
#include "rlrun/algos/ppo_recurrent/ppo_recurrent.hpp"
#include "rlrun/algos/qrdqn/qrdqn.hpp"
#include "rlrun/algos/sac/sac.hpp"
#include "rlrun/algos/td3/td3.hpp"
#include "rlrun/algos/tqc/tqc.hpp"
#include "rlrun/algos/trpo/trpo.hpp"
#include "rlrun/wrappers/action_repeat.hpp"
#include "rlrun/wrappers/box_as_discrete.hpp"
#include "rlrun/wrappers/clip_action.hpp"
#include "rlrun/wrappers/discrete_as_box.hpp"
#include "rlrun/wrappers/frame_stack.hpp"
#include "rlrun/wrappers/noop_reset.hpp"
#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/normalize_reward.hpp"
#include "rlrun/wrappers/one_hot_observation.hpp"
#include "rlrun/wrappers/rescale_action.hpp"
#include "rlrun/wrappers/reward_shaping.hpp"
#include "rlrun/wrappers/time_feature.hpp"
#include "rlrun/wrappers/transform_reward.hpp"

namespace rlrun {

void add_builtin_wrappers(Registry& r) {
  r.add(make_wrapper_entry<DiscreteAsBox>(
      "DiscreteAsBox",
      "Box(-1, 1, (n,)) scores -> argmax action of a Discrete(n) env (SAC/TD3 on CartPole)"));
  r.add(make_wrapper_entry<BoxAsDiscrete>(
      "BoxAsDiscrete", "Discrete(bins^dims) grid over a Box action space (DQN on Pendulum)"));
  // Workflow wrappers (issue 4): SB3 VecNormalize halves (statistics stored in the model file),
  // Gymnasium's action/observation/reward wrappers, reward shaping from YAML.
  r.add(make_wrapper_entry<NormalizeObservation>(
      "NormalizeObservation",
      "running mean/std observation normalisation (SB3 VecNormalize norm_obs)"));
  r.add(make_wrapper_entry<NormalizeReward>(
      "NormalizeReward",
      "reward / running std of the discounted return (SB3 VecNormalize norm_reward)"));
  r.add(make_wrapper_entry<ClipAction>(
      "ClipAction", "clip actions to the env's Box bounds; agent sees Box(-inf, inf) (Gymnasium)"));
  r.add(make_wrapper_entry<RescaleAction>(
      "RescaleAction",
      "agent acts in Box(min_action, max_action), mapped onto the env's bounds (Gymnasium)"));
  r.add(make_wrapper_entry<FrameStack>("FrameStack",
                                       "the last n_stack observations stacked, oldest first "
                                       "(Gymnasium; layout sb3: SB3 VecFrameStack)"));
  r.add(make_wrapper_entry<FrameStackObservation>(
      "FrameStackObservation",
      "Gymnasium 1.0's name for FrameStack: stack_size, padding_type (reset | zero)"));
  r.add(make_wrapper_entry<TransformReward>(
      "TransformReward", "reward' = clip(scale * reward + offset, clip_min, clip_max), or sign"));
  // SB3's Atari pieces that make sense without Atari, and rl-zoo's FrameSkip.
  r.add(make_wrapper_entry<FrameSkip>(
      "FrameSkip", "repeat each action `skip` times, rewards summed (rl-zoo FrameSkip)"));
  r.add(make_wrapper_entry<MaxAndSkip>(
      "MaxAndSkip", "repeat each action, rewards summed, max of the last two frames (SB3)"));
  r.add(make_wrapper_entry<NoopReset>(
      "NoopReset", "1 to noop_max steps of action 0 after each reset (SB3 NoopResetEnv)"));
  r.add(make_wrapper_entry<RewardShaping>(
      "RewardShaping",
      "adds YAML-configured terms to the reward (obs_above_for, obs_abs, action_sq, ...)"));
  r.add(make_wrapper_entry<TimeFeature>("TimeFeature",
                                        "appends the remaining episode time 1 - t/max_steps to the "
                                        "observation (sb3_contrib TimeFeatureWrapper)"));
  r.add(make_wrapper_entry<OneHotObservation>(
      "OneHotObservation", "Discrete/MultiDiscrete/MultiBinary observations as SB3's one-hot Box"));
}

void add_builtin_algorithms(Registry& r) {
  r.add(make_algorithm_entry<PPO>("PPO",
                                  "Proximal Policy Optimization (SB3 semantics); "
                                  "Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<A2C>("A2C",
                                  "Advantage Actor-Critic (SB3 semantics, RMSprop); "
                                  "Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<SAC>(
      "SAC", "Soft Actor-Critic (SB3 semantics, learned entropy coefficient); Box actions"));
  r.add(make_algorithm_entry<DQN>(
      "DQN", "Deep Q-Network (SB3 semantics, epsilon-greedy, Huber loss); Discrete actions"));
  r.add(make_algorithm_entry<QRDQN>(
      "QRDQN",
      "Quantile Regression DQN (sb3-contrib semantics: DQN with a distributional, "
      "quantile-Huber critic); Discrete actions"));
  r.add(make_algorithm_entry<TD3>(
      "TD3", "Twin Delayed DDPG (SB3 semantics, clipped double-Q, delayed actor); Box actions"));
  r.add(make_algorithm_entry<DDPG>(
      "DDPG",
      "Deep Deterministic Policy Gradient (SB3 semantics: TD3 without its tricks); Box actions"));
  r.add(make_algorithm_entry<TQC>("TQC",
                                  "Truncated Quantile Critics (sb3-contrib semantics: SAC with "
                                  "truncated distributional critics); Box actions"));
  r.add(make_algorithm_entry<CrossQ>(
      "CrossQ",
      "CrossQ (sb3-contrib semantics: SAC with batch-renormalised networks, no target "
      "networks, a joint critic pass over s and s'); Box actions"));
  r.add(make_algorithm_entry<MaskablePPO>(
      "MaskablePPO",
      "PPO with invalid-action masks (sb3-contrib semantics, env reports "
      "info action_mask.*); Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<RecurrentPPO>(
      "RecurrentPPO",
      "PPO with an LSTM policy (sb3-contrib semantics: recurrent states reset at episode "
      "starts, minibatches of sequences); Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<TRPO>(
      "TRPO",
      "Trust Region Policy Optimization (sb3-contrib semantics: natural gradient by conjugate "
      "gradient, KL line search); Box/Discrete/MultiDiscrete/MultiBinary actions"));
  r.add(make_algorithm_entry<ARS>(
      "ARS",
      "Augmented Random Search (sb3-contrib semantics: antithetic weight perturbations, the "
      "n_top best directions); Box/Discrete actions"));
}

const Registry& policy_registry() {
  static const Registry registry = [] {
    Registry r;
    add_builtin_wrappers(r);
    add_builtin_algorithms(r);
    return r;
  }();
  return registry;
}

}  // namespace rlrun
