#pragma once
// A fixed-depth minimax player (negamax with alpha-beta pruning). It looks `depth` plies ahead
// (its own move is ply 1: depth 1 takes an immediate win, depth 2 also avoids moves after which
// the other player wins at once); positions at the horizon count as 0, the game having no
// heuristic, so a win found sooner scores higher and a loss later scores higher (score
// kWin - plies for a win, -(kWin - plies) for a loss, 0 for a draw or the horizon). At
// tic-tac-toe's full depth (9) it is a perfect player.
//
// Ties: several moves may share the best score. `Ties::kRandom` picks one of them uniformly
// with the env's Rng (reproducible for a seed, and games against it differ, so win rates over
// many games mean something); `Ties::kFirst` picks the lowest action index (fully
// deterministic play).
#include <vector>

#include "rlrun/envs/board_games/opponent.hpp"

namespace rlrun::board_games {

class MinimaxOpponent : public Opponent {
 public:
  enum class Ties { kRandom, kFirst };
  static constexpr int kWin = 1000;

  MinimaxOpponent(int depth, Ties ties);
  std::string name() const override;
  int choose(const BoardGame& game, const BoardPosition& position, Rng& rng) const override;

  // The exact negamax score of each legal action (for position.to_move), in action order,
  // searched to the depth; -kWin * 2 for illegal actions.
  std::vector<int> action_scores(const BoardGame& game, const BoardPosition& position) const;
  int depth() const { return depth_; }

 private:
  int depth_;
  Ties ties_;
};

// The negamax value of `position` for the player to move, searched `depth` plies, alpha-beta
// window [alpha, beta]; `ply` = plies already played from the root (for win distances).
int negamax(const BoardGame& game, const BoardPosition& position, int depth, int ply, int alpha,
            int beta);

}  // namespace rlrun::board_games
