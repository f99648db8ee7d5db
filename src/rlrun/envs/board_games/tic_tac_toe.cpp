#include "rlrun/envs/board_games/tic_tac_toe.hpp"

#include <array>
#include <stdexcept>

namespace rlrun::board_games {

namespace {

// board.py's winning_combinations: the three of each column, each row, and both diagonals.
constexpr std::array<std::array<int, 3>, 8> kLines{
    {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {0, 3, 6}, {1, 4, 7}, {2, 5, 8}, {0, 4, 8}, {2, 4, 6}}};

}  // namespace

bool TicTacToe::legal(const BoardPosition& position, int action) const {
  return !position.over() && action >= 0 && action < kSquares && position.cells[action] == 0;
}

int TicTacToe::play(BoardPosition& position, int action) const {
  if (!legal(position, action))
    throw std::logic_error("TicTacToe: square " + std::to_string(action) + " is not a legal move");
  const int8_t piece = static_cast<int8_t>(position.to_move + 1);
  position.cells[action] = piece;
  ++position.moves_played;
  // Only the mover's new mark can complete a line: the game stopped at the first one
  // (game_status() checks every line of both players, with the same result).
  for (const auto& line : kLines) {
    if (position.cells[line[0]] == piece && position.cells[line[1]] == piece &&
        position.cells[line[2]] == piece) {
      position.outcome = win_for(position.to_move);
      break;
    }
  }
  if (!position.over() && position.moves_played == kSquares) position.outcome = Outcome::kDraw;
  position.to_move = 1 - position.to_move;
  return action;
}

}  // namespace rlrun::board_games
