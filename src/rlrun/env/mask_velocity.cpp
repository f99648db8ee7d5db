#include "rlrun/env/mask_velocity.hpp"

#include <stdexcept>
#include <utility>

#include "rlrun/nn/policy_graph.hpp"

namespace rlrun {

MaskVelocity::MaskVelocity(EnvPtr inner, std::string id, const std::vector<int>& velocity_indices)
    : Wrapper(std::move(inner)), id_(std::move(id)) {
  const Space& space = inner_->observation_space();
  if (!space.is_box())
    throw std::invalid_argument(id_ + ": velocity masking needs a Box observation, not " +
                                space.describe());
  // np.ones_like(observation_space.sample()); mask[velocity_indices] = 0.0
  mask_.assign(static_cast<size_t>(space.flat_dim()), 1.0f);
  for (int index : velocity_indices) {
    if (index < 0 || static_cast<size_t>(index) >= mask_.size())
      throw std::invalid_argument(id_ + ": velocity index " + std::to_string(index) +
                                  " outside the observation of " + inner_->id());
    mask_[static_cast<size_t>(index)] = 0.0f;
  }
}

void MaskVelocity::apply(std::span<float> obs) const {
  for (size_t i = 0; i < mask_.size(); ++i) obs[i] *= mask_[i];
}

void MaskVelocity::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  inner_->reset(seed, obs);
  apply(obs);
}

StepResult MaskVelocity::step(std::span<const float> action, std::span<float> obs) {
  const StepResult result = inner_->step(action, obs);
  apply(obs);
  return result;
}

std::string MaskVelocity::export_observation(PolicyGraph& graph, const std::string& obs) const {
  const auto n = static_cast<Eigen::Index>(mask_.size());
  return graph.affine(obs, Eigen::VectorXf::Zero(n),
                      Eigen::Map<const Eigen::VectorXf>(mask_.data(), n), Eigen::VectorXf::Zero(n));
}

std::string MaskVelocity::export_action(PolicyGraph& /*graph*/, const std::string& action) const {
  return action;
}

std::string no_velocity_id(const std::string& base_id) {
  const size_t version = base_id.rfind("-v");
  if (version == std::string::npos) return base_id + "NoVel";
  return base_id.substr(0, version) + "NoVel" + base_id.substr(version);
}

EnvEntry masked_velocity_entry(const EnvEntry& base, std::vector<int> velocity_indices) {
  EnvEntry entry = base;
  entry.id = no_velocity_id(base.id);
  entry.description = base.id + " with its velocities masked to 0 (rl-zoo's MaskVelocityWrapper)";
  entry.policies.clear();
  const std::string id = entry.id;
  entry.make = [make = base.make, id, velocity_indices](const AnyConfig& kwargs) -> EnvPtr {
    return std::make_unique<MaskVelocity>(make(kwargs), id, velocity_indices);
  };
  return entry;
}

}  // namespace rlrun
