#pragma once
// Deep Deterministic Policy Gradient (Lillicrap et al. 2015, arXiv:1509.02971) as SB3 2.x has
// it (stable_baselines3/ddpg/ddpg.py): TD3 with "all tricks removed" — policy_delay 1,
// target_noise_clip 0 (so no target policy smoothing), one critic unless policy.n_critics says
// otherwise — and its own defaults, which equal TD3's apart from those. So DDPG owns a TD3 built
// from to_td3(config) and forwards to it; the update code exists once.
#include <string>

#include "rlrun/algos/algorithm.hpp"
#include "rlrun/algos/td3/td3.hpp"

namespace rlrun {

class DDPG : public Algorithm {
 public:
  struct Config {
    Schedule learning_rate = Schedule::constant(1e-3);
    OffPolicyConfig off_policy;      // SB3 DDPG defaults: 1e6, 100, 256, 0.005, 0.99, 1, 1
    ActionNoiseConfig action_noise;  // none by default (rl-zoo: normal, std 0.1)
    Td3PolicyConfig policy{.n_critics = 1};

    template <class V>
    void visit(V& v) {
      v("learning_rate", learning_rate,
        "Adam step size of the actor and the critic: a number or lin_<initial>", non_negative());
      off_policy.visit(v);
      action_noise.visit(v);
      v("policy", policy, "networks: net_arch, activation_fn, n_critics (1)");
    }
  };

  static constexpr SpaceKind kActionSpaces[] = {SpaceKind::kBox};

  // The TD3 settings SB3's DDPG.__init__ passes to TD3.__init__.
  static TD3::Config to_td3(const Config& config);

  static ConfigProblems check(const Config& config, const AlgorithmSetup& setup) {
    return TD3::check(to_td3(config), setup);
  }

  // Throws std::invalid_argument for bad settings or spaces (as TD3).
  DDPG(const Config& config, const AlgorithmSetup& setup);

  std::string id() const override { return "DDPG"; }
  void learn(VecEnv& env, int64_t total_timesteps, TrainingHooks& hooks) override;
  void predict(const Eigen::Ref<const Eigen::MatrixXf>& obs, bool deterministic,
               Eigen::MatrixXf& actions) override;
  void export_policy(PolicyGraph& graph, const std::string& obs, bool with_value) const override {
    td3_.export_policy(graph, obs, with_value);
  }
  void save(TensorMap& tensors) const override { td3_.save(tensors); }
  void load(const TensorMap& tensors) override { td3_.load(tensors); }
  void save_training_state(StateWriter& out) const override { td3_.save_training_state(out); }
  void load_training_state(const StateReader& in) override {
    td3_.load_training_state(in);
    num_timesteps_ = td3_.num_timesteps();
  }

  TD3& td3() { return td3_; }
  const TD3& td3() const { return td3_; }

 private:
  TD3 td3_;
};

}  // namespace rlrun
