#include "rlrun/runtime/run/self_play_callback.hpp"

#include <set>
#include <string>

#include "rlrun/core/errors.hpp"
#include "rlrun/env/graph_policy.hpp"

namespace rlrun {

namespace {

// The training envs' copies that sample opponents from a pool (opponent: self_play).
std::vector<PlaysAgainstPool*> pool_players(VecEnv& env) {
  std::vector<PlaysAgainstPool*> players;
  for (int c = 0; c < env.num_copies(); ++c) {
    auto* player = dynamic_cast<PlaysAgainstPool*>(&env.env(c).unwrapped());
    if (player && player->wants_policy_pool()) players.push_back(player);
  }
  return players;
}

}  // namespace

SelfPlayCallback::SelfPlayCallback(TrainingContext& context, const SelfPlayConfig& config)
    : context_(context),
      config_(config),
      pool_(std::make_shared<PolicyPool>(config.pool_size, config.latest_probability)),
      players_(pool_players(context.env)) {
  const std::string id = context.env_spec.id;
  if (players_.empty())
    throw UsageError("self_play: " + id +
                     " plays no opponent from a policy pool (TicTacToe-v0 and ConnectFour-v0 do "
                     "with env.kwargs.opponent: self_play)");
  // The snapshots play on the env's own observations: the policy must read those unchanged.
  if (context.env_spec.section.normalize.enabled || !context.env_spec.wrappers.empty())
    throw UsageError("self_play: the snapshots play on " + id +
                     "'s own observations, so the training envs take no wrappers and no "
                     "normalize");
  try {
    freeze(context.algorithm);  // the policy must be one categorical: say so before training
  } catch (const ExportError& e) {
    throw UsageError("self_play: " + std::string(e.what()));
  }
  for (PlaysAgainstPool* player : players_) player->set_policy_pool(pool_);
  // A resumed run's snapshots come from its checkpoint (read_state); a new run starts with the
  // untrained policy.
  if (!context.resuming) take_snapshot(0);
}

std::shared_ptr<const FrozenPolicy> SelfPlayCallback::freeze(const Algorithm& algorithm) const {
  PolicyGraph graph;
  graph.add_input("obs", context_.env.observation_space().flat_dim());
  algorithm.export_policy(graph, "obs", /*with_value=*/false);
  return std::make_shared<GraphPolicy>(std::move(graph));
}

void SelfPlayCallback::take_snapshot(int64_t num_timesteps) {
  Snapshot snapshot;
  snapshot.timesteps = num_timesteps;
  context_.algorithm.save(snapshot.model);
  snapshot.policy = freeze(context_.algorithm);
  const int64_t id = next_id_++;
  pool_->add({id, num_timesteps, snapshot.policy});
  kept_[id] = std::move(snapshot);
  next_snapshot_ = num_timesteps + config_.freq;
  forget_unused();
}

void SelfPlayCallback::forget_unused() {
  std::set<int64_t> used;
  for (const PolicySnapshot& s : pool_->snapshots()) used.insert(s.id);
  for (const PlaysAgainstPool* player : players_) used.insert(player->pool_snapshot_in_use());
  for (auto it = kept_.begin(); it != kept_.end();)
    it = used.count(it->first) ? std::next(it) : kept_.erase(it);
}

bool SelfPlayCallback::on_step(int64_t num_timesteps) {
  if (num_timesteps >= next_snapshot_) take_snapshot(num_timesteps);
  return true;
}

void SelfPlayCallback::write_state(StateWriter& out) const {
  out.put_int("next_id", next_id_);
  out.put_int("next_snapshot", next_snapshot_);
  std::vector<int64_t> ids, in_pool;
  for (const PolicySnapshot& s : pool_->snapshots()) in_pool.push_back(s.id);
  for (const PlaysAgainstPool* player : players_) {
    const int64_t used = player->pool_snapshot_in_use();
    if (used >= 0 && kept_.count(used)) ids.push_back(used);
  }
  ids.insert(ids.end(), in_pool.begin(), in_pool.end());
  std::set<int64_t> written;
  for (int64_t id : ids) {
    if (!written.insert(id).second) continue;
    const Snapshot& snapshot = kept_.at(id);
    StateWriter sub = out.sub("snapshot_" + std::to_string(id));
    sub.put_int("timesteps", snapshot.timesteps);
    for (const auto& [name, tensor] : snapshot.model)
      sub.tensors()[sub.prefix() + "model/" + name] = tensor;
  }
  out.put_vector("pool", in_pool);
  out.put_vector("saved", std::vector<int64_t>(written.begin(), written.end()));
}

void SelfPlayCallback::read_state(const StateReader& in) {
  next_id_ = in.get_int_in("next_id", 0, INT64_MAX);
  next_snapshot_ = in.get_int_in("next_snapshot", 0, INT64_MAX);
  const std::vector<int64_t> saved = in.get_span<int64_t>("saved");
  const std::vector<int64_t> in_pool = in.get_span<int64_t>("pool");
  if (!context_.make_algorithm)
    throw StateMismatch("self_play: this run cannot rebuild its snapshots");
  std::unique_ptr<Algorithm> scratch = context_.make_algorithm();
  pool_ = std::make_shared<PolicyPool>(config_.pool_size, config_.latest_probability);
  kept_.clear();
  for (int64_t id : saved) {
    if (id < 0 || id >= next_id_) throw StateMismatch("self_play: a snapshot id out of range");
    const StateReader sub = in.sub("snapshot_" + std::to_string(id));
    Snapshot snapshot;
    snapshot.timesteps = sub.get_int_in("timesteps", 0, INT64_MAX);
    const std::string prefix = sub.prefix() + "model/";
    for (auto it = in.tensors().lower_bound(prefix);
         it != in.tensors().end() && it->first.compare(0, prefix.size(), prefix) == 0; ++it)
      snapshot.model[it->first.substr(prefix.size())] = it->second;
    scratch->load(snapshot.model);  // checks every tensor as a model file's
    snapshot.policy = freeze(*scratch);
    kept_[id] = std::move(snapshot);
  }
  for (int64_t id : in_pool) {
    const auto it = kept_.find(id);
    if (it == kept_.end()) throw StateMismatch("self_play: a pool snapshot was not saved");
    pool_->add({id, it->second.timesteps, it->second.policy});
  }
  for (const auto& [id, snapshot] : kept_)
    if (!pool_->find(id)) pool_->add_retired({id, snapshot.timesteps, snapshot.policy});
  for (PlaysAgainstPool* player : players_) player->set_policy_pool(pool_);
}

}  // namespace rlrun
