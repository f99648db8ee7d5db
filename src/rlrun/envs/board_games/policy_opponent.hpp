#pragma once
// A frozen policy (env/policy_pool.hpp: a self-play snapshot of the learner, or a past
// checkpoint) as the opponent. It sees the board as the learner does, from its own side
// (PettingZoo's planes: its pieces in plane 0; "this allows for self-play", tictactoe.py), and
// plays only legal moves: the policy's logits with the illegal ones masked out (sb3-contrib's
// MaskableCategorical), then the best (deterministic) or a sample from their softmax drawn with
// the env's Rng.
#include <cstdint>
#include <memory>

#include "rlrun/env/policy_pool.hpp"
#include "rlrun/envs/board_games/opponent.hpp"

namespace rlrun::board_games {

class PolicyOpponent : public Opponent {
 public:
  // Throws std::invalid_argument when the policy's actions are not the game's.
  PolicyOpponent(const BoardGame& game, std::shared_ptr<const FrozenPolicy> policy,
                 int64_t snapshot_id, bool deterministic);
  std::string name() const override;
  int choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const override;
  int64_t snapshot_id() const { return snapshot_id_; }

 private:
  std::shared_ptr<const FrozenPolicy> policy_;
  int64_t snapshot_id_;
  bool deterministic_;
};

}  // namespace rlrun::board_games
