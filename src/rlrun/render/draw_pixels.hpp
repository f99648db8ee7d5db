#pragma once
// Draws an image observation — height x width pixels of `channels` floats 0-255 each,
// channels-last, row 0 at the top; 1 channel is gray, 3 are RGB — scaled to fill a frame,
// nearest pixel. How the pixel wrappers (AddRenderObservation, GrayscaleObservation) show the
// observation an agent saw, e.g. in `rlrun record`.
#include <span>

#include "rlrun/frame.hpp"

namespace rlrun {

void draw_pixels(std::span<const float> image, int height, int width, int channels, Frame& frame);

}  // namespace rlrun
