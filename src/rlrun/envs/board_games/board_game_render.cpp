// The board games' picture (Gymnasium's render_mode="rgb_array"; PettingZoo draws the same
// boards from images).
#include <array>
#include <stdexcept>

#include "rlrun/envs/board_games/board_drawing.hpp"
#include "rlrun/envs/board_games/board_game_env.hpp"

namespace rlrun::board_games {

namespace {

void draw_marks(const BoardGame& game, const BoardPosition& position, Frame& frame) {
  const double rows = game.draw_rows(), cols = game.draw_cols();
  for (int i = 1; i < game.draw_cols(); ++i)
    frame.line({static_cast<double>(i), 0}, {static_cast<double>(i), rows}, {40, 40, 40}, 0.05);
  for (int i = 1; i < game.draw_rows(); ++i)
    frame.line({0, static_cast<double>(i)}, {cols, static_cast<double>(i)}, {40, 40, 40}, 0.05);
  for (int cell = 0; cell < game.num_cells(); ++cell) {
    const CellPlace at = game.place_of(cell);
    const double x = at.col + 0.5, y = at.row + 0.5, r = 0.3;
    if (position.cells[cell] == 1) {
      frame.line({x - r, y - r}, {x + r, y + r}, {200, 40, 40}, 0.1);
      frame.line({x - r, y + r}, {x + r, y - r}, {200, 40, 40}, 0.1);
    } else if (position.cells[cell] == 2) {
      frame.circle({x, y}, r + 0.02, {30, 30, 30});
      frame.circle({x, y}, r - 0.08, {255, 255, 255});
    }
  }
}

void draw_discs(const BoardGame& game, const BoardPosition& position, Frame& frame) {
  const double rows = game.draw_rows(), cols = game.draw_cols();
  const std::array<Point, 4> board{Point{0, 0}, Point{cols, 0}, Point{cols, rows}, Point{0, rows}};
  frame.polygon(board, {40, 80, 190});
  for (int cell = 0; cell < game.num_cells(); ++cell) {
    const CellPlace at = game.place_of(cell);
    const Rgb color = position.cells[cell] == 1   ? Rgb{210, 40, 40}
                      : position.cells[cell] == 2 ? Rgb{240, 210, 40}
                                                  : Rgb{255, 255, 255};
    frame.circle({at.col + 0.5, at.row + 0.5}, 0.38, color);
  }
}

}  // namespace

RenderSpec board_render_spec(const BoardGame& game) {
  return {kCellPixels * game.draw_cols(), kCellPixels * game.draw_rows(), 2.0};
}

void draw_board(const BoardGame& game, const BoardPosition& position, Frame& frame) {
  frame.begin_scene(game.draw_cols(), game.draw_rows(), {255, 255, 255}, /*y_up=*/false);
  if (game.draws_marks())
    draw_marks(game, position, frame);
  else
    draw_discs(game, position, frame);
  frame.end_scene();
}

RenderSpec BoardGameEnv::render_spec() const { return board_render_spec(*game_); }

bool BoardGameEnv::render(Frame& frame) const {
  if (!has_state_) throw std::logic_error(id() + ": call reset() before render()");
  draw_board(*game_, position_, frame);
  return true;
}

}  // namespace rlrun::board_games
