#include "rlrun/runtime/plugin_env.hpp"

#include <stdexcept>
#include <utility>

namespace rlrun {

Space space_from_api(const api::Space& s, const std::string& what) {
  try {
    switch (s.kind) {
      case api::SpaceKind::kBox:
        return Space::box(s.low, s.high, s.shape);
      case api::SpaceKind::kDiscrete:
        return Space::discrete(s.n, s.start);
      case api::SpaceKind::kMultiDiscrete:
        return Space::multi_discrete(s.nvec);
      case api::SpaceKind::kMultiBinary:
        return Space::multi_binary(static_cast<int>(s.n));
    }
    throw std::invalid_argument("unknown space kind " + std::to_string(static_cast<int>(s.kind)));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(what + " is not a valid space: " + e.what());
  }
}

PluginEnv::PluginEnv(std::unique_ptr<api::Env> env, std::string id)
    : env_(std::move(env)), id_(std::move(id)) {
  if (!env_) throw std::invalid_argument(id_ + ": the plugin returned no env");
  observation_space_ = space_from_api(env_->observation_space(), id_ + "'s observation_space");
  action_space_ = space_from_api(env_->action_space(), id_ + "'s action_space");
  // Keys declared in the constructor are known before the first reset (the evaluator and
  // the Monitor look them up once, at construction).
  copy_info();
}

void PluginEnv::copy_info() {
  const api::Info& from = env_->info();
  // New keys (declared after construction) are added once; steps then only copy values.
  while (index_.size() < from.keys().size())
    index_.push_back(info_.add_key(from.keys()[index_.size()]));
  for (size_t i = 0; i < index_.size(); ++i) info_.set(index_[i], from.values()[i]);
}

void PluginEnv::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  env_->reset(seed, obs);
  copy_info();
}

StepResult PluginEnv::step(std::span<const float> action, std::span<float> obs) {
  const api::StepResult r = env_->step(action, obs);
  copy_info();
  return {r.reward, r.terminated, r.truncated};
}

}  // namespace rlrun
