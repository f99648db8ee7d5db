#pragma once
// The env.kwargs of the board-game envs (TicTacToe-v0, ConnectFour-v0): who the learner plays
// against and which side it takes.
#include <string>

#include "rlrun/core/config_checks.hpp"

namespace rlrun::board_games {

struct BoardGameConfig {
  std::string opponent = "random";         // random | minimax | self_play
  int minimax_depth = 2;                   // plies the minimax opponent searches
  std::string minimax_ties = "random";     // random | first: how minimax picks among equal moves
  std::string learner_side = "alternate";  // first | second | alternate | random
  double opponent_random_moves = 0.0;      // probability of a uniformly random opponent move
  bool self_play_deterministic = false;    // pool opponents play their best move, not a sample

  template <class V>
  void visit(V& v) {
    v("opponent", opponent,
      "who moves for the other side: random (uniform over legal moves), minimax (alpha-beta "
      "to minimax_depth plies) or self_play (a snapshot of the learner from the pool the "
      "`self_play:` section fills, or given by `rlrun eval --opponent model:FILE`; random until "
      "there is one)",
      OneOf{{"random", "minimax", "self_play"}});
    v("minimax_depth", minimax_depth,
      "plies the minimax opponent looks ahead (its own move is 1; tic-tac-toe's 9 is perfect play)",
      in_range(1, 42));
    v("minimax_ties", minimax_ties,
      "among equally good moves minimax picks one at random from the env's RNG (random) or the "
      "lowest action (first)",
      OneOf{{"random", "first"}});
    v("learner_side", learner_side,
      "the side the learner plays: first, second, alternate (first in even episodes, counted "
      "from the last seeded reset) or random (per episode, from the env's RNG)",
      OneOf{{"first", "second", "alternate", "random"}});
    v("opponent_random_moves", opponent_random_moves,
      "probability that an opponent move is uniformly random instead of the opponent's own "
      "(an epsilon-greedy opponent: more varied games to learn from)",
      unit_interval());
    v("self_play_deterministic", self_play_deterministic,
      "a self_play opponent plays its policy's best legal move (true) or samples one from its "
      "masked softmax with the env's RNG (false)");
  }
};

}  // namespace rlrun::board_games
