#include "rlrun/envs/board_games/connect_four.hpp"

#include <stdexcept>

namespace rlrun::board_games {

bool ConnectFour::legal(const BoardPosition& position, int action) const {
  return !position.over() && action >= 0 && action < kCols && position.cells[action] == 0;
}

bool ConnectFour::completes_four(const BoardPosition& position, int cell) {
  const int row = cell / kCols, col = cell % kCols;
  const int8_t piece = position.cells[cell];
  if (piece == 0) return false;
  // The pieces of `piece` next to (row, col) in direction (dr, dc), not counting it.
  const auto run = [&](int dr, int dc) {
    int count = 0;
    for (int r = row + dr, c = col + dc; r >= 0 && r < kRows && c >= 0 && c < kCols;
         r += dr, c += dc) {
      if (position.cells[r * kCols + c] != piece) break;
      ++count;
    }
    return count;
  };
  // Horizontal, vertical and both diagonals: check_for_winner's four scans.
  constexpr int kDirections[4][2] = {{0, 1}, {1, 0}, {1, 1}, {1, -1}};
  for (const auto& d : kDirections)
    if (1 + run(d[0], d[1]) + run(-d[0], -d[1]) >= 4) return true;
  return false;
}

int ConnectFour::play(BoardPosition& position, int action) const {
  if (!legal(position, action))
    throw std::logic_error("ConnectFour: column " + std::to_string(action) +
                           " is not a legal move");
  // step(): scan the column from the bottom row up for the first empty cell.
  int cell = -1;
  for (int row = kRows - 1; row >= 0; --row) {
    if (position.cells[row * kCols + action] == 0) {
      cell = row * kCols + action;
      break;
    }
  }
  position.cells[cell] = static_cast<int8_t>(position.to_move + 1);
  ++position.moves_played;
  // check_for_winner() scans the whole board for the mover's piece; only lines through the new
  // piece can be new (the game ended at the first four), so checking those is the same.
  if (completes_four(position, cell))
    position.outcome = win_for(position.to_move);
  else if (position.moves_played == kRows * kCols)
    position.outcome = Outcome::kDraw;
  position.to_move = 1 - position.to_move;
  return cell;
}

}  // namespace rlrun::board_games
