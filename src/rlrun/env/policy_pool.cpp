#include "rlrun/env/policy_pool.hpp"

#include <stdexcept>
#include <string>

namespace rlrun {

PolicyPool::PolicyPool(int capacity, double latest_probability)
    : capacity_(capacity), latest_probability_(latest_probability) {
  if (capacity < 1) throw std::invalid_argument("a policy pool holds at least 1 snapshot");
  if (!(latest_probability >= 0.0 && latest_probability <= 1.0))
    throw std::invalid_argument("the latest snapshot's probability must be in [0, 1]");
}

void PolicyPool::add(PolicySnapshot snapshot) {
  if (!snapshot.policy) throw std::invalid_argument("a policy snapshot needs a policy");
  if (!snapshots_.empty() && snapshot.id <= snapshots_.back().id)
    throw std::invalid_argument("policy snapshot ids must increase, got " +
                                std::to_string(snapshot.id) + " after " +
                                std::to_string(snapshots_.back().id));
  snapshots_.push_back(std::move(snapshot));
  if (static_cast<int>(snapshots_.size()) > capacity_) snapshots_.erase(snapshots_.begin());
}

const PolicySnapshot& PolicyPool::sample(Rng& rng) const {
  if (snapshots_.empty()) throw std::logic_error("sampling from an empty policy pool");
  const bool take_latest = rng.uniform() < latest_probability_;
  const uint64_t older = snapshots_.size() - 1;
  const uint64_t pick = rng.below(older > 0 ? older : 1);
  if (take_latest || older == 0) return snapshots_.back();
  return snapshots_[pick];
}

const PolicySnapshot* PolicyPool::find(int64_t id) const {
  for (const auto* list : {&snapshots_, &retired_})
    for (const PolicySnapshot& snapshot : *list)
      if (snapshot.id == id) return &snapshot;
  return nullptr;
}

void PolicyPool::add_retired(PolicySnapshot snapshot) {
  if (!snapshot.policy) throw std::invalid_argument("a policy snapshot needs a policy");
  retired_.push_back(std::move(snapshot));
}

}  // namespace rlrun
