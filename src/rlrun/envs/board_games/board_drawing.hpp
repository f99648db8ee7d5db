#pragma once
// A board game's position as a picture: what BoardGameEnv renders for `rlrun record` and what
// the two-seat game of the Python package (rlrun.env("TicTacToe-v0")) returns as rgb_array.
// Tic-tac-toe as a 3x3 grid with the first player's X in red and the second's O in black,
// connect four as a blue frame with red (first) and yellow (second) discs.
#include "rlrun/env.hpp"
#include "rlrun/envs/board_games/board_game.hpp"
#include "rlrun/frame.hpp"

namespace rlrun::board_games {

// Pixels per cell of the drawing.
inline constexpr int kCellPixels = 100;

// The drawing's size and frame rate.
RenderSpec board_render_spec(const BoardGame& game);
// Draws `position` over the whole frame.
void draw_board(const BoardGame& game, const BoardPosition& position, Frame& frame);

}  // namespace rlrun::board_games
