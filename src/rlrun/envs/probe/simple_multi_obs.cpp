#include "rlrun/envs/probe/simple_multi_obs.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "rlrun/env/discrete_action.hpp"

namespace rlrun {

namespace {
// Flat layout (keys sorted): moves [0, 4), row [4], vec [5, 10).
constexpr size_t kMoves = 0, kRow = 4, kVec = 5;

// SB3 init_possible_transitions: the cells from which each action changes the state.
bool possible(int cell, int action) {
  static const std::vector<int> kFrom[4] = {{1, 2, 3, 13, 14, 15},   // left
                                            {0, 4, 8, 3, 7, 11},     // down
                                            {0, 1, 2, 12, 13, 14},   // right
                                            {4, 8, 12, 7, 11, 15}};  // up
  const auto& from = kFrom[action];
  return std::find(from.begin(), from.end(), cell) != from.end();
}
}  // namespace

int SimpleMultiObs::next_cell(int cell, int action) {
  if (!possible(cell, action)) return cell;
  switch (action) {
    case kLeft: return cell - 1;
    case kDown: return cell + kSide;
    case kRight: return cell + 1;
    default: return cell - kSide;
  }
}

SimpleMultiObs::SimpleMultiObs(const Config& config) : config_(config) {
  observation_space_ = Space::dict({{"vec", Space::box(0.0f, 1.0f, {kVectorSize})},
                                    {"row", Space::discrete(kSide)},
                                    {"moves", Space::multi_binary(kNumActions)}});
  action_space_ = Space::discrete(kNumActions);
  id_ = "SimpleMultiObsEnv-v0";
  key_success_ = info_.add_key("is_success");
  Rng rng(static_cast<uint64_t>(config_.vector_seed));
  for (auto& column : column_vectors_)
    for (float& v : column) v = static_cast<float>(rng.uniform());
}

void SimpleMultiObs::write_observation(std::span<float> obs) const {
  for (int a = 0; a < kNumActions; ++a) obs[kMoves + a] = possible(state_, a) ? 1.0f : 0.0f;
  obs[kRow] = static_cast<float>(state_ / kSide);
  const auto& column = column_vectors_[static_cast<size_t>(state_ % kSide)];
  std::copy(column.begin(), column.end(), obs.begin() + kVec);
}

void SimpleMultiObs::reset(std::optional<uint64_t> seed, std::span<float> obs) {
  seeding_.on_reset(seed);
  state_ = 0;
  if (config_.random_start) {
    // The 11 free cells other than the goal, in order.
    static const int kStarts[] = {0, 1, 2, 3, 4, 7, 8, 11, 12, 13, 14};
    state_ = kStarts[seeding_.rng().below(std::size(kStarts))];
  }
  has_state_ = true;
  info_.clear();
  info_.set(key_success_, 0.0);
  write_observation(obs);
}

StepResult SimpleMultiObs::step(std::span<const float> action, std::span<float> obs) {
  if (!has_state_) throw std::logic_error("SimpleMultiObsEnv-v0: call reset() before step()");
  const int chosen = checked_discrete_action(action_space_, action, "SimpleMultiObsEnv-v0");
  state_ = next_cell(state_, chosen);
  StepResult result;
  result.terminated = state_ == kGoal;
  result.reward = result.terminated ? 1.0 : -0.1;
  info_.clear();
  info_.set(key_success_, result.terminated ? 1.0 : 0.0);
  write_observation(obs);
  return result;
}

void SimpleMultiObs::write_state(StateWriter& out) const {
  seeding_.write_state(out);
  out.put_bool("has_state", has_state_);
  out.put_int("state", state_);
}

void SimpleMultiObs::read_state(const StateReader& in) {
  seeding_.read_state(in);
  has_state_ = in.get_bool("has_state");
  state_ = static_cast<int>(in.get_int_in("state", 0, kSide * kSide - 1));
  if (is_wall(state_)) throw StateMismatch("SimpleMultiObsEnv-v0: the saved cell is a wall");
}

}  // namespace rlrun
