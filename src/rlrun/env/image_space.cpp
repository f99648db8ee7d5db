#include "rlrun/env/image_space.hpp"

#include <algorithm>
#include <stdexcept>

namespace rlrun {

bool is_pixel_box(const Space& box) {
  return box.is_uint8_box() &&
         std::all_of(box.low().begin(), box.low().end(), [](float v) { return v == 0.0f; }) &&
         std::all_of(box.high().begin(), box.high().end(), [](float v) { return v == 255.0f; });
}

std::optional<ImageInput> image_input(const Space& space, bool normalize_images) {
  if (!space.is_box() || space.shape().size() != 3) return std::nullopt;
  if (normalize_images && !is_pixel_box(space)) return std::nullopt;
  const std::vector<int>& s = space.shape();
  // np.argmin: the first smallest dimension.
  const auto smallest = std::min_element(s.begin(), s.end()) - s.begin();
  if (smallest == 0) return ImageInput{s[0], s[1], s[2], false};
  return ImageInput{s[2], s[0], s[1], true};
}

ImageInput require_image_input(const Space& space, bool normalize_images) {
  if (const auto image = image_input(space, normalize_images)) return *image;
  // SB3 torch_layers.py NatureCNN's assertion, with rlrun's names.
  std::string why = "images are Boxes of three dimensions";
  if (space.is_box() && space.shape().size() == 3)
    why = space.is_uint8_box() ? "images are bounded by 0 and 255"
                               : "images have dtype uint8 (Box(0, 255, shape, uint8))";
  throw std::invalid_argument(
      "you should use NatureCNN only with images, not with " + space.describe() +
      " (you are probably using features_extractor_class: NatureCNN, SB3's CnnPolicy, instead "
      "of the default FlattenExtractor, SB3's MlpPolicy / MultiInputPolicy): " +
      why +
      "; for images that are normalized already (VecNormalize, or your own scaling) set "
      "normalize_images: false");
}

}  // namespace rlrun
