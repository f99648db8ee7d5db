// PettingZoo classic's tic-tac-toe and connect four, played against an opponent inside the env.
#include "rlrun/env/env_entry.hpp"
#include "rlrun/envs/board_games/board_game_envs.hpp"
#include "rlrun/envs/board_games/minimax_policy.hpp"

namespace rlrun::envs {

void register_board_games(EnvEntries& out) {
  using namespace board_games;
  const size_t first = out.size();
  // No TimeLimit: every game ends by itself (9 and 42 moves at most).
  out.push_back(make_env_entry<TicTacToeEnv>(
      "TicTacToe-v0",
      "PettingZoo's tic-tac-toe against an opponent (random or minimax); Box(3,3,2) planes, "
      "Discrete(9) squares, action mask",
      0));
  out.push_back(make_env_entry<ConnectFourEnv>(
      "ConnectFour-v0",
      "PettingZoo's connect four against an opponent (random or minimax); Box(6,7,2) planes, "
      "Discrete(7) columns, action mask",
      0));
  for (size_t i = first; i < out.size(); ++i) {
    out[i].metrics = {"win", "draw", "loss"};
    out[i].policies.push_back(
        {"minimax",
         "alpha-beta minimax with the env's minimax_depth and minimax_ties, for the learner's side",
         make_minimax_policy});
  }
  // Steps of copies may run on several threads at once: each copy is its own board and RNG.
  mark_independent_copies(out, first);
}

}  // namespace rlrun::envs
