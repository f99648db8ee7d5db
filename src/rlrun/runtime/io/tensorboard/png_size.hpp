#pragma once
// A PNG's size, read from its header: TensorBoard's image events carry it. Apart from the
// drawing code (learning_curve_image.hpp), so that writing events needs no Cairo.
#include <string>
#include <utility>

namespace rlrun {

// Width and height from a PNG's IHDR chunk (0, 0 when `png` is not a PNG).
std::pair<int, int> png_size(const std::string& png);

}  // namespace rlrun
