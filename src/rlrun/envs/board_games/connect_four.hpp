#pragma once
// Connect Four with PettingZoo's rules and layout (pettingzoo/classic/connect_four/
// connect_four.py, connect_four-v3): 6 rows x 7 columns stored row-major with row 0 at the top;
// action c drops a piece into column c, where it falls to the lowest empty row; a column whose
// top cell is taken is illegal (_legal_moves). Four of the mover's pieces in a row, column or
// diagonal win (check_for_winner); a full board without one is a draw. The observation is the
// board reshaped to (6, 7, 2).
#include "rlrun/envs/board_games/board_game.hpp"

namespace rlrun::board_games {

class ConnectFour : public BoardGame {
 public:
  static constexpr int kRows = 6;
  static constexpr int kCols = 7;

  std::string name() const override { return "ConnectFour-v0"; }
  int num_cells() const override { return kRows * kCols; }
  int num_actions() const override { return kCols; }
  std::vector<int> observation_shape() const override { return {kRows, kCols, 2}; }
  int draw_rows() const override { return kRows; }
  int draw_cols() const override { return kCols; }
  CellPlace place_of(int cell) const override { return {cell / kCols, cell % kCols}; }

  bool draws_marks() const override { return false; }

  bool legal(const BoardPosition& position, int action) const override;
  int play(BoardPosition& position, int action) const override;
  // Whether the piece at `cell` lies on four in a row of its owner (lines through it only).
  static bool completes_four(const BoardPosition& position, int cell);
};

}  // namespace rlrun::board_games
