#pragma once
// The registered board-game envs: TicTacToe-v0 and ConnectFour-v0, each BoardGameEnv over its
// rules, with its own default minimax depth (tic-tac-toe's 9 is perfect play; connect four's 2
// is the benchmark opponent).
#include <memory>
#include <string>
#include <vector>

#include "rlrun/envs/board_games/board_game_env.hpp"
#include "rlrun/envs/board_games/connect_four.hpp"
#include "rlrun/envs/board_games/tic_tac_toe.hpp"

namespace rlrun::board_games {

class TicTacToeEnv : public BoardGameEnv {
 public:
  struct Config : BoardGameConfig {
    Config() { minimax_depth = 9; }
  };
  TicTacToeEnv() : TicTacToeEnv(Config{}) {}
  explicit TicTacToeEnv(const Config& config)
      : BoardGameEnv(std::make_unique<TicTacToe>(), config) {}
};

class ConnectFourEnv : public BoardGameEnv {
 public:
  struct Config : BoardGameConfig {};
  ConnectFourEnv() : ConnectFourEnv(Config{}) {}
  explicit ConnectFourEnv(const Config& config)
      : BoardGameEnv(std::make_unique<ConnectFour>(), config) {}
};

// The ids of the games (board_game_rules knows each).
inline std::vector<std::string> board_game_ids() { return {"TicTacToe-v0", "ConnectFour-v0"}; }

// The rules of the game registered as `env_id` (TicTacToe-v0, ConnectFour-v0), or null.
inline std::unique_ptr<const BoardGame> board_game_rules(const std::string& env_id) {
  if (env_id == "TicTacToe-v0") return std::make_unique<TicTacToe>();
  if (env_id == "ConnectFour-v0") return std::make_unique<ConnectFour>();
  return nullptr;
}

}  // namespace rlrun::board_games
