#include "rlrun/envs/board_games/policy_opponent.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rlrun::board_games {

PolicyOpponent::PolicyOpponent(const BoardGame& game, std::shared_ptr<const FrozenPolicy> policy,
                               int64_t snapshot_id, bool deterministic)
    : policy_(std::move(policy)), snapshot_id_(snapshot_id), deterministic_(deterministic) {
  if (!policy_) throw std::invalid_argument("a policy opponent needs a policy");
  if (policy_->num_actions() != game.num_actions())
    throw std::invalid_argument(game.name() + ": the opponent's policy has " +
                                std::to_string(policy_->num_actions()) + " actions, the game " +
                                std::to_string(game.num_actions()));
}

std::string PolicyOpponent::name() const {
  return "policy snapshot " + std::to_string(snapshot_id_);
}

int PolicyOpponent::choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const {
  std::array<float, 2 * kMaxCells> obs{};
  std::array<float, kMaxCells> logits{};
  const size_t n = static_cast<size_t>(game.num_actions());
  game.write_planes(position, position.to_move,
                    std::span<float>(obs.data(), 2 * static_cast<size_t>(game.num_cells())));
  policy_->logits(std::span<const float>(obs.data(), 2 * static_cast<size_t>(game.num_cells())),
                  std::span<float>(logits.data(), n));
  int best = -1;
  for (int a = 0; a < game.num_actions(); ++a)
    if (game.legal(position, a) && (best < 0 || logits[a] > logits[best])) best = a;
  if (best < 0) throw std::logic_error(game.name() + ": the policy opponent has no legal move");
  if (deterministic_) return best;
  // Softmax over the legal actions, shifted by the largest logit; one uniform draw.
  std::array<double, kMaxCells> weights{};
  double total = 0;
  for (int a = 0; a < game.num_actions(); ++a) {
    weights[a] =
        game.legal(position, a) ? std::exp(static_cast<double>(logits[a] - logits[best])) : 0.0;
    total += weights[a];
  }
  double u = rng.uniform() * total;
  for (int a = 0; a < game.num_actions(); ++a) {
    if (weights[a] == 0.0) continue;
    if (u < weights[a]) return a;
    u -= weights[a];
  }
  return best;  // rounding left u at the very top
}

}  // namespace rlrun::board_games
