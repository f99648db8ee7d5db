#pragma once
// Text overlay in a frame's top-left corner: a few lines of small monospace text on a
// translucent box, sized relative to the frame so it reads the same at any resolution.
// Used by `rlrun record` for env id, episode, step and return so far. The box stays within
// the left 40 % of the frame, where centred scenes leave room (the traffic task's north arm
// runs up the middle): a wider line is split at its double-space separators ("episode 1/3
// step 40" becomes two lines), and if that is not enough the text gets smaller.
#include <string>
#include <vector>

#include "rlrun/frame.hpp"

namespace rlrun {

// Draws in pixel coordinates (calls frame.end_scene() first).
void draw_text_overlay(Frame& frame, const std::vector<std::string>& lines);

}  // namespace rlrun
