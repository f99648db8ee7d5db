#include "rlrun/wrappers/vec_normalize.hpp"

#include <stdexcept>
#include <vector>

#include "rlrun/wrappers/normalize_observation.hpp"
#include "rlrun/wrappers/normalize_reward.hpp"

namespace rlrun {

void decode(const ConfigNode& n, NormalizeSetting& out) {
  if (n.is_scalar()) {
    out = NormalizeSetting{};
    out.enabled = n.as_bool();
    return;
  }
  if (!n.is_map())
    n.fail(
        "expected true, false or a map {norm_obs, norm_reward, clip_obs, clip_reward, gamma, "
        "epsilon}");
  out = read_config<NormalizeSetting>(n);
  out.enabled = true;
}

YAML::Node encode(const NormalizeSetting& v) {
  if (!v.enabled) return YAML::Node(false);
  NormalizeSetting copy = v;
  ConfigWriter writer;
  copy.visit(writer);
  YAML::Node node = writer.node();
  node.SetStyle(YAML::EmitterStyle::Flow);
  return node;
}

EnvPtr add_normalization(EnvPtr env, const NormalizeSetting& setting, double gamma) {
  if (!setting.enabled) return env;
  if (setting.norm_obs) {
    NormalizeObservation::Config config;
    config.clip_obs = setting.clip_obs;
    config.epsilon = setting.epsilon;
    env = std::make_unique<NormalizeObservation>(std::move(env), config);
  }
  if (setting.norm_reward) {
    NormalizeReward::Config config;
    config.gamma = gamma;
    config.clip_reward = setting.clip_reward;
    config.epsilon = setting.epsilon;
    auto reward = std::make_unique<NormalizeReward>(std::move(env), config);
    reward->set_unscaled_when_frozen(true);  // rl-zoo's eval env: norm_reward=False
    env = std::move(reward);
  }
  return env;
}

namespace {

// VecNormalize.reset / step_wait over the copies' env.normalize wrappers. The statistics are
// copy 0's (the trainer shares them across copies, runtime/experiment/env_statistics.hpp); the
// discounted returns are each copy's own.
class BatchNormalization : public VecStepHook {
 public:
  BatchNormalization(std::vector<NormalizeObservation*> obs, std::vector<NormalizeReward*> rewards)
      : obs_(std::move(obs)),
        rewards_(std::move(rewards)),
        returns_(rewards_.size()),
        scratch_(rewards_.size()) {}

  void after_reset(Eigen::MatrixXf& obs) override {
    if (!obs_.empty()) {
      obs_[0]->update_batch(obs);  // if self.training and self.norm_obs: obs_rms.update(obs)
      normalize_columns(obs, nullptr);
    }
    for (NormalizeReward* r : rewards_) r->end_episode();  // self.returns = np.zeros(num_envs)
  }

  void after_step(Eigen::MatrixXf& obs, Eigen::MatrixXf& final_obs, Eigen::VectorXd& rewards,
                  std::span<const uint8_t> done) override {
    if (!obs_.empty()) {
      obs_[0]->update_batch(obs);  // the batch holds the auto-reset observations
      normalize_columns(obs, nullptr);
      normalize_columns(final_obs, &done);  // infos[idx]["terminal_observation"]
    }
    if (rewards_.empty()) return;
    for (size_t i = 0; i < rewards_.size(); ++i)
      returns_[i] = rewards_[i]->add_to_return(rewards[static_cast<Eigen::Index>(i)]);
    rewards_[0]->update_batch(returns_, scratch_);  // _update_reward: ret_rms.update(returns)
    for (size_t i = 0; i < rewards_.size(); ++i) {
      const Eigen::Index col = static_cast<Eigen::Index>(i);
      rewards[col] = rewards_[0]->scale(rewards[col]);
      if (done[i]) rewards_[i]->end_episode();  // self.returns[dones] = 0
    }
  }

  void normalize_obs(Eigen::Ref<Eigen::MatrixXf> obs) const override {
    if (obs_.empty()) return;
    for (Eigen::Index j = 0; j < obs.cols(); ++j)
      obs_[0]->normalize(std::span<float>(obs.col(j).data(), static_cast<size_t>(obs.rows())));
  }

  void normalize_rewards(Eigen::Ref<Eigen::RowVectorXf> rewards) const override {
    if (rewards_.empty()) return;
    for (Eigen::Index j = 0; j < rewards.size(); ++j)
      rewards(j) = static_cast<float>(rewards_[0]->scale(rewards(j)));
  }

 private:
  void normalize_columns(Eigen::MatrixXf& m, const std::span<const uint8_t>* only) const {
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      if (only && !(*only)[static_cast<size_t>(j)]) continue;
      obs_[0]->normalize(std::span<float>(m.col(j).data(), static_cast<size_t>(m.rows())));
    }
  }

  std::vector<NormalizeObservation*> obs_;
  std::vector<NormalizeReward*> rewards_;
  std::vector<double> returns_;
  std::vector<double> scratch_;
};

}  // namespace

void install_batch_normalization(VecEnv& env, const NormalizeSetting& setting) {
  if (!setting.enabled) return;
  std::vector<NormalizeObservation*> obs;
  std::vector<NormalizeReward*> rewards;
  for (int c = 0; c < env.num_copies(); ++c) {
    Env* top = &env.env(c);
    if (setting.norm_reward) {
      auto* r = dynamic_cast<NormalizeReward*>(top);
      if (!r)
        throw std::logic_error("env.normalize: copy's outermost wrapper is not NormalizeReward");
      r->set_batched(true);
      rewards.push_back(r);
      top = &r->inner();
    }
    if (setting.norm_obs) {
      auto* o = dynamic_cast<NormalizeObservation*>(top);
      if (!o)
        throw std::logic_error("env.normalize: no NormalizeObservation at the top of the stack");
      o->set_batched(true);
      obs.push_back(o);
    }
  }
  env.set_step_hook(std::make_unique<BatchNormalization>(std::move(obs), std::move(rewards)));
}

}  // namespace rlrun
