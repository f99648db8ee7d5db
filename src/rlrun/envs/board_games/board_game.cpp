#include "rlrun/envs/board_games/board_game.hpp"

#include <algorithm>

namespace rlrun::board_games {

BoardPosition BoardGame::start() const { return BoardPosition{}; }

void BoardGame::write_mask(const BoardPosition& position, std::span<float> mask) const {
  for (int a = 0; a < num_actions(); ++a) mask[a] = legal(position, a) ? 1.0f : 0.0f;
}

std::vector<int> BoardGame::legal_actions(const BoardPosition& position) const {
  std::vector<int> actions;
  for (int a = 0; a < num_actions(); ++a)
    if (legal(position, a)) actions.push_back(a);
  return actions;
}

void BoardGame::write_planes(const BoardPosition& position, int perspective,
                             std::span<float> obs) const {
  const int8_t own = static_cast<int8_t>(perspective + 1);
  const int8_t other = static_cast<int8_t>(2 - perspective);
  for (int cell = 0; cell < num_cells(); ++cell) {
    obs[2 * cell] = position.cells[cell] == own ? 1.0f : 0.0f;
    obs[2 * cell + 1] = position.cells[cell] == other ? 1.0f : 0.0f;
  }
}

bool BoardGame::plausible(const BoardPosition& position) const {
  const int8_t* begin = position.cells.data();
  const int8_t* end = begin + num_cells();
  if (std::any_of(end, position.cells.end(), [](int8_t cell) { return cell != 0; })) return false;
  const auto first = std::count(begin, end, int8_t{1});
  const auto second = std::count(begin, end, int8_t{2});
  if (first + second + std::count(begin, end, int8_t{0}) != num_cells()) return false;
  if (first + second != position.moves_played) return false;
  // The first player has moved once more than the second exactly when the second is to move.
  return first - second == position.to_move && (position.to_move == 0 || position.to_move == 1);
}

}  // namespace rlrun::board_games
