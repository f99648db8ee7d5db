#pragma once
// Text overlay in a frame's top-left corner: a few lines of small monospace text on a
// translucent box, sized relative to the frame so it reads the same at any resolution.
// Used by `rlrun record` for env id, episode, step and return so far.
#include <string>
#include <vector>

#include "rlrun/frame.hpp"

namespace rlrun {

// Draws in pixel coordinates (calls frame.end_scene() first).
void draw_text_overlay(Frame& frame, const std::vector<std::string>& lines);

}  // namespace rlrun
